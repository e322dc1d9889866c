// Libraries opened with dlopen on first use (models/core/load_library.hpp).

#include "models/core/load_library.hpp"

#include <dlfcn.h>

#include <utility>

namespace condyn {
namespace {

LibraryUnavailable unavailable(const LibraryUse& use, const std::string& what) {
  const char* detail = dlerror();
  return LibraryUnavailable(
      "cannot use " + use.name + " (" + use.soname + "), which " + use.purpose + ": " + what +
      (detail ? std::string(": ") + detail : std::string()) + "; install Debian's " + use.package);
}

}  // namespace

LoadedLibrary::LoadedLibrary(LibraryUse use, Scope scope) : use_(std::move(use)) {
  const int visibility = scope == Scope::global ? RTLD_GLOBAL : RTLD_LOCAL;
  handle_ = dlopen(use_.soname.c_str(), RTLD_NOW | visibility);
  if (handle_ == nullptr) throw unavailable(use_, "dlopen failed");
}

void* LoadedLibrary::find(const char* symbol) const {
  dlerror();  // clear a message left by an earlier call
  return dlsym(handle_, symbol);
}

void* LoadedLibrary::address(const char* symbol) const {
  void* p = find(symbol);
  if (p == nullptr) throw unavailable(use_, std::string("no symbol ") + symbol);
  return p;
}

}  // namespace condyn
