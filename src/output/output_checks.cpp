#include "src/output/output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <filesystem>
#include <optional>
#include <string_view>

#include "src/output/output_plan_impl.hpp"

namespace condyn {

namespace fs = std::filesystem;

namespace {

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

fs::path OutputPlan::Impl::follow_links(const Output& o) {
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

bool OutputPlan::Impl::in_planned_folder(const fs::path& folder) const {
  return std::any_of(outputs.begin(), outputs.end(), [&](const Output& f) {
    return f.kind == Kind::folder && f.checked && is_within(folder, f.target);
  });
}

void OutputPlan::Impl::check_folder(Output& o) {
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

void OutputPlan::Impl::check_output(Output& o) {
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
  } else if (errno == ENAMETOOLONG || o.target.filename().native().size() > NAME_MAX) {
    // The temporary file's shorter name would pass, and the rename after the run fail.
    refuse(o, "cannot be created: " + errno_text(ENAMETOOLONG) + " (at most " +
                  std::to_string(NAME_MAX) + " bytes a name)");
  }
  const fs::path folder = o.target.parent_path();
  if (::stat(folder.c_str(), &st) != 0) {
    if (in_planned_folder(folder)) return;  // created with its folder, after the work
    refuse(o, "the folder " + folder.string() + " does not exist");
  }
  if (!S_ISDIR(st.st_mode)) refuse(o, folder.string() + " is not a folder");
  create_temp(o, true);
}

void OutputPlan::Impl::check_not_input(const Output& o) const {
  for (const auto& in : inputs) {
    const bool same = (o.exists && in.exists && o.dev == in.dev && o.ino == in.ino) ||
                      (o.kind == Kind::regular && o.target == in.canonical);
    if (same) {
      refuse(o, "is " + in.path + ", an input of this command: choose another name");
    }
  }
}

bool OutputPlan::Impl::same_target(const Output& a, const Output& b) {
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

bool OutputPlan::remove_stale(const std::filesystem::path& path) const {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0) return false;  // protected
  for (const auto& in : impl_->inputs) {
    if (in.exists && in.dev == st.st_dev && in.ino == st.st_ino) return false;
  }
  std::error_code ignored;
  return std::filesystem::remove(path, ignored);
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

}  // namespace condyn
