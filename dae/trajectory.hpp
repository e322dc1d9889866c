#pragma once
/// Results at the output times, in full DOF space, whatever the scheme.

#include <Eigen/Dense>
#include <vector>

#include "models/model.hpp"

namespace condyn {

struct Trajectory {
  std::vector<double> t;
  Eigen::MatrixXd u, v;        ///< n x nt displacements and velocities
  Eigen::MatrixXd reaction;    ///< n x nt: f_con, so M u'' + C u' + K u = f + f_con
  Eigen::MatrixXd multiplier;  ///< m x nt: lambda with f_con = -Aᵀ lambda
  Eigen::VectorXd drift_position, drift_velocity;  ///< nt, max-norm constraint residuals
};

/// Builds a trajectory from full-space u, u', u'' at the output times. Reactions are recovered
/// from the full equations: rho = M u'' + C u' + K u − f(t) (the chapter's reaction recovery,
/// eqs. 5.8 and 5.12, for every DOF at once), lambda = −(A Aᵀ)⁻¹ A rho (exact when rho lies in
/// range(Aᵀ), as it does for a solution of the constrained equations), f_con = −Aᵀ lambda.
[[nodiscard]] Trajectory assemble_trajectory(const Model& model, const std::vector<double>& times,
                                             const std::vector<Eigen::VectorXd>& u,
                                             const std::vector<Eigen::VectorXd>& v,
                                             const std::vector<Eigen::VectorXd>& a);

}  // namespace condyn
