#pragma once
/// How a model's results are shown when its output columns are not its coordinates. A mechanism
/// integrates natural coordinates (models/systems/multibody_system.hpp) but its outputs are the
/// contract's: poses `crank.x`, `crank.angle` (or a unit quaternion in 3D), velocities
/// `crank.vx`, `crank.omega`, accelerations `crank.ax`, `crank.alpha`, joint reactions
/// `hinge.fx`, `hinge.m` and named points `crank.B.x`. A Model without an OutputMap shows u, u',
/// u'' per DOF and −Aᵀλ per DOF (the columns of docs/scenes.md "Output").
///
/// A map is constant and shared by every writer and thread; what it needs of the past (an angle
/// continued across ±π, a quaternion's sign kept continuous) it is given: the previous row.

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "models/core/output_quantity.hpp"

namespace condyn {

class OutputMap {
 public:
  using Vector = Eigen::VectorXd;
  virtual ~OutputMap() = default;

  /// The full column names of displacement, velocity, acceleration or reaction, in the order the
  /// functions below fill them (no prefix is added: `crank.vx`, not `vel_crank.vx`). Other
  /// quantities are not mapped (an empty list).
  [[nodiscard]] virtual const std::vector<std::string>& names(Quantity q) const = 0;

  /// The displacement columns at (t, u). `previous` holds the previous output row's columns, or
  /// is empty at the first row: angles continue from it (no jump of 2π) and quaternions keep
  /// their sign (qw > 0 at the first row).
  virtual void displacement(double t, const Vector& u, const Vector& previous,
                            Vector& out) const = 0;
  virtual void velocity(double t, const Vector& u, const Vector& v, Vector& out) const = 0;
  virtual void acceleration(double t, const Vector& u, const Vector& v, const Vector& a,
                            Vector& out) const = 0;
  /// The reaction columns from the multipliers λ (m, the model's rows in order).
  virtual void reaction(double t, const Vector& u, const Vector& lambda, Vector& out) const = 0;

  /// Named points ([output] points = ["crank.B"]): the index of "body.point", if there is one.
  [[nodiscard]] virtual std::optional<int> point(std::string_view name) const = 0;
  /// The dimension's global coordinates of point `index` at u.
  virtual void point_position(int index, const Vector& u, Eigen::Ref<Vector> out) const = 0;
  [[nodiscard]] virtual int dimension() const = 0;

 protected:
  OutputMap() = default;
  OutputMap(const OutputMap&) = default;
  OutputMap& operator=(const OutputMap&) = default;
};

}  // namespace condyn
