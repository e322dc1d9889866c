#pragma once
/// The general constrained mechanical system the multiplier formulations are written against:
///
///   M(t, u) u'' = f(t, u, u') − A(t, u)ᵀ λ                  (f_con = −Aᵀλ)
///   φ_i(t, u) = 0              for position-level rows i     (holonomic; A_i = ∂φ_i/∂u)
///   ψ_i(t, u, u') = 0          for every row i: the velocity-level form, ψ = A(t, u) u' + b(t, u)
///                              (ψ_i = dφ_i/dt along u' for position rows; A_i u' − h_i for
///                              velocity rows, which may be nonholonomic)
///   A(t, u) u'' = γ(t, u, u')  the acceleration-level form, γ = A u'' − dψ/dt (for nonlinear
///                              rows it carries the curvature terms, −u'ᵀ ∂²φ/∂u² u' − …)
///
/// Linear models are one case of it (models/core/linear_system.hpp): constant M, A, and curvature
/// blocks that are empty. Every Jacobian block is reported with a pattern that does not depend on
/// the arguments (structural zeros are stored as explicit zeros), so a formulation assembles its
/// Jacobian pattern once, at the initial state.
///
/// An object of this class is an evaluator: it keeps scratch space and the matrices it returns by
/// reference, so evaluating changes it (the methods are not const). The Model holds its system as
/// a constant prototype; every run, and every thread, evaluates its own clone(), which shares the
/// constant data and owns its caches. The evaluator also knows the integration segment it is in
/// (begin_segment), so that no load step switches on inside a segment.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <optional>
#include <vector>

namespace condyn {

class MechanicalSystem {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;
  using Sparse = Eigen::SparseMatrix<double>;

  virtual ~MechanicalSystem() = default;

  /// A new evaluator of the same system: the constant data shared, its own caches (a clone of the
  /// Model's prototype starts outside any segment).
  [[nodiscard]] virtual std::unique_ptr<MechanicalSystem> clone() const = 0;

  /// The integration segment starting at t0 begins: load steps with start <= t0 are on, later ones
  /// off, until the next call. Before any call (an evaluation outside an integration), a step is
  /// on at t when start <= t.
  void begin_segment(double t0) { segment_start_ = t0; }

  [[nodiscard]] virtual int dofs() const = 0;
  [[nodiscard]] virtual int constraints() const = 0;
  /// true for rows written at position level (they get φ and, under GGL, a μ).
  [[nodiscard]] virtual const std::vector<bool>& position_rows() const = 0;

  /// M(t, u), n x n, its pattern fixed. The reference stays valid until the next call (a linear
  /// system returns its constant matrix: no copy on the residual's hot path).
  [[nodiscard]] virtual const Sparse& mass(double t, ConstRef u) = 0;
  /// f(t, u, u'): applied loads minus internal forces (K u + C u' for a linear model), plus the
  /// velocity-dependent inertia terms of generalized coordinates. Load steps as begin_segment says.
  virtual void force(double t, ConstRef u, ConstRef v, Ref f) = 0;
  /// The tangent stiffness −df/du and damping −df/du', n x n each (K and C of a linear model),
  /// patterns fixed; references valid until the next call. Written with the structural sign so
  /// that a linear system returns the model's own K and C: one copy of the stiffness in a run
  /// (at 10⁶ DOFs a copy of K is 200 MB).
  [[nodiscard]] virtual const Sparse& stiffness(double t, ConstRef u, ConstRef v) = 0;
  [[nodiscard]] virtual const Sparse& damping(double t, ConstRef u, ConstRef v) = 0;

  /// A(t, u), m x n, pattern fixed; the reference stays valid until the next call.
  [[nodiscard]] virtual const Sparse& constraint_jacobian(double t, ConstRef u) = 0;
  /// φ (m; zero on velocity rows).
  virtual void position_residual(double t, ConstRef u, Ref phi) = 0;
  /// ψ (m).
  virtual void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) = 0;
  /// γ (m).
  virtual void acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) = 0;

  /// true when M or A depend on the state (nonlinear geometry, generalized coordinates,
  /// nonholonomic rows): the curvature blocks below are then nonempty and M, A must be
  /// re-evaluated at every state.
  [[nodiscard]] virtual bool has_curvature() const { return false; }

  /// The state derivatives Newton's matrix needs beyond M, A, f_u, f_v (exact; tested against
  /// finite differences). Each returns an empty (0 x 0) matrix when the term vanishes identically
  /// (the default, right for constant M and A); otherwise a matrix of the stated size whose
  /// pattern does not depend on the arguments. References are valid until the next call.
  // The defaults ignore their arguments; by-value Refs are the signature every override shares.
  // NOLINTBEGIN(performance-unnecessary-value-param)
  /// d(M(t, u) a)/du, n x n.
  [[nodiscard]] virtual const Sparse& mass_jacobian(double /*t*/, ConstRef /*u*/, ConstRef /*a*/) {
    return empty();
  }
  /// d(A(t, u)ᵀ w)/du, n x n (w: m multipliers).
  [[nodiscard]] virtual const Sparse& constraint_force_jacobian(double /*t*/, ConstRef /*u*/,
                                                                ConstRef /*w*/) {
    return empty();
  }
  /// d(A(t, u) a)/du, m x n (a: n accelerations).
  [[nodiscard]] virtual const Sparse& constraint_product_jacobian(double /*t*/, ConstRef /*u*/,
                                                                  ConstRef /*a*/) {
    return empty();
  }
  /// dψ/du, m x n (dψ/du' is A).
  [[nodiscard]] virtual const Sparse& velocity_residual_jacobian(double /*t*/, ConstRef /*u*/,
                                                                 ConstRef /*v*/) {
    return empty();
  }
  /// dγ/du and dγ/du', m x n each.
  [[nodiscard]] virtual const Sparse& acceleration_bias_jacobian_u(double /*t*/, ConstRef /*u*/,
                                                                   ConstRef /*v*/) {
    return empty();
  }
  [[nodiscard]] virtual const Sparse& acceleration_bias_jacobian_v(double /*t*/, ConstRef /*u*/,
                                                                   ConstRef /*v*/) {
    return empty();
  }

  /// Total mechanical energy ½ u'ᵀ M u' + V(u) for a conservative system (time-independent
  /// loads and constraints, no damping); nothing otherwise.
  [[nodiscard]] virtual std::optional<double> energy(double /*t*/, ConstRef /*u*/, ConstRef /*v*/) {
    return std::nullopt;
  }
  /// The terms of the energy balance at one state (docs/energy.md): the potential energy V(u)
  /// (strain energy ½uᵀKu of a linear model), the power vᵀC v the damping dissipates, and the
  /// power f_ext(t)ᵀv of the applied loads, where f = f_ext − ∂V/∂u − C v. The default serves a
  /// conservative system: V = energy() − ½vᵀM v, nothing dissipated, no applied load beyond V.
  /// Nothing when the system cannot split its forces so.
  struct EnergyParts {
    double potential = 0.0, dissipation_power = 0.0, load_power = 0.0;
  };
  [[nodiscard]] virtual std::optional<EnergyParts> energy_parts(double t, ConstRef u, ConstRef v) {
    const auto e = energy(t, u, v);
    if (!e) return std::nullopt;
    return EnergyParts{*e - 0.5 * v.dot(mass(t, u) * v), 0.0, 0.0};
  }
  // NOLINTEND(performance-unnecessary-value-param)

  /// The size of the coordinates the constraint rows compute with (node positions, lengths),
  /// whose roundoff bounds what the displacements can be held to; 0 when the system has none
  /// beyond the displacements (matrix models, angles).
  [[nodiscard]] virtual double coordinate_scale() const { return 0.0; }
  /// The size of the values the position rows compute with at the start (the longest rod of a
  /// truss), whose roundoff eps times it is the rows' own (dae/formulations/model_scales.hpp,
  /// GGL's μ); 0 when the rows compute with the displacements alone.
  [[nodiscard]] virtual double row_length_scale() const { return 0.0; }

 protected:
  MechanicalSystem() = default;
  MechanicalSystem(const MechanicalSystem&) = default;  ///< for clone()
  MechanicalSystem& operator=(const MechanicalSystem&) = delete;

  static const Sparse& empty() {
    static const Sparse none;
    return none;
  }
  /// The step_reference of TimeFunction::derivative for an evaluation at t: the segment's start,
  /// or t itself outside an integration.
  [[nodiscard]] double steps_at(double t) const { return segment_start_.value_or(t); }

 private:
  std::optional<double> segment_start_;
};

/// Stores a dense block in S with every entry in the pattern (explicit zeros kept), so that the
/// pattern never depends on the values: for the small dense blocks of generalized-coordinate
/// models.
inline void store_dense(Eigen::SparseMatrix<double>& S, const Eigen::MatrixXd& D) {
  if (S.rows() != D.rows() || S.cols() != D.cols() || S.nonZeros() != D.size()) {
    std::vector<Eigen::Triplet<double>> all;
    for (Eigen::Index j = 0; j < D.cols(); ++j)
      for (Eigen::Index i = 0; i < D.rows(); ++i) all.emplace_back(i, j, 1.0);
    S.resize(D.rows(), D.cols());
    S.setFromTriplets(all.begin(), all.end());
    S.makeCompressed();
  }
  std::copy(D.data(), D.data() + D.size(), S.valuePtr());  // column-major, all entries
}

}  // namespace condyn
