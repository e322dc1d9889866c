#include "src/output/output_format.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "src/output/output_files.hpp"

namespace condyn {

namespace {

/// The extension, lowercased, with its dot ("" for none, "." for a trailing dot).
std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// "CSV (.csv)", "HDF5 (.h5, .hdf5, .hdf)", "JUnit XML (.xml)".
std::string format_names(FileFormat format) {
  switch (format) {
    case FileFormat::csv:
      return "CSV (.csv";
    case FileFormat::hdf5:
      return "HDF5 (.h5, .hdf5, .hdf";
    case FileFormat::xml:
      return "JUnit XML (.xml";
  }
  return "";
}

}  // namespace

std::optional<FileFormat> named_format(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".csv") return FileFormat::csv;
  if (ext == ".h5" || ext == ".hdf5" || ext == ".hdf") return FileFormat::hdf5;
  if (ext == ".xml") return FileFormat::xml;
  return std::nullopt;
}

bool has_no_extension(const std::string& path) { return extension_of(path).empty(); }

std::string accepted_names(std::initializer_list<FileFormat> accepted) {
  std::string out;
  bool first = true;
  for (const FileFormat f : accepted) {
    out += (first ? "" : " or ") + format_names(f) +
           (first ? ", or a name without an extension)" : ")");
    first = false;
  }
  return out;
}

FileFormat output_format(const std::string& path, const std::string& source,
                         std::initializer_list<FileFormat> accepted) {
  if (has_no_extension(path)) return *accepted.begin();
  const std::optional<FileFormat> named = named_format(path);
  if (named && std::find(accepted.begin(), accepted.end(), *named) != accepted.end()) {
    return *named;
  }
  const std::string ext = std::filesystem::path(path).extension().string();
  throw OutputError(
      source + " " + path + ": " +
      (named ? "the extension " + ext + " asks for a format " + source + " does not write"
             : "the extension " + ext + " names no format condyn writes") +
      ": " + source + " writes " + accepted_names(accepted));
}

}  // namespace condyn
