#pragma once
/// What a built-in benchmark model is (models/systems/benchmarks.hpp makes them): its mechanical
/// system, names, published initial state and the published reference states a run is checked
/// against. The Model carries the reference (Model::reference), so core holds the types.

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/core/mechanical_system.hpp"

namespace condyn {

/// A reference state at one time, with the trust its source states.
struct PublishedReference {
  double t = 0.0;
  Eigen::VectorXd u, v;  ///< positions and velocities (v empty when not published)
  /// Multipliers in condyn's sign convention (f_con = −Aᵀλ); empty when not published.
  Eigen::VectorXd lambda;
  /// Significant digits the source vouches for, per group (the test set: q and v to ~10, λ to ~7).
  int digits_u = 10, digits_v = 10, digits_lambda = 7;
  std::string source;  ///< one line: where the numbers come from
};

struct BenchmarkModel {
  std::shared_ptr<const MechanicalSystem> system;
  std::vector<std::string> dof_names;         ///< output column names
  std::vector<std::string> constraint_names;  ///< one per row of A
  Eigen::VectorXd u0, v0;                     ///< consistent initial state (published)
  double t_end = 0.0;                         ///< the published interval's end
  /// The reference at time t, when one is known there (Andrews: t = 0.03; car axis: t = 3;
  /// pendulum: t = 2N exactly).
  std::function<std::optional<PublishedReference>(double t)> reference;
  std::string description;  ///< one line for `condyn info`
};

}  // namespace condyn
