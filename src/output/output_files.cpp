#include "src/output/output_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "src/output/fd_stream.hpp"
#include "src/output/output_plan_impl.hpp"

namespace condyn {

namespace fs = std::filesystem;

std::string errno_text(int error) { return std::strerror(error); }

void OutputPlan::Impl::remove_temp(Output& o) {
  if (o.node == nullptr) return;
  ::unlink(o.temp.c_str());
  release_temp(o.node);
  o.temp.clear();
}

void OutputPlan::Impl::create_temp(Output& o, bool at_check) {
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

void OutputPlan::Impl::write_stream(Output& o) {
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

void OutputPlan::Impl::put_in_place(Output& o) {
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
    throw std::runtime_error(o.path + ": cannot move the output into place (" + errno_text(error) +
                             ")");
  }
  release_temp(o.node);
  o.temp.clear();
}

OutputPlan::OutputPlan() : impl_(std::make_unique<Impl>()) {}

OutputPlan::~OutputPlan() {
  for (auto& o : impl_->outputs) impl_->remove_temp(o);
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

std::string OutputPlan::write_in_place(Id id) {
  auto& o = impl_->outputs.at(id);
  if (!o.checked) check();
  if (o.kind == Impl::Kind::descriptor || o.kind == Impl::Kind::device) {
    throw std::logic_error(o.path + ": a stream output cannot be written in place");
  }
  if (o.temp.empty()) impl_->create_temp(o, false);
  o.written = true;
  return o.temp.string();
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
