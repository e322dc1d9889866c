// Modal damping ratios (issue 13): damping = { modal = z } or { modal = [z1, z2, ...] }.
//
// C is built from the modes of the constrained model, so that it is classical (diagonal in
// those modes: the exact modal reference uses it as is) and each mode i gets the ratio z_i:
// with N an orthonormal basis of null(A) and Ψ the NᵀMN-orthonormal modes of (NᵀKN, NᵀMN),
// φ = NΨ and C = (Mφ) diag(2 z_i ω_i) (Mφ)ᵀ, so that φᵀCφ = diag(2 z_i ω_i). Dense (the modes
// are): refused above the dense limit, where Rayleigh damping is the sparse choice.

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "models/assembly/model_builder.hpp"
#include "models/core/null_space.hpp"

namespace condyn {

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
  const Eigen::MatrixXd N = null_space_basis(model_.A, n);
  const Eigen::MatrixXd M(model_.M), K(*model_.K);
  const Eigen::MatrixXd Mr = N.transpose() * M * N, Kr = N.transpose() * K * N;
  const Eigen::LLT<Eigen::MatrixXd> regular(Mr);
  if (regular.info() != Eigen::Success || regular.rcond() < 1e-12) {
    fail(where,
         "modal damping needs mass on every motion the constraints allow (massless DOFs have "
         "no modes of their own); use Rayleigh damping");
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes(
      Kr, Mr, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (modes.info() != Eigen::Success) fail(where, "the eigenproblem of (K, M) did not converge");
  const Eigen::MatrixXd Mphi = M * (N * modes.eigenvectors());
  const auto count = modes.eigenvalues().size();
  Eigen::VectorXd c(count);
  for (Eigen::Index i = 0; i < count; ++i) {
    const double omega = std::sqrt(std::max(modes.eigenvalues()[i], 0.0));
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
       << " modes of the constrained model (" << std::sqrt(std::max(modes.eigenvalues()[0], 0.0))
       << " ... " << std::sqrt(std::max(modes.eigenvalues()[count - 1], 0.0))
       << " rad/s); C dense in those DOFs";
  report_.damping = rule.str();
  if (ratios.size() > static_cast<std::size_t>(count)) {
    report_.warnings.push_back(
        "damping.modal gives " + std::to_string(ratios.size()) + " ratios for the " +
        std::to_string(count) + " modes of the constrained model: the last " +
        std::to_string(ratios.size() - static_cast<std::size_t>(count)) + " are unused");
  }
}

}  // namespace condyn
