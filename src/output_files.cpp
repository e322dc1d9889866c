#include "src/output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <streambuf>
#include <string_view>

namespace condyn {

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------------
// Temporary files removed on a fatal signal. The handler may run at any point of the program, so
// it reads only a list that is never freed and lock-free atomic flags, and calls only unlink,
// signal and raise (async-signal-safe). Nodes are reused, never deleted.

struct TempNode {
  char path[PATH_MAX] = {};
  std::atomic<bool> live{false};  ///< the handler removes `path`
  bool in_use = false;            ///< owned by an output (main program only)
  TempNode* next = nullptr;
};

std::atomic<TempNode*> g_temps{nullptr};

extern "C" void remove_temps_and_reraise(int sig) {
  for (TempNode* n = g_temps.load(); n != nullptr; n = n->next) {
    if (n->live.load()) ::unlink(n->path);
  }
  // The default action (termination) happens when the handler returns: the signal is blocked
  // while it runs, so the raise stays pending until then.
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void install_signal_handlers() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  for (int sig : {SIGTERM, SIGINT, SIGHUP, SIGPIPE}) {
    struct sigaction old {};
    // A signal the caller ignores (nohup, a shell's SIGPIPE policy) stays ignored.
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = remove_temps_and_reraise;
    sigfillset(&action.sa_mask);  // one cleanup at a time
    ::sigaction(sig, &action, nullptr);
  }
}

/// Registers `path` for removal on a signal before the file is created, so no temporary file
/// ever exists unregistered.
TempNode* register_temp(const std::string& path) {
  static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler reads these flags");
  if (path.size() >= PATH_MAX) throw OutputError(path + ": the path is too long");
  install_signal_handlers();
  TempNode* node = nullptr;
  for (TempNode* n = g_temps.load(); n != nullptr && node == nullptr; n = n->next) {
    if (!n->in_use) node = n;
  }
  if (node == nullptr) {
    node = new TempNode;  // NOLINT(cppcoreguidelines-owning-memory): lives as long as the program
    node->next = g_temps.load();
    g_temps.store(node);
  }
  node->in_use = true;
  std::memcpy(node->path, path.c_str(), path.size() + 1);
  node->live.store(true);
  return node;
}

void release_temp(TempNode*& node) {
  if (node == nullptr) return;
  node->live.store(false);
  node->in_use = false;
  node = nullptr;
}

// ---------------------------------------------------------------------------------------------

/// A stream buffer over a file descriptor: what the CSV writers write into, whether the target
/// is a temporary file, a device, a FIFO or standard output.
class FdBuf : public std::streambuf {
 public:
  FdBuf(int fd, bool owned) : fd_(fd), owned_(owned), buffer_(std::size_t{1} << 16) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  ~FdBuf() override {
    if (owned_ && fd_ >= 0) ::close(fd_);
  }
  FdBuf(const FdBuf&) = delete;
  FdBuf& operator=(const FdBuf&) = delete;

  /// Flushes and, when owned, closes: 0 on success, else the errno of the first failure.
  int finish() {
    if (!drain() && error_ == 0) error_ = EIO;
    if (owned_ && fd_ >= 0) {
      if (::close(fd_) != 0 && error_ == 0) error_ = errno;
      fd_ = -1;
    }
    return error_;
  }

 protected:
  int_type overflow(int_type ch) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  bool drain() {
    if (error_ != 0) return false;
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      p += n;
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }

  int fd_;
  bool owned_;
  int error_ = 0;
  std::vector<char> buffer_;
};

/// Runs `writer` into `fd`; returns 0 or the errno of the failure.
int write_into(int fd, bool owned, const OutputPlan::Writer& writer) {
  FdBuf buf(fd, owned);
  std::ostream out(&buf);
  writer(out);
  out.flush();
  const int error = buf.finish();
  return error != 0 ? error : (out ? 0 : EIO);
}

/// `-`, /dev/stdout, /dev/stderr, /dev/fd/N and /proc/self/fd/N name an open descriptor, which is
/// written where it stands (no truncation, no renaming: a file the shell opened stays its file).
std::optional<int> descriptor_of(const std::string& path) {
  if (path == "-" || path == "/dev/stdout") return 1;
  if (path == "/dev/stderr") return 2;
  for (const std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (path.rfind(prefix, 0) != 0) continue;
    const std::string digits = path.substr(prefix.size());
    if (digits.empty() || digits.size() > 6 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      return std::nullopt;
    }
    return std::stoi(digits);
  }
  return std::nullopt;
}

std::string errno_text(int error) { return std::strerror(error); }

bool is_within(const fs::path& p, const fs::path& folder) {
  auto [f, q] = std::mismatch(folder.begin(), folder.end(), p.begin(), p.end());
  return f == folder.end();
}

fs::path canonical_or_plain(const fs::path& p) {
  std::error_code ec;
  fs::path abs = fs::absolute(p, ec);
  if (ec) return p.lexically_normal();
  fs::path canon = fs::weakly_canonical(abs, ec);
  return ec ? abs.lexically_normal() : canon;
}

}  // namespace

struct OutputPlan::Impl {
  enum class Kind { regular, descriptor, device, folder };

  struct Output {
    std::string path, source;
    Kind kind = Kind::regular;
    bool checked = false;
    int fd = -1;      ///< descriptor outputs
    fs::path target;  ///< the file (links followed, canonical) or device written
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
    fs::path temp;  ///< regular outputs: the temporary file beside target
    TempNode* node = nullptr;
    bool written = false;
    Writer stream_writer;  ///< streams: written at commit
  };

  struct Input {
    std::string path;
    fs::path canonical;
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

  void remove_temp(Output& o) {
    if (o.node == nullptr) return;
    ::unlink(o.temp.c_str());
    release_temp(o.node);
    o.temp.clear();
  }

  /// Creates the temporary file of a regular output; failing is a usage error (OutputError) at
  /// check, a write error (std::runtime_error) after the work.
  void create_temp(Output& o, bool at_check) {
    const fs::path folder = o.target.parent_path();
    // The name's first 200 bytes: the temporary name stays within NAME_MAX (255).
    const std::string stem = o.target.filename().string().substr(0, 200);
    for (int attempt = 0; attempt < 100; ++attempt) {
      o.temp = folder / ("." + stem + ".condyn-tmp-" + std::to_string(::getpid()) + "-" +
                         std::to_string(temp_counter++));
      o.node = register_temp(o.temp.string());
      const int fd = ::open(o.temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd >= 0) {
        ::close(fd);
        return;
      }
      const int error = errno;
      release_temp(o.node);
      o.temp.clear();
      if (error == EEXIST) continue;
      const std::string why =
          "cannot create a file in the folder " + folder.string() + " (" + errno_text(error) + ")";
      if (at_check) refuse(o, why);
      throw std::runtime_error(o.path + ": " + why);
    }
    refuse(o, "cannot find a free temporary name in " + folder.string());
  }

  /// Follows symbolic links (also dangling ones) to the path that will be written.
  static fs::path follow_links(const Output& o) {
    fs::path p = o.path;
    for (int hops = 0; hops < 40; ++hops) {
      struct stat st {};
      if (::lstat(p.c_str(), &st) != 0) return p;  // missing: the folder check says why
      if (!S_ISLNK(st.st_mode)) return p;
      std::error_code ec;
      const fs::path link = fs::read_symlink(p, ec);
      if (ec) refuse(o, "cannot read the symbolic link " + p.string() + " (" + ec.message() + ")");
      p = link.is_absolute() ? link : p.parent_path() / link;
    }
    refuse(o, "too many levels of symbolic links");
  }

  [[nodiscard]] bool in_planned_folder(const fs::path& folder) const {
    return std::any_of(outputs.begin(), outputs.end(), [&](const Output& f) {
      return f.kind == Kind::folder && f.checked && is_within(folder, f.target);
    });
  }

  void check_folder(Output& o) {
    if (o.path.empty()) refuse(o, "an empty folder name");
    o.target = canonical_or_plain(o.path);
    struct stat st {};
    if (::stat(o.target.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode)) refuse(o, "exists and is not a folder");
      // The folder takes files: a probe file created and removed.
      Output probe;
      probe.path = o.path;
      probe.source = o.source;
      probe.target = o.target / ".probe";
      create_temp(probe, true);
      remove_temp(probe);
      return;
    }
    // Missing: the nearest existing ancestor must be a folder where a folder can be created.
    fs::path child = o.target;
    fs::path parent = child.parent_path();
    while (::stat(parent.c_str(), &st) != 0 && parent != parent.parent_path()) {
      child = parent;
      parent = parent.parent_path();
    }
    if (!S_ISDIR(st.st_mode)) refuse(o, parent.string() + " is not a folder");
    if (::mkdir(child.c_str(), 0777) != 0) {
      refuse(o, "cannot create the folder " + child.string() + " (" + errno_text(errno) + ")");
    }
    ::rmdir(child.c_str());
  }

  void check_output(Output& o) {
    if (o.path.empty()) refuse(o, "an empty file name");
    if (const auto fd = descriptor_of(o.path)) {
      o.kind = Kind::descriptor;
      o.fd = *fd;
      const int flags = ::fcntl(o.fd, F_GETFL);
      if (flags < 0) refuse(o, "descriptor " + std::to_string(o.fd) + " is not open");
      if ((flags & O_ACCMODE) == O_RDONLY) {
        refuse(o, "descriptor " + std::to_string(o.fd) + " is open for reading only");
      }
      struct stat st {};
      if (::fstat(o.fd, &st) == 0 && S_ISREG(st.st_mode)) {  // `> file`: that file is taken
        o.exists = true;
        o.dev = st.st_dev;
        o.ino = st.st_ino;
      }
      return;
    }
    if (o.path.back() == '/') refuse(o, "names a folder (name a file)");
    o.target = canonical_or_plain(follow_links(o));
    struct stat st {};
    if (::stat(o.target.c_str(), &st) == 0) {
      o.exists = true;
      o.dev = st.st_dev;
      o.ino = st.st_ino;
      if (S_ISDIR(st.st_mode)) refuse(o, "is a folder (name a file)");
      if (S_ISBLK(st.st_mode) || S_ISSOCK(st.st_mode)) {
        refuse(o, std::string("is a ") + (S_ISBLK(st.st_mode) ? "block device" : "socket") +
                      ": outputs are files, character devices (/dev/null) or pipes");
      }
      if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
        o.kind = Kind::device;
        if (::access(o.target.c_str(), W_OK) != 0) {
          refuse(o, "cannot be written (" + errno_text(errno) + ")");
        }
        return;
      }
      if ((st.st_mode & 0222) == 0 || ::access(o.target.c_str(), W_OK) != 0) {
        refuse(o,
               "is read-only: condyn does not replace a protected file (make it writable or "
               "choose another name)");
      }
    }
    const fs::path folder = o.target.parent_path();
    if (::stat(folder.c_str(), &st) != 0) {
      if (in_planned_folder(folder)) return;  // created with its folder, after the work
      refuse(o, "the folder " + folder.string() + " does not exist");
    }
    if (!S_ISDIR(st.st_mode)) refuse(o, folder.string() + " is not a folder");
    create_temp(o, true);
  }

  void check_not_input(const Output& o) const {
    for (const auto& in : inputs) {
      const bool same = (o.exists && in.exists && o.dev == in.dev && o.ino == in.ino) ||
                        (o.kind == Kind::regular && o.target == in.canonical);
      if (same) {
        refuse(o, "is " + in.path + ", an input of this command: choose another name");
      }
    }
  }

  static bool same_target(const Output& a, const Output& b) {
    if (a.kind == Kind::folder || b.kind == Kind::folder) return false;
    if (a.kind == Kind::descriptor || b.kind == Kind::descriptor) {
      if (a.kind == b.kind && a.fd == b.fd) return true;
      // A descriptor redirected to a file (`--out - > r.csv`) and an output naming that file.
      return a.exists && b.exists && a.dev == b.dev && a.ino == b.ino;
    }
    if (a.kind == Kind::device && b.kind == Kind::device && a.target == "/dev/null" &&
        b.target == "/dev/null") {
      return false;  // a sink may take any number of outputs
    }
    return (a.exists && b.exists && a.dev == b.dev && a.ino == b.ino) || a.target == b.target;
  }

  void write_stream(Output& o) {
    int error = 0;
    if (o.kind == Kind::descriptor) {
      std::cout.flush();
      std::cerr.flush();
      error = write_into(o.fd, false, o.stream_writer);
    } else {
      const int fd = ::open(o.target.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
      error = fd < 0 ? errno : write_into(fd, true, o.stream_writer);
    }
    if (error != 0) {
      throw std::runtime_error(o.path + ": writing the output failed (" + errno_text(error) + ")");
    }
  }

  /// Renames the temporary file over the target, with the permission bits of the file replaced.
  void put_in_place(Output& o) {
    struct stat st {};
    if (::stat(o.target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) {
      ::chmod(o.temp.c_str(), st.st_mode & 07777);
      if (st.st_nlink > 1) {
        std::cerr << "warning: " << o.source << " " << o.path << " had " << st.st_nlink
                  << " hard links: it was replaced by a new file, its other names keep the "
                     "previous content\n";
      }
    }
    if (::rename(o.temp.c_str(), o.target.c_str()) != 0) {
      const int error = errno;
      remove_temp(o);
      throw std::runtime_error(o.path + ": cannot move the output into place (" +
                               errno_text(error) + ")");
    }
    release_temp(o.node);
    o.temp.clear();
  }
};

OutputPlan::OutputPlan() : impl_(std::make_unique<Impl>()) {}

OutputPlan::~OutputPlan() {
  for (auto& o : impl_->outputs) impl_->remove_temp(o);
}

void OutputPlan::add_input(const std::string& path) {
  Impl::Input in;
  in.path = path;
  in.canonical = canonical_or_plain(path);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    in.exists = true;
    in.dev = st.st_dev;
    in.ino = st.st_ino;
  }
  impl_->inputs.push_back(std::move(in));
}

OutputPlan::Id OutputPlan::add_output(const std::string& path, const std::string& source) {
  auto& outputs = impl_->outputs;
  for (Id k = 0; k < outputs.size(); ++k) {
    if (outputs[k].kind != Impl::Kind::folder && outputs[k].path == path &&
        outputs[k].source == source) {
      return k;  // planned before the work, written after it
    }
  }
  Impl::Output o;
  o.path = path;
  o.source = source;
  outputs.push_back(std::move(o));
  return outputs.size() - 1;
}

void OutputPlan::add_folder(const std::string& path, const std::string& source) {
  for (const auto& o : impl_->outputs) {
    if (o.kind == Impl::Kind::folder && o.path == path) return;
  }
  Impl::Output o;
  o.path = path;
  o.source = source;
  o.kind = Impl::Kind::folder;
  impl_->outputs.push_back(std::move(o));
}

void OutputPlan::check() {
  auto& outputs = impl_->outputs;
  for (auto& o : outputs) {  // folders first: files may lie in folders still to be created
    if (o.kind == Impl::Kind::folder && !o.checked) {
      impl_->check_folder(o);
      o.checked = true;
    }
  }
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    auto& o = outputs[k];
    if (o.checked) continue;
    impl_->check_output(o);
    o.checked = true;
    impl_->check_not_input(o);
    for (std::size_t j = 0; j < k; ++j) {
      if (Impl::same_target(outputs[j], o)) {
        const auto& earlier = outputs[j];
        const bool descriptors =
            o.kind == Impl::Kind::descriptor && earlier.kind == Impl::Kind::descriptor;
        const std::string stream =
            o.fd == 1 ? "standard output" : "descriptor " + std::to_string(o.fd);
        Impl::refuse(o, descriptors ? stream + " already takes " + earlier.source
                                    : "is the same file as " + earlier.source + " " + earlier.path +
                                          " (each output needs its own file)");
      }
    }
  }
}

void OutputPlan::create_folders() {
  for (const auto& o : impl_->outputs) {
    if (o.kind != Impl::Kind::folder) continue;
    std::error_code ec;
    fs::create_directories(o.target, ec);
    if (ec) {
      throw std::runtime_error(o.path + ": cannot create the output folder (" + ec.message() + ")");
    }
  }
}

void OutputPlan::write(Id id, Writer writer) {
  auto& o = impl_->outputs.at(id);
  if (!o.checked) check();
  if (o.kind == Impl::Kind::descriptor || o.kind == Impl::Kind::device) {
    o.stream_writer = std::move(writer);
    o.written = true;
    return;
  }
  if (o.temp.empty()) impl_->create_temp(o, false);
  const int fd = ::open(o.temp.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  const int error = fd < 0 ? errno : write_into(fd, true, writer);
  if (error != 0) {
    throw std::runtime_error(o.path + ": writing the output failed (" + errno_text(error) + ")");
  }
  o.written = true;
}

void OutputPlan::commit(const std::vector<Id>& ids) {
  auto& outputs = impl_->outputs;
  for (Id id : ids) {
    if (!outputs.at(id).written) throw std::logic_error("commit of an output never written");
  }
  // Every file is complete in its temporary; the streams now, then the renames, so that a
  // failing stream (a closed pipe, /dev/full) leaves every file as it was.
  for (Id id : ids) {
    auto& o = outputs[id];
    if (o.kind == Impl::Kind::descriptor || o.kind == Impl::Kind::device) impl_->write_stream(o);
  }
  for (Id id : ids) {
    auto& o = outputs[id];
    if (o.kind == Impl::Kind::regular) impl_->put_in_place(o);
  }
  for (auto& o : outputs) impl_->remove_temp(o);  // the outputs not chosen
}

void OutputPlan::commit_all() {
  std::vector<Id> ids;
  for (Id k = 0; k < impl_->outputs.size(); ++k) {
    if (impl_->outputs[k].written) ids.push_back(k);
  }
  commit(ids);
}

bool OutputPlan::to_stdout(Id id) const {
  const auto& o = impl_->outputs.at(id);
  return o.kind == Impl::Kind::descriptor && o.fd == 1;
}

bool OutputPlan::any_to_stdout() const {
  for (Id k = 0; k < impl_->outputs.size(); ++k) {
    if (to_stdout(k)) return true;
  }
  return false;
}

bool OutputPlan::is_stream(Id id) const {
  const auto& o = impl_->outputs.at(id);
  return o.kind == Impl::Kind::descriptor || o.kind == Impl::Kind::device;
}

std::string OutputPlan::display_name(Id id) const {
  const auto& o = impl_->outputs.at(id);
  return o.path == "-" ? "standard output" : o.path;
}

}  // namespace condyn
