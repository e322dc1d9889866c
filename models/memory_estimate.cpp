// The memory a model needs to integrate, from its nonzeros, against MemAvailable: what replaced
// the fixed DOF and constraint limits.

#include "models/memory_estimate.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace condyn {

namespace {

constexpr double kBytesPerNonzero = 12.0;  // a double and a 32-bit row index
constexpr double kIdaVectors = 30.0;
constexpr double kModelCopies = 3.0;

std::string count(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

}  // namespace

MemoryEstimate integration_memory_estimate(const ModelSizes& s) {
  const double model_nonzeros = s.nnz_mass + s.nnz_damping + s.nnz_stiffness + s.nnz_constraints;
  MemoryEstimate e;
  e.newton_nonzeros =
      s.nnz_mass + s.nnz_damping + s.nnz_stiffness + 2.0 * s.dofs + 4.0 * s.nnz_constraints;
  const double unknowns = 2.0 * s.dofs + 2.0 * s.constraints;
  const double rest =
      kIdaVectors * 8.0 * unknowns + kModelCopies * kBytesPerNonzero * model_nonzeros;
  // L and U, and their copy for the solves when large enough (dae/fixed_pattern_klu.hpp).
  const auto factors = [](double entries) {
    return entries >= static_cast<double>(kStreamedSolveFromEntries) ? 2.0 * entries : entries;
  };
  e.bytes =
      kBytesPerNonzero * (2.0 * e.newton_nonzeros + factors(kKluFillFactor * e.newton_nonzeros)) +
      rest;
  e.lower_bound = kBytesPerNonzero * (2.0 * e.newton_nonzeros + factors(e.newton_nonzeros)) + rest;
  return e;
}

namespace {

/// The value of `key` in a /proc file of "Key: value kB" lines, in bytes.
std::optional<double> proc_kib(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string name, unit;
  double value = 0;
  while (in >> name >> value) {
    std::getline(in, unit);
    if (name == key) return value * 1024.0;  // the kernel writes kB (KiB)
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> available_memory_bytes() {
  const std::optional<double> free = proc_kib("/proc/meminfo", "MemAvailable:");
  if (!free) return std::nullopt;
  // What condyn holds already (the model read and built so far) is part of every estimate.
  return *free + proc_kib("/proc/self/status", "RssAnon:").value_or(0.0);
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1000.0 && u < 5) {
    bytes /= 1000.0;
    ++u;
  }
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << bytes << " " << units[u];
  return s.str();
}

std::optional<std::string> memory_refusal(const ModelSizes& sizes, const MemoryEstimate& e,
                                          double available) {
  if (e.lower_bound <= available) return std::nullopt;
  return count(sizes.dofs) + " DOFs and " + count(sizes.constraints) +
         " constraints need at least " + format_bytes(e.lower_bound) +
         " to integrate (a Newton matrix of " + count(e.newton_nonzeros) +
         " nonzeros, its KLU factors at least as large, and the solver's vectors; about " +
         format_bytes(e.bytes) + " with typical fill), more than the " + format_bytes(available) +
         " this machine has available (MemAvailable in /proc/meminfo, with what condyn holds "
         "already): reduce the model or run "
         "it on a machine with more memory";
}

std::optional<std::string> memory_warning(const MemoryEstimate& e, double available) {
  if (e.bytes <= available) return std::nullopt;
  return "integrating needs about " + format_bytes(e.bytes) + " (at least " +
         format_bytes(e.lower_bound) + "; KLU's fill taken as " + count(kKluFillFactor) +
         " times the Newton matrix), more than the " + format_bytes(available) +
         " available now: the run may fail for lack of memory";
}

}  // namespace condyn
