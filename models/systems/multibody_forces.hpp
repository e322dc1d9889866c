#pragma once
/// The applied forces of a mechanism in natural coordinates (models/systems/multibody_system.hpp)
/// as generalized forces f(t, q, q'), with their exact tangents −∂f/∂q and −∂f/∂q':
///
///   gravity          m g on r (constant)
///   point_force      Bᵀ F(t) at a marker x = B q + x0 (B constant): a pattern load per component
///   torque           2D τ(t) perp(u) on u (virtual work τ δθ, δu = δθ perp(u));
///                    3D ½ T(t) × R_k on each column R_k (Σ_k R_k × Q_k = T on the manifold)
///   spring_damper    between markers x1, x2, d = x2 − x1, l = |d|, e = d/l:
///                    F2 = −(k (l − L) + c l') e on x2, −F2 on x1 (l' = e·d')
///   rotational       at a revolute joint: δ = the relative angle minus the rest angle, taken in
///   spring_damper    (−π, π] (atan2 of two quadratic forms), moment −k δ − c δ' on ∂δ/∂q
///
/// A spring of length 0 has no direction: its force is taken as 0 there.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

#include "models/core/mechanical_system.hpp"
#include "models/core/mechanism.hpp"
#include "models/core/model.hpp"
#include "models/systems/multibody_geometry.hpp"

namespace condyn {

class MultibodyForces {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;
  using Triplets = std::vector<Eigen::Triplet<double>>;

  MultibodyForces(const Mechanism& m, const MultibodyGeometry& g);

  /// f += the applied forces at (t, q, v); steps: TimeFunction's step reference.
  void add_force(double t, double steps, const ConstRef& q, const ConstRef& v, Ref f) const;
  /// −∂f/∂q and −∂f/∂q' as triplets (the same positions at every call).
  void stiffness(double t, double steps, const ConstRef& q, const ConstRef& v, Triplets& out) const;
  void damping(const ConstRef& q, const ConstRef& v, Triplets& out) const;
  /// V (gravity, constant point forces, springs), the dampers' power and the power of the
  /// time-dependent point forces and of the torques.
  [[nodiscard]] MechanicalSystem::EnergyParts energy_parts(double t, double steps,
                                                           const ConstRef& q,
                                                           const ConstRef& v) const;
  /// No damper, no torque, only constant loads: V is the whole potential.
  [[nodiscard]] bool conservative() const { return conservative_; }

 private:
  /// An affine vector or form restricted to the columns it touches, dense there.
  struct LocalVector {
    std::vector<int> cols;
    Eigen::MatrixXd B;  ///< dim x cols
    Eigen::VectorXd x0;
  };
  struct Spring {
    LocalVector d;  ///< x2 − x1
    double k, c, rest;
  };
  struct Angle {
    std::vector<int> cols;
    Eigen::MatrixXd HX, HY;  ///< the forms' Hessians on cols
    Eigen::VectorXd gX, gY;
    double cX, cY;
    double k, c;
  };
  /// δ, ∂δ/∂q (on cols) and ∂²δ/∂q² of an angle element.
  struct AngleState {
    double delta;
    Eigen::VectorXd grad;
    Eigen::MatrixXd hess;
  };
  struct Torque {
    int body;
    std::vector<TimeFunction> components;  ///< 1 (2D) or 3 (3D), global
  };

  [[nodiscard]] AngleState angle_state(const Angle& a, const ConstRef& q) const;
  /// The generalized force of a torque element at (t, q).
  void add_torque(const Torque& tq, double t, double steps, const ConstRef& q, Ref f) const;
  [[nodiscard]] static Eigen::VectorXd gather(const std::vector<int>& cols, const ConstRef& x);
  static void scatter(const std::vector<int>& cols, const Eigen::MatrixXd& block, Triplets& out);
  /// q0: the coordinates at t = 0 (the spring's length, the angle's zero there).
  void add_spring(const Mechanism& m, const Eigen::VectorXd& q0, const Mechanism::Force& f);
  void add_angle(const Mechanism& m, const Eigen::VectorXd& q0, const Mechanism::Force& f);
  void add_point_force(const MultibodyGeometry& g, const Mechanism& m, const Mechanism::Force& f);

  int dim_, n_;
  MultibodyGeometry geometry_;
  std::vector<Load> loads_;  ///< gravity and point forces
  std::vector<Spring> springs_;
  std::vector<Angle> angles_;
  std::vector<Torque> torques_;
  bool conservative_ = true;
};

}  // namespace condyn
