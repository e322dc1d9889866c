#pragma once
/// Runs the condyn executable (CONDYN_BINARY) in a scratch folder, as users and outside checks
/// do: the exit code, standard output and standard error of one command line.

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace condyn::test {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class Sandbox {
 public:
  Sandbox()
      : dir_(fs::temp_directory_path() /
             ("condyn_cli_" + std::to_string(::getpid()) + "_" + std::to_string(next_id()))) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~Sandbox() { fs::remove_all(dir_); }
  Sandbox(const Sandbox&) = delete;
  Sandbox& operator=(const Sandbox&) = delete;

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  [[nodiscard]] fs::path path(const std::string& name) const { return dir_ / name; }

  Result run(const std::string& args) const {
    const std::string cmd = "cd '" + dir_.string() + "' && '" + std::string(CONDYN_BINARY) + "' " +
                            args + " > out.txt 2> err.txt";
    const int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir_ / "out.txt");
    r.err = slurp(dir_ / "err.txt");
    return r;
  }

 private:
  static int next_id() {
    static int id = 0;  // one folder per sandbox, so two may be alive at once
    return id++;
  }
  fs::path dir_;
};

}  // namespace condyn::test
