#pragma once
/// A DAE F(t, y, y') = 0 as the integrator sees it. Implementations: the reduced ODE of the
/// elimination path (dae/formulations/reduced_ode.hpp) and, later, the multiplier formulations.

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "dae/interface/unknown_kind.hpp"
#include "dae/linsolve/block_jacobian.hpp"
#include "dae/linsolve/newton_system.hpp"

namespace condyn {

class DaeProblem {
 public:
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;

  virtual ~DaeProblem() = default;

  /// Number of unknowns in y.
  [[nodiscard]] virtual int size() const = 0;
  /// The integration segment starting at t0 begins (at the start of the run and at every load
  /// step, before make_consistent): load steps with start <= t0 are on until the next call, so no
  /// step switches on inside a segment.
  virtual void begin_segment(double t0) = 0;
  /// r = F(t, y, y') in the current segment.
  virtual void residual(double t, ConstRef y, ConstRef yp, Ref r) const = 0;
  /// Sparsity pattern of dF/dy + cj dF/dy' (column-major, compressed), fixed for the whole run.
  [[nodiscard]] virtual const JacobianPattern& jacobian_pattern() const = 0;
  /// Fills the values of J = dF/dy + cj dF/dy' in the pattern (J views exactly that pattern).
  virtual void fill_jacobian(double t, ConstRef y, ConstRef yp, double cj, JacobianMap J) const = 0;
  /// fill_jacobian on a matrix that has the pattern (jacobian_pattern().matrix()).
  void jacobian(double t, const ConstRef& y, const ConstRef& yp, double cj,
                Eigen::SparseMatrix<double>& J) const {
    fill_jacobian(t, y, yp, cj, map_of(J));
  }
  /// 1 for differential components, 0 for algebraic ones (IDASetId).
  [[nodiscard]] virtual Eigen::VectorXd differential_id() const = 0;
  /// The differentiation index of each component: 1 for ordinary differential and index-1
  /// algebraic components; 2 for GGL's and index2's multipliers and index3's velocities; 3 for
  /// index3's multipliers. Components of index k >= 2 are left out of the local error test (the
  /// BDF error estimate does not apply to them) and their error weights in the Newton
  /// convergence test are scaled by (h/T)^(k−1), T the model's time scale (so that the factor is a
  /// pure number), as RADAU5 scales higher-index components by h^(k−1).
  /// Unscaled, the Newton matrix's conditioning (1/h² for index 2) makes their roundoff exceed any
  /// tolerance at small steps and the step size collapses (seen under GGL on chapter case E at
  /// rtol <= 1e-9); with zero weight, IDA's modified Newton never converges them (GGL's μ grew
  /// 2x per step between Jacobian updates, to 4e4 where it is 0). Empty means all 1.
  [[nodiscard]] virtual Eigen::VectorXd variable_index() const { return {}; }
  /// true: the algebraic components (differential_id 0) are left out of the local error test
  /// even when they are of index 1 (IDASetSuppressAlg), for algebraic variables whose error
  /// estimate amplifies the differential ones' (Baumgarte's λ, see MultiplierDae).
  [[nodiscard]] virtual bool suppress_algebraic_error() const { return false; }
  /// true: IDA may keep a Newton matrix factored at an earlier cj while cj stays in its band
  /// (dae/integrators/ida_integrator.cpp), the condensed one included, and widen the band on
  /// large systems. Only where every unknown is differential and in the error test, which then
  /// catches what a stale matrix leaves, and nothing read from the unknowns amplifies it: not
  /// index1's λ, out of the tests (it drifted to 1e19 on the chapter truss), nor penalty's
  /// reactions w φ(u), the Newton tolerance times the weight.
  [[nodiscard]] virtual bool reuses_newton_matrix() const { return false; }
  /// The kind of each unknown, for its absolute tolerance (IntegratorOptions::atol_of); empty:
  /// every unknown gets the displacement atol.
  [[nodiscard]] virtual std::vector<UnknownKind> unknown_kinds() const { return {}; }
  /// Per unknown, a floor under |y_i| in its error weight 1/(rtol max(|y_i|, floor_i) + atol_i),
  /// written into `floor` (resized to size()); false (and `floor` untouched): none. Read by the
  /// weights of higher-index problems (variable_index) at every step once a run is trapped,
  /// failing the error test at every step (dae/integrators/ida_integrator.cpp). Schemes that
  /// project onto constraint rows (GGL, index3) hand a DOF a share of the other DOFs' local errors
  /// in each row; a DOF near 0 beside large ones cannot be held to its own rtol·|y_i| + atol
  /// (MultiplierDae::error_scale_floors).
  virtual bool error_scale_floors(double /*t*/, const ConstRef& /*y*/,
                                  Eigen::VectorXd& /*floor*/) const {
    return false;
  }
  /// Per unknown, the largest |coefficient| at (t, y) of the constraint row a multiplier or μ
  /// belongs to, 0 for the other unknowns (IntegratorOptions::atol_vector); empty: no such row.
  [[nodiscard]] virtual Eigen::VectorXd multiplier_row_scales(double /*t*/,
                                                              const Eigen::VectorXd& /*y*/) const {
    return {};
  }
  /// Per unknown, the lightest positive diagonal mass among the DOFs the constraint row of a
  /// multiplier touches at (t, y), 0 for the other unknowns and for rows over massless DOFs alone
  /// (IntegratorOptions::atol_vector); empty: no such row.
  [[nodiscard]] virtual Eigen::VectorXd multiplier_row_masses(double /*t*/,
                                                              const Eigen::VectorXd& /*y*/) const {
    return {};
  }
  /// Its own solver of IDA's Newton systems (∂F/∂y + cj ∂F/∂y') x = b, or nothing: IDA then
  /// factors the Jacobian jacobian() fills.
  [[nodiscard]] virtual std::unique_ptr<NewtonSystem> newton_system() const { return nullptr; }
  /// For each equation, whether it is algebraic (no y') and its Newton corrections from a stale
  /// matrix are to satisfy it exactly (dae/integrators/stale_correction.hpp); empty: none.
  [[nodiscard]] virtual std::vector<bool> algebraic_equations() const { return {}; }
  /// Makes (y, y') consistent at time t, where the segment begins (begin_segment(t)): keeps the
  /// differential components of y, recomputes the algebraic ones and y' (used at t = 0 and after
  /// every load step, where accelerations and multipliers jump). Throws std::runtime_error when the
  /// consistency system is singular.
  virtual void make_consistent(double t, Eigen::VectorXd& y, Eigen::VectorXd& yp) const = 0;
  /// At a restart (a breakpoint, before make_consistent): the velocities in y moved onto the
  /// velocity rows at t, where a drive's table changed its rate (Model::breakpoints). Nothing by
  /// default.
  virtual void jump_velocities(double /*t*/, Eigen::VectorXd& /*y*/) const {}
};

}  // namespace condyn
