#pragma once
// Shared libraries that condyn opens with dlopen when a scene first needs them (SuiteSparseQR,
// CHOLMOD, OpenBLAS: models/core/sparse_qr.hpp says why), by their SONAME, with their entry
// points resolved by name. A library that cannot be opened, or lacks an entry point, is reported
// naming it, what condyn needs it for and the Debian package that installs it.

#include <stdexcept>
#include <string>

namespace condyn {

/// A library loaded on first use: its name as users know it (`CHOLMOD`), its SONAME, what condyn
/// needs it for (a clause after "which": `factors symmetric positive-definite Newton matrices`)
/// and the Debian package that installs it.
struct LibraryUse {
  std::string name;
  std::string soname;
  std::string purpose;
  std::string package;
};

/// Thrown when a library cannot be opened or lacks an entry point: "cannot use NAME (SONAME),
/// which PURPOSE: WHAT: the loader's message; install Debian's PACKAGE".
class LibraryUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One library opened for the rest of the process (never closed: its functions may be called
/// until the process ends).
class LoadedLibrary {
 public:
  /// Whose symbols the library's own lookups, and those of libraries opened later, may see:
  /// `local` keeps them to this handle; `global` lets a library opened afterwards bind to them
  /// (OpenBLAS for CHOLMOD's BLAS and LAPACK calls).
  enum class Scope { local, global };

  /// Opens `use.soname` with every symbol bound now (RTLD_NOW). Throws LibraryUnavailable.
  LoadedLibrary(LibraryUse use, Scope scope);

  /// Sets `f` to the library's function `symbol`. Throws LibraryUnavailable when it has none.
  template <class F>
  void resolve(const char* symbol, F& f) const {
    // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): dlsym returns void*
    f = reinterpret_cast<F>(address(symbol));
  }
  /// Sets `f` to the function `symbol` of the library or of a library it depends on, or to
  /// nullptr when none has it; returns whether one does.
  template <class F>
  bool resolve_if_present(const char* symbol, F& f) const {
    // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): dlsym returns void*
    f = reinterpret_cast<F>(find(symbol));
    return f != nullptr;
  }

 private:
  [[nodiscard]] void* address(const char* symbol) const;
  [[nodiscard]] void* find(const char* symbol) const;  ///< nullptr when absent
  LibraryUse use_;
  void* handle_ = nullptr;
};

}  // namespace condyn
