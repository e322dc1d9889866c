#pragma once
/// The files a command writes, checked before the work and committed together after it.
///
/// Life of an output: add_output() names it; check() resolves and checks every output before any
/// work is done (so a bad path costs no integration); write() fills it; commit() puts every
/// chosen output in place at once. What a path may be:
/// - a regular file (existing or not): written to a temporary file beside its target, renamed
///   over it at commit. The folder must exist and take a new file (check() creates the
///   temporary file there). An existing file keeps its permission bits; a file without any write
///   permission is refused (it is protected); a file with other hard links is replaced (its other
///   names keep the previous content, with a warning).
/// - a symbolic link: followed, also when dangling; the file it names is written, the link stays.
/// - `-`, /dev/stdout, /dev/stderr, /dev/fd/N, /proc/self/fd/N: the open descriptor itself.
/// - a character device or a FIFO (/dev/null, a named pipe): opened and written in place.
/// Refused: folders, block devices, sockets, an input of the command (the scene), two outputs
/// naming the same file (only /dev/null may be named twice), a missing folder.
/// Temporary files are removed on every exit path, SIGTERM, SIGINT, SIGHUP and SIGPIPE included.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace condyn {

/// An output the command cannot write, found before any work: a usage error (exit 2).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputPlan {
 public:
  using Writer = std::function<void(std::ostream&)>;
  using Id = std::size_t;

  OutputPlan();
  ~OutputPlan();  ///< removes every temporary file not committed
  OutputPlan(const OutputPlan&) = delete;
  OutputPlan& operator=(const OutputPlan&) = delete;

  /// A file the command reads: no output may be it (the same file, by any name or link).
  void add_input(const std::string& path);
  /// An output at `path`; `source` names where the path came from in messages ("--out").
  Id add_output(const std::string& path, const std::string& source);
  /// A folder the command fills (compare, stress): created with its parents by create_folders().
  void add_folder(const std::string& path, const std::string& source);

  /// Resolves and checks every output and folder added since the last call: throws OutputError
  /// naming the source and path. Creates the temporary file of each regular output.
  void check();
  /// Creates the folders added with add_folder (after check()); throws std::runtime_error.
  void create_folders();

  /// Writes output `id` (checked): a regular output into its temporary file at once; a stream
  /// (descriptor, device, FIFO) at commit, after every regular output is written, so nothing
  /// reaches a stream before all files are complete. Throws std::runtime_error naming the path.
  void write(Id id, Writer writer);
  /// For a regular output (not is_stream): the path of its temporary file, for a writer that
  /// opens it by name and fills it over the run (rows as they are computed, HDF5); the output
  /// then counts as written. Throws std::logic_error for a stream, std::runtime_error when the
  /// temporary file cannot be created.
  [[nodiscard]] std::string write_in_place(Id id);
  /// Commits the outputs `ids` (each written): streams first, then every rename. Outputs not
  /// listed are dropped (their temporary files removed). Throws std::runtime_error.
  void commit(const std::vector<Id>& ids);
  /// Commits every written output.
  void commit_all();
  /// Removes a file an earlier run of the command left in its folder and this one did not
  /// write (compare's figures, stress's generated scenes), as the outputs are protected: not
  /// an input of the command (by any name or link), not a file without any write permission,
  /// only a regular file. Returns whether it was removed.
  bool remove_stale(const std::filesystem::path& path) const;

  /// True when output `id` goes to standard output: then every other line goes to stderr.
  [[nodiscard]] bool to_stdout(Id id) const;
  [[nodiscard]] bool any_to_stdout() const;
  /// True when output `id` is written in place (descriptor, device, FIFO): no temporary file,
  /// nothing to keep beside it.
  [[nodiscard]] bool is_stream(Id id) const;
  /// The path as given, or "standard output" for `-`.
  [[nodiscard]] std::string display_name(Id id) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace condyn
