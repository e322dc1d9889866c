// The options and summary of an integration (dae/interface/solve_summary.hpp): checks, tolerances
// per kind of unknown, and the summary's one line.
#include "dae/interface/solve_summary.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "models/core/number_cell.hpp"
#include "models/core/solve_spec.hpp"

namespace condyn {

void IntegratorSettings::validate() const {
  auto bad = [](const std::string& what) { throw std::invalid_argument("integrator: " + what); };
  if (!(rtol > 0.0) || !std::isfinite(rtol)) bad("rtol must be > 0");
  if (!(atol > 0.0) || !std::isfinite(atol)) bad("atol must be > 0");
  for (const auto& [value, name] :
       {std::pair{atol_velocity, "atol_velocity"}, std::pair{atol_multiplier, "atol_multiplier"},
        std::pair{atol_mu, "atol_mu"}}) {
    if (value && (!(*value > 0.0) || !std::isfinite(*value)))
      bad(std::string(name) + " must be > 0 and finite");
  }
  if (output_times.empty()) bad("no output times");
  if (!std::is_sorted(output_times.begin(), output_times.end())) bad("output times not ascending");
  if (!std::is_sorted(breakpoints.begin(), breakpoints.end())) bad("breakpoints not ascending");
  if (max_steps_per_output <= 0) bad("max_steps_per_output must be > 0");
  if (max_steps < 0) bad("max_steps must be >= 0");
  if (!(max_wall_seconds >= 0.0) || !std::isfinite(max_wall_seconds))
    bad("max_wall_seconds must be >= 0");
  if (!(progress_after_seconds >= 0.0) || !(progress_every_seconds >= 0.0))
    bad("progress intervals must be >= 0");
  if (!(time_scale > 0.0) || !std::isfinite(time_scale)) bad("time_scale must be > 0");
  if (first_step && (!(*first_step > 0.0) || !std::isfinite(*first_step)))
    bad("first_step must be > 0");
}

double IntegratorSettings::atol_of(UnknownKind kind) const {
  switch (kind) {
    case UnknownKind::displacement:
      break;
    case UnknownKind::velocity:
      return atol_velocity.value_or(atol);
    case UnknownKind::multiplier:
      return atol_multiplier.value_or(atol);
    case UnknownKind::mu:
      return atol_mu.value_or(atol);
  }
  return atol;
}

Eigen::VectorXd IntegratorSettings::atol_vector(const std::vector<UnknownKind>& kinds, int size,
                                                const Eigen::VectorXd& row_scales,
                                                const Eigen::VectorXd& row_masses) const {
  if (kinds.empty()) return Eigen::VectorXd::Constant(size, atol);
  if (static_cast<int>(kinds.size()) != size)
    throw std::logic_error("integrator: unknown kinds do not match the problem size");
  Eigen::VectorXd out(size);
  for (int i = 0; i < size; ++i) out[i] = atol_of(kinds[static_cast<std::size_t>(i)]);
  if (row_masses.size() != 0 && multiplier_atol_per_row && multiplier_mass > 0.0) {
    if (row_masses.size() != size)
      throw std::logic_error("integrator: row masses do not match the problem size");
    // A row whose lightest mass lies more than kRowScaleSpan below the common one: its λ moves
    // that mass, so its atol shrinks by how far beyond the span it lies (never below kMinAtol).
    const double reach = multiplier_mass / kRowScaleSpan;
    for (int i = 0; i < size; ++i) {
      if (kinds[static_cast<std::size_t>(i)] == UnknownKind::multiplier && row_masses[i] > 0.0 &&
          row_masses[i] < reach) {
        out[i] = std::max(out[i] * (row_masses[i] / reach), kMinAtol);
      }
    }
  }
  if (row_scales.size() == 0) return out;
  if (row_scales.size() != size)
    throw std::logic_error("integrator: row scales do not match the problem size");
  // Rows within kRowScaleSpan of the largest keep the common figure; a smaller row gets it times
  // how far it lies beyond that span. (Scaled by the full ratio, the rows of Andrews' mechanism,
  // lengths within a decade, lost 3 to 11 times in accuracy at the same rtol under GGL:
  // docs/schemes.md, "Absolute tolerances".)
  const double reach = row_scales.maxCoeff() / kRowScaleSpan;
  for (int i = 0; i < size; ++i) {
    const UnknownKind kind = kinds[static_cast<std::size_t>(i)];
    const bool per_row = (kind == UnknownKind::multiplier && multiplier_atol_per_row) ||
                         (kind == UnknownKind::mu && mu_atol_per_row);
    // A row without a coefficient at the start keeps the common figure; none grows past 1e300,
    // where its error weight would leave the normal doubles.
    if (per_row && row_scales[i] > 0.0 && row_scales[i] < reach) {
      out[i] = std::min(out[i] * (reach / row_scales[i]), 1e300);
    }
  }
  return out;
}

std::optional<std::string> SolveSummary::error_test_warning() const {
  constexpr long kManySteps = 10'000;
  if (steps < kManySteps || 2 * error_test_failures < steps) return std::nullopt;
  return "warning: " + std::to_string(error_test_failures) + " of " + std::to_string(steps) +
         " steps failed the error test: the result may be off by far more than rtol; compare it "
         "with another scheme (index1 or projection)";
}

std::optional<std::string> SolveSummary::atol_warning(double atol) const {
  if (!(max_abs_displacement > 0.0) || !(atol > max_abs_displacement)) return std::nullopt;
  std::ostringstream s;
  s.precision(3);
  s << "warning: atol " << atol << " exceeds the largest displacement of the run ("
    << max_abs_displacement
    << "): the error test held none of the motion, which may be off by up to atol; set atol to "
       "the size of the smallest displacement that matters";
  return s.str();
}

std::optional<std::string> SolveSummary::drift_warning(double rtol, double atol) const {
  const double allowed = kDriftMultiple * (rtol * max_abs_displacement + atol);
  if (!(max_relative_drift_position > allowed)) return std::nullopt;
  std::ostringstream s;
  s.precision(3);
  s << "warning: the constraints drifted by " << max_relative_drift_position
    << " (the largest |phi_i| / max_j |A_ij| over the run, a length"
    << (worst_drift_place().empty() ? "" : ", at " + worst_drift_place()) << "), beyond "
    << static_cast<int>(kDriftMultiple) << " (rtol max|u| + atol) = " << allowed
    << ": the result does not hold its constraints to the tolerance asked; ";
  if (scheme == "penalty") {
    s << "penalty approximates them (error about |f_con| / w): raise [solve] penalty weight, or "
         "use ggl or projection";
  } else if (scheme == "index1" || scheme == "index2" || scheme == "baumgarte") {
    s << scheme << " lets the drift grow: use ggl or projection, which hold it, or a tighter rtol";
  } else {
    s << "tighten rtol, or compare with projection, which holds the drift at every step";
  }
  return s.str();
}

std::string SolveSummary::worst_drift_place() const {
  if (!worst_drift_joint.empty()) return "joint " + worst_drift_joint;
  if (!worst_drift_body.empty()) return "the rigid-body rows of body " + worst_drift_body;
  return "";
}

std::string SolveSummary::brief(const std::vector<RunNote>& said_before) const {
  std::ostringstream s;
  s.precision(3);
  s << scheme << ": " << termination << ", " << steps << " steps, " << residual_evals
    << " residual and " << jacobian_evals << " Jacobian evaluations, " << newton_failures
    << " Newton and " << error_test_failures << " error-test failures, " << unknowns
    << " unknowns, wall ";
  // Three significant digits below 100 ms; whole milliseconds above, never an exponent (a run of
  // minutes printed as 1.7e+05 ms would hide its last three digits).
  const double wall_ms = wall_seconds * 1e3;
  if (wall_ms >= 100.0) {
    s << std::llround(wall_ms);
  } else {
    s << wall_ms;
  }
  s << " ms, max drift position " << max_drift_position << " velocity " << max_drift_velocity;
  if (!worst_drift_joint.empty()) {
    s << " (worst joint " << worst_drift_joint << ")";
  } else if (!worst_drift_body.empty()) {
    s << " (worst: " << worst_drift_place() << ")";
  }
  if (max_abs_mu >= 0.0) s << ", max |mu| " << max_abs_mu;
  if (const std::string text = notes_text(said_before); !text.empty()) s << "; " << text;
  return s.str();
}

std::string SolveSummary::notes_text(const std::vector<RunNote>& said_before) const {
  std::string text;
  for (const RunNote& note : notes) {
    if (std::find(said_before.begin(), said_before.end(), note) == said_before.end())
      text += (text.empty() ? "" : "; ") + note.text;
  }
  return text;
}

void SolveSummary::add_note(RunNote::Kind kind, std::string text) {
  notes.push_back({kind, std::move(text)});
}

void SolveSummary::set_reached(double t) {
  std::string fixed = std::to_string(t);
  termination = "reached t = " + (std::stod(fixed) == t ? fixed : shortest_number(t));
}

}  // namespace condyn
