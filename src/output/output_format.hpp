#pragma once
/// The format of a file condyn writes or reads back, from its name. Every option naming an output
/// file writes what the name's extension says or refuses it before any work (exit 2): run's
/// --out and [output] file (CSV or HDF5), --steps-out (CSV), check's --junit (JUnit XML); `plot`
/// reads what run writes under each name run accepts (docs/cli.md, "Outputs").

#include <initializer_list>
#include <optional>
#include <string>

namespace condyn {

enum class FileFormat { csv, hdf5, xml };

/// The format a name's extension names, in any case: `.csv` CSV, `.h5`, `.hdf5` and `.hdf` HDF5,
/// `.xml` XML. A name without an extension (`-`, /dev/stdout, a FIFO `pipe`, `results`) names
/// none: nullopt, as does an extension condyn does not know (`.txt`, `.hdf4`, a trailing dot).
[[nodiscard]] std::optional<FileFormat> named_format(const std::string& path);
/// True for a name without an extension (the folder's dots do not count; `.csv` alone is a
/// hidden file's name, not an extension).
[[nodiscard]] bool has_no_extension(const std::string& path);

/// The format output `path` (named by `source`, as "--out") is written in: the one its extension
/// names when `accepted` holds it; the first of `accepted` for a name without an extension.
/// Throws OutputError "SOURCE PATH: ..." naming the extensions `source` accepts otherwise.
[[nodiscard]] FileFormat output_format(const std::string& path, const std::string& source,
                                       std::initializer_list<FileFormat> accepted);

/// "CSV (.csv, or a name without an extension) or HDF5 (.h5, .hdf5, .hdf)": the names a list of
/// formats accepts, the first one's including names without an extension.
[[nodiscard]] std::string accepted_names(std::initializer_list<FileFormat> accepted);

}  // namespace condyn
