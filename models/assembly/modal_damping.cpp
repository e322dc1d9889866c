// Damping from the modes of the constrained model: modal damping ratios (issue 13), damping =
// { modal = z } or { modal = [z1, z2, ...] }, and Rayleigh damping by modes (issue 47), damping
// = { rayleigh = { modes = [i, j], ratios = [z1, z2] } }.
//
// C is built from the modes of the constrained model, so that it is classical (diagonal in
// those modes: the exact modal reference uses it as is) and each mode i gets the ratio z_i:
// with N an orthonormal basis of null(A) and Ψ the NᵀMN-orthonormal modes of (NᵀKN, NᵀMN),
// φ = NΨ and C = (Mφ) diag(2 z_i ω_i) (Mφ)ᵀ, so that φᵀCφ = diag(2 z_i ω_i). Dense (the modes
// are): refused above the dense limit, where Rayleigh damping is the sparse choice. Rayleigh
// damping by modes needs only two frequencies, found as `condyn modes` finds them: sparse beyond
// its dense limit.

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/assembly/model_builder.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/core/master_slave.hpp"
#include "models/core/null_space.hpp"
#include "models/core/pencil_modes.hpp"
#include "models/core/rayleigh.hpp"

namespace condyn {

namespace {

/// The constrained model's modes, dense: N an orthonormal basis of null(A) (n x (n − m)), ω²
/// ascending and Ψ the NᵀMN-orthonormal modes of (NᵀKN, NᵀMN).
struct DenseModes {
  Eigen::MatrixXd N;
  Eigen::VectorXd omega2;
  Eigen::MatrixXd psi;
};

/// Fills `out`, or says what prevents it ("needs mass on every motion ..."), to follow the name of
/// what asked for the modes and precede its advice.
std::optional<std::string> dense_modes(const Model& model, DenseModes& out) {
  const int n = model.dofs();
  out.N = null_space_basis(model.A, n);
  const Eigen::MatrixXd M(model.M), K(*model.K);
  const Eigen::MatrixXd Mr = out.N.transpose() * M * out.N, Kr = out.N.transpose() * K * out.N;
  const Eigen::LLT<Eigen::MatrixXd> regular(Mr);
  if (regular.info() != Eigen::Success || regular.rcond() < 1e-12) {
    return "needs mass on every motion the constraints allow (massless DOFs have no modes of "
           "their own)";
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(
      Kr, Mr, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (modes.info() != Eigen::Success) return "failed: the eigenproblem of (K, M) did not converge";
  out.omega2 = modes.eigenvalues();
  out.psi = modes.eigenvectors();
  return std::nullopt;
}

}  // namespace

void ModelBuilder::apply_modal_damping() {
  const auto& ratios = spec_.model.modal_ratios;
  if (ratios.empty()) return;
  const SourcePoint& where = spec_.model.modal_where;
  if (model_.is_nonlinear()) {
    fail(where,
         "modal damping needs a linear model: this one has no constant modes (large "
         "displacements, rigid members or a built-in nonlinear model)");
  }
  if (model_.has_damping()) {  // a truss's member dampers: C would replace them
    fail(where,
         "modal damping gives every mode its ratio, and the members' dampers (c) would be "
         "lost: give one or the other");
  }
  const int n = model_.dofs();
  if (static_cast<double>(n) * n > kMaxDenseEntries) {
    fail(where, "modal damping is built from the model's modes, dense n x n: " + std::to_string(n) +
                    " DOFs is beyond the dense limit (" +
                    std::to_string(static_cast<long>(std::sqrt(kMaxDenseEntries))) +
                    "); use damping = { rayleigh = { frequencies = [...], ratios = [...] } }, "
                    "which stays sparse");
  }
  DenseModes modes;
  if (const auto problem = dense_modes(model_, modes)) {
    fail(where, "modal damping " + *problem + "; use Rayleigh damping");
  }
  const Eigen::MatrixXd M(model_.M);
  const Eigen::MatrixXd Mphi = M * (modes.N * modes.psi);
  const auto count = modes.omega2.size();
  Eigen::VectorXd c(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double omega = std::sqrt(std::max(modes.omega2[i], 0.0));
    const double z = ratios[std::min(static_cast<std::size_t>(i), ratios.size() - 1)];
    c[i] = 2.0 * z * omega;
  }
  const Eigen::MatrixXd C = Mphi * c.asDiagonal() * Mphi.transpose();
  const Eigen::MatrixXd symmetric = 0.5 * C + 0.5 * C.transpose();  // no overflow at 1e308
  model_.C = symmetric.sparseView(1.0, 1e-14 * symmetric.cwiseAbs().maxCoeff());
  model_.C.makeCompressed();
  std::ostringstream rule;
  rule.precision(4);
  rule << "modal damping: ratio" << (ratios.size() == 1 ? " " : "s ");
  for (std::size_t i = 0; i < ratios.size(); ++i) rule << (i ? ", " : "") << ratios[i];
  rule << (ratios.size() > 1 ? " (the last for the higher modes)" : "") << " on the " << count
       << " modes of the constrained model (" << std::sqrt(std::max(modes.omega2[0], 0.0))
       << " ... " << std::sqrt(std::max(modes.omega2[count - 1], 0.0))
       << " rad/s); C dense in those DOFs";
  report_.damping = rule.str();
  if (ratios.size() > static_cast<std::size_t>(count)) {
    report_.warnings.push_back(
        "damping.modal gives " + std::to_string(ratios.size()) + " ratios for the " +
        std::to_string(count) + " modes of the constrained model: the last " +
        std::to_string(ratios.size() - static_cast<std::size_t>(count)) + " are unused");
  }
}

/// ω of the `picked` modes (1 the lowest) of the constrained model, found as `condyn modes` finds
/// them (dae/formulations/natural_modes.hpp), so that they number and agree alike: u = T û
/// (master_slave.hpp), the pencil (TᵀKT, TᵀMT) with its massless DOFs condensed, dense up to
/// kDenseModeDofs and by shift-invert Lanczos beyond (pencil_modes.hpp), which stays sparse.
/// Fails at the key for what prevents them: too few modes, a rigid motion, no modes.
std::array<double, 2> ModelBuilder::rayleigh_mode_frequencies() const {
  const auto& picked = spec_.model.rayleigh_modes;
  const SourcePoint& where = spec_.model.rayleigh_where;
  const auto advice = std::string("; give their frequencies instead, rayleigh = { frequencies = ") +
                      "[f_i, f_j], ratios = [...] }";
  MasterSlave transform;
  try {
    transform = master_slave_transform(model_.A);
  } catch (const CoupledGroupTooLarge& e) {
    fail(where, std::string("Rayleigh damping by modes eliminates the constraints, and ") +
                    e.what() + advice);
  }
  const Eigen::SparseMatrix<double>& T = transform.T;
  const Eigen::SparseMatrix<double> Tt = T.transpose();
  const Eigen::SparseMatrix<double> K = Tt * *model_.K * T, M = Tt * model_.M * T;
  const int available = mode_count(M), highest = std::max(picked[0], picked[1]);
  if (highest > available) {
    fail(where, "mode " + std::to_string(highest) + ": the constrained model has " +
                    std::to_string(available) + " modes");
  }
  PencilModes modes;
  try {
    modes = lowest_modes(K, M, highest);
  } catch (const ModesUnavailable& e) {
    fail(where, std::string("Rayleigh damping by modes: ") + e.what() + advice);
  } catch (const std::invalid_argument& e) {  // beyond both the dense and the Lanczos limits
    fail(where, std::string("Rayleigh damping by modes: ") + e.what() + advice);
  }
  std::array<double, 2> omega{};
  for (std::size_t k = 0; k < 2; ++k) {
    omega[k] = std::sqrt(modes.omega2[picked[k] - 1]);
    if (!(omega[k] > 0.0)) {
      fail(where,
           "mode " + std::to_string(picked[k]) +
               " has zero frequency (a rigid motion): Rayleigh damping cannot set its ratio");
    }
  }
  return omega;
}

/// damping = { rayleigh = { modes = [i, j], ratios = [z1, z2] } }: C = a0 M + a1 K with ratio z1
/// at ω_i and z2 at ω_j, the frequencies of modes i and j of the constrained model. Beside a
/// truss's member dampers, as Rayleigh damping by frequencies.
void ModelBuilder::apply_rayleigh_modes() {
  const auto& picked = spec_.model.rayleigh_modes;
  if (picked.empty()) return;
  const SourcePoint& where = spec_.model.rayleigh_where;
  if (model_.is_nonlinear()) {
    fail(where,
         "Rayleigh damping by modes needs a linear model, whose modes are constant: this one has "
         "large displacements, rigid members or is a built-in nonlinear model");
  }
  const std::array<double, 2> omega = rayleigh_mode_frequencies();
  const auto [z1, z2] = spec_.model.rayleigh_mode_ratios;
  const auto [a0, a1] = rayleigh_coefficients(omega[0], omega[1], z1, z2, 1.0);
  std::ostringstream rule;
  rule.precision(6);
  rule << "Rayleigh damping C = a0 M + a1 K with a0 = " << a0 << ", a1 = " << a1 << ", from ratio "
       << z1 << " at mode " << picked[0] << " (omega " << omega[0]
       << " rad per time unit) and ratio " << z2 << " at mode " << picked[1] << " (omega "
       << omega[1] << ")";
  if (!std::isfinite(a0) || !std::isfinite(a1) || a0 < 0.0 || a1 < 0.0) {
    fail(where, "these pairs give " + rule.str().substr(rule.str().find("a0 =")) +
                    ": a negative or infinite coefficient (modes of equal frequency, or ratios "
                    "that z(ω) = a0/(2ω) + a1 ω/2 cannot have there)");
  }
  // M and K positive semi-definite, a0 and a1 >= 0: so is C; a truss's member dampers kept.
  if (model_.C.nonZeros() == 0) model_.rayleigh = RayleighCoefficients{a0, a1};
  model_.C = (a0 * model_.M + a1 * *model_.K + model_.C).pruned();
  model_.C.makeCompressed();
  report_.damping = rule.str();
}

}  // namespace condyn
