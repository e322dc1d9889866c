// The factorization of a run's Newton matrices (dae/run/factorization_choice.hpp).

#include "dae/run/factorization_choice.hpp"

#include <sstream>

#include "dae/interface/scheme_not_applicable.hpp"
#include "dae/linsolve/fixed_pattern_klu.hpp"
#include "models/core/load_library.hpp"
#include "models/core/memory_estimate.hpp"

namespace condyn {

namespace {

/// KLU's factor entries in memory: a value and a 32-bit row index each.
constexpr double kKluBytesPerEntry = sizeof(double) + sizeof(int);

std::string three_digits(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

}  // namespace

bool FactorizationCandidates::cholmod_smaller() const {
  return !cholmod.empty() && least_fill(cholmod).factor_bytes < klu_bytes;
}

std::string FactorizationCandidates::describe() const {
  std::ostringstream s;
  s << "KLU (amd) " << three_digits(klu_entries) << " entries in L and U, "
    << format_bytes(klu_bytes);
  for (const CholmodCandidate& c : cholmod) {
    s << "; CHOLMOD (" << c.ordering << ") " << three_digits(c.factor_entries) << " entries in L, "
      << three_digits(c.flops) << " flops, " << format_bytes(c.factor_bytes);
  }
  return s.str();
}

FactorizationCandidates analyse_factorizations(const Eigen::SparseMatrix<double>& matrix) {
  FactorizationCandidates c;
  c.unknowns = static_cast<int>(matrix.rows());
  c.nonzeros = matrix.nonZeros();
  c.klu_entries = predicted_klu_factor(matrix).entries;
  c.klu_bytes = c.klu_entries * kKluBytesPerEntry;
  c.cholmod = cholmod_candidates(matrix);
  return c;
}

FactorizationChoice choose_factorization(const NewtonSystem* newton, Scheme scheme,
                                         const SolveSpec& settings) {
  using LinearSolver = SolveSpec::LinearSolver;
  if (settings.dense_linear_solver) return {false, "dense LU ([solve] linear_solver = \"dense\")"};
  if (settings.linear_solver == LinearSolver::klu) {
    return {false, "KLU ([solve] linear_solver = \"klu\")"};
  }
  if (settings.linear_solver == LinearSolver::automatic && !settings.condensed_newton) {
    return {false,
            "KLU: the integrator's Jacobian over [u; v] is unsymmetric (under elimination and "
            "penalty of a linear model, linear_solver = \"cholmod\" or newton = \"condensed\" "
            "condenses it to the symmetric "
            "K + cj C + cj^2 M, which CHOLMOD factors)"};
  }
  const Eigen::SparseMatrix<double>* matrix = newton ? newton->symmetric_matrix() : nullptr;
  if (matrix == nullptr) {
    const std::string why = std::string("the Newton matrix of ") + to_string(scheme) +
                            " is not symmetric positive definite (CHOLMOD factors the condensed "
                            "K + cj C + cj^2 M of elimination and penalty on a linear model; "
                            "multipliers make a saddle point, and other schemes' Jacobians are "
                            "unsymmetric)";
    if (settings.linear_solver == LinearSolver::cholmod) {
      throw SchemeNotApplicable(
          "\"cholmod\" cannot factor this run's Newton matrices: " + why +
              "; use \"klu\" or \"auto\", or scheme = \"elimination\" or \"penalty\"",
          settings.linear_solver_where);
    }
    return {false, "KLU: " + why};
  }
  FactorizationCandidates candidates;
  try {
    candidates = analyse_factorizations(*matrix);
  } catch (const LibraryUnavailable& e) {
    if (settings.linear_solver == LinearSolver::cholmod) {
      throw SchemeNotApplicable(std::string("\"cholmod\": ") + e.what(),
                                settings.linear_solver_where);
    }
    return {false, std::string("KLU (auto): ") + e.what(), true};
  }
  const CholmodCandidate& best = least_fill(candidates.cholmod);
  std::ostringstream s;
  s << " the condensed Newton matrix K + cj C + cj^2 M (" << candidates.unknowns
    << " unknowns, symmetric positive definite): " << candidates.describe();
  if (settings.linear_solver == LinearSolver::cholmod) {
    return {true,
            "CHOLMOD (" + best.ordering + ", [solve] linear_solver = \"cholmod\") on" + s.str(),
            false,
            best.ordering,
            best.factor_entries,
            best.factor_bytes,
            best.flops};
  }
  if (candidates.cholmod_smaller()) {
    return {true,
            "CHOLMOD (" + best.ordering + ", auto: the smaller factor) on" + s.str(),
            false,
            best.ordering,
            best.factor_entries,
            best.factor_bytes,
            best.flops};
  }
  return {false, "KLU (auto: the smaller factor) on" + s.str()};
}

std::optional<std::string> factorization_time_warning(const FactorizationChoice& choice) {
  const double seconds = choice.factor_flops / kFactorFlopRate;
  if (!choice.cholmod || !(seconds > kSlowFactorSeconds)) return std::nullopt;
  return "each factorization of the Newton matrix is predicted at " +
         three_digits(choice.factor_flops) + " flops (CHOLMOD, " + choice.ordering +
         "), at least " + three_digits(seconds) + " s at " + three_digits(kFactorFlopRate) +
         " flop/s: every step that refactors (at the start, and wherever the step size " +
         "changes much) takes at least that long";
}

}  // namespace condyn
