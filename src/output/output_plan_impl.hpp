#pragma once
/// OutputPlan's state (internal to src/): a record per output and per input, and the two halves
/// of its work. Before the work, output_checks.cpp resolves and checks every path (what a path
/// may be, which files are the same); after it, output_files.cpp writes into temporary files and
/// commits them (temp_registry.hpp removes them on a fatal signal).

#include <sys/stat.h>
#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

#include "src/output/output_files.hpp"
#include "src/output/temp_registry.hpp"

namespace condyn {

struct OutputPlan::Impl {
  enum class Kind { regular, descriptor, device, folder };

  struct Output {
    std::string path, source;
    Kind kind = Kind::regular;
    bool checked = false;
    int fd = -1;                   ///< descriptor outputs
    std::filesystem::path target;  ///< the file (links followed, canonical) or device written
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
    std::filesystem::path temp;  ///< regular outputs: the temporary file beside target
    TempNode* node = nullptr;
    bool written = false;
    Writer stream_writer;  ///< streams: written at commit
  };

  struct Input {
    std::string path;
    std::filesystem::path canonical;
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
  };

  std::vector<Output> outputs;
  std::vector<Input> inputs;
  unsigned temp_counter = 0;

  [[noreturn]] static void refuse(const Output& o, const std::string& why) {
    throw OutputError(o.source + " " + o.path + ": " + why);
  }

  // Checks before the work (output_checks.cpp).

  /// Follows symbolic links (also dangling ones) to the path that will be written.
  static std::filesystem::path follow_links(const Output& o);
  [[nodiscard]] bool in_planned_folder(const std::filesystem::path& folder) const;
  void check_folder(Output& o);
  void check_output(Output& o);
  void check_not_input(const Output& o) const;
  static bool same_target(const Output& a, const Output& b);

  // Temporary files, writing and commit (output_files.cpp).

  void remove_temp(Output& o);
  /// Creates the temporary file of a regular output; failing is a usage error (OutputError) at
  /// check, a write error (std::runtime_error) after the work.
  void create_temp(Output& o, bool at_check);
  void write_stream(Output& o);
  /// Renames the temporary file over the target, with the permission bits of the file replaced.
  void put_in_place(Output& o);
};

/// The message of an errno value.
std::string errno_text(int error);

}  // namespace condyn
