#pragma once
/// Temporary files removed on a fatal signal (SIGTERM, SIGINT, SIGHUP, SIGPIPE): how an output's
/// temporary file (src/output_files.hpp) is cleaned up when the program is killed before it
/// commits. Internal to src/.

#include <string>

namespace condyn {

/// A registered temporary file. Nodes live as long as the program and are reused.
struct TempNode;

/// Registers `path` for removal on a signal, before the file is created; installs the signal
/// handlers on first use. Throws OutputError when the path is longer than PATH_MAX.
[[nodiscard]] TempNode* register_temp(const std::string& path);
/// The file is gone or in place: a signal no longer removes it. Sets `node` to nullptr.
void release_temp(TempNode*& node);

}  // namespace condyn
