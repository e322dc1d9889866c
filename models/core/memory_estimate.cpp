// The memory a model needs to integrate, from its nonzeros, against MemAvailable: what replaced
// the fixed DOF and constraint limits.

#include "models/core/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "models/core/model.hpp"

namespace condyn {

namespace {

constexpr double kBytesPerNonzero = 12.0;  // a double and a 32-bit row index
/// Resident before any model is read: the executable, its libraries and their data.
constexpr double kProcessBytes = 7.0e6;
constexpr double kModelCopies = 3.0;
/// IDA's: six history arrays, error weights, the Newton iterates and work vectors.
constexpr double kIntegratorVectors = 30.0;

std::string count(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

/// Bytes of a factor of `entries` entries that costs `flops`, with the streamed copy when the
/// Newton solvers keep one.
double factor_bytes(double entries, double flops) {
  return (keeps_streamed_copy(entries, flops) ? 2.0 : 1.0) * kBytesPerNonzero * entries;
}

}  // namespace

MemoryEstimate integration_memory_estimate(const ModelSizes& m, const IntegratedSizes& s) {
  const double model_nonzeros = m.nnz_mass + m.nnz_damping + m.nnz_stiffness + m.nnz_constraints;
  const double copies = kModelCopies + (s.condensed ? 1.0 : 0.0) + (s.reduced ? 1.0 : 0.0);
  const double rest = kProcessBytes + copies * kBytesPerNonzero * model_nonzeros +
                      kIntegratorVectors * 8.0 * s.unknowns;
  MemoryEstimate e;
  e.newton_nonzeros = s.newton_nonzeros;
  e.factor_entries = s.factor_entries;
  if (s.dense) {  // the matrix and its LU, in place of KLU's
    e.bytes = e.lower_bound = rest + 2.0 * 8.0 * s.unknowns * s.unknowns;
    return e;
  }
  const double newton = (kBytesPerNonzero * (s.condensed ? 2.0 : 1.0) + 4.0) * s.newton_nonzeros;
  if (s.cholmod_factor_bytes > 0) {
    e.cholmod = true;
    e.bytes = e.lower_bound = rest + newton + s.cholmod_factor_bytes;
    return e;
  }
  e.bytes =
      rest + newton + factor_bytes(std::max(s.factor_entries, s.newton_nonzeros), s.factor_flops);
  // One copy: the run decides on the streamed one from its own factor's flops, which the
  // analysis only predicts.
  e.lower_bound = rest + newton + kBytesPerNonzero * s.newton_nonzeros;
  return e;
}

ModelSizes model_sizes(const Model& model) {
  ModelSizes sizes;
  sizes.dofs = model.dofs();
  sizes.constraints = model.constraint_count();
  sizes.nnz_mass = static_cast<double>(model.M.nonZeros());
  sizes.nnz_damping = static_cast<double>(model.C.nonZeros());
  sizes.nnz_stiffness = static_cast<double>(model.K->nonZeros());
  sizes.nnz_constraints = static_cast<double>(model.A.nonZeros());
  return sizes;
}

MemoryEstimate least_memory_estimate(const ModelSizes& m) {
  IntegratedSizes fewest;
  fewest.unknowns = 2.0 * std::max(m.dofs - m.constraints, 0.0);
  fewest.newton_nonzeros = fewest.factor_entries = fewest.unknowns;
  return integration_memory_estimate(m, fewest);
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
                                          const std::string& what, double available) {
  if (e.lower_bound <= available) return std::nullopt;
  return count(sizes.dofs) + " DOFs and " + count(sizes.constraints) +
         " constraints need at least " + format_bytes(e.lower_bound) + " to integrate under " +
         what + " (a Newton matrix of " + count(e.newton_nonzeros) +
         " nonzeros, its KLU factors at least as large, and the solver's vectors), more than the " +
         format_bytes(available) +
         " this machine has available (MemAvailable in /proc/meminfo, with what condyn holds "
         "already): reduce the model or run it on a machine with more memory";
}

std::string factor_name(const MemoryEstimate& e) {
  return e.cholmod ? "CHOLMOD's factor" : "KLU's factors";
}

std::optional<std::string> memory_warning(const MemoryEstimate& e, const std::string& what,
                                          double available) {
  if (e.bytes <= available) return std::nullopt;
  return "integrating under " + what + " needs about " + format_bytes(e.bytes) + " (at least " +
         format_bytes(e.lower_bound) + "; " + factor_name(e) + " predicted at " +
         count(e.factor_entries) + " entries), more than the " + format_bytes(available) +
         " available now: the run may fail for lack of memory";
}

}  // namespace condyn
