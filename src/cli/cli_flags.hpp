#pragma once
/// Command-line values read strictly: a number flag takes a whole decimal number, a list flag a
/// comma-separated list whose every item is checked, and every message names the flag.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "models/core/solve_spec.hpp"

namespace condyn {

/// The whole of `text` as a finite decimal number (`2`, `0.5`, `1e-6`, `-3.`), else nullopt:
/// `abc`, `0x10`, `1e-3x`, `nan`, `inf`, `1e999` (beyond a double) are not numbers here.
[[nodiscard]] std::optional<double> parse_decimal(const std::string& text);

/// `text` as a relative tolerance given by `flag`; throws CLI::ValidationError naming the flag.
[[nodiscard]] double parse_rtol_flag(const std::string& flag, const std::string& text);

/// CLI11 checks for number options, with short messages: a relative tolerance in
/// [kMinRtol, 1), a number > 0, a whole number in [lo, hi].
[[nodiscard]] CLI::Validator rtol_check();
[[nodiscard]] CLI::Validator positive_check();
/// An absolute tolerance: a number >= kMinAtol.
[[nodiscard]] CLI::Validator atol_check();
[[nodiscard]] CLI::Validator whole_check(int lo, int hi);
/// A tolerance for a side run (compare --drift-rtol): like rtol_check, bounded by [lo, hi].
[[nodiscard]] CLI::Validator decimal_range_check(double lo, double hi);

/// A file name for an output: not empty.
[[nodiscard]] CLI::Validator file_name_check();
/// Refuses an empty value: a flag given as '' is a mistake, not a request for the default.
[[nodiscard]] CLI::Validator non_empty_check();
/// True for a value of blanks only (spaces, tabs, line ends) or none: an empty value.
[[nodiscard]] bool is_blank(const std::string& text);

/// A scheme named by `flag`; throws CLI::ValidationError naming the flag and the schemes.
[[nodiscard]] Scheme parse_scheme_flag(const std::string& flag, const std::string& s);
/// Schemes listed by `flag` ("ggl,index3", split_list's rules), each a scheme by name ('auto'
/// refused: a study names what it runs); throws CLI::ValidationError naming the flag.
[[nodiscard]] std::vector<Scheme> parse_scheme_list(const std::string& flag, const std::string& s);
/// --constraints: "mixed" or "multipliers"; throws CLI::ValidationError otherwise.
/// --constraints: refused under a scheme without multipliers (elimination, penalty, projection).
[[nodiscard]] SolveSpec::Treatment parse_treatment_flag(const std::string& s, Scheme scheme);
/// The scene's settings with the flags' overrides, checked together (SolveSpec::validate): a
/// --step beyond t_end, a Newmark-family parameter out of range are bad input, thrown as a
/// SceneError naming `scene` (exit 2), as the same values in the file are.
void check_settings(const std::string& scene, const SolveSpec& settings);
/// --step on `cmd` (run, info, check, compare): the Newmark family's fixed step, overriding
/// [solve] step, a positive decimal.
void add_step_option(CLI::App* cmd, std::optional<double>& step);

/// Splits "a,b,c" (spaces ignored); an empty item (a stray comma) or one listed twice is refused
/// with CLI::ValidationError naming `flag`.
[[nodiscard]] std::vector<std::string> split_list(const std::string& flag, const std::string& s);

}  // namespace condyn
