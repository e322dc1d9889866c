#pragma once
/// Results at the output times, in full DOF space, whatever the scheme.

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <memory>
#include <optional>
#include <vector>

#include "dae/formulations/acceleration.hpp"
#include "dae/integrators/step_driver.hpp"
#include "dae/run/energy_balance.hpp"
#include "models/core/constraint_drift.hpp"
#include "models/core/model.hpp"

namespace condyn {

/// Constraint drift at one internal step of the integrator (exact step values, not interpolated).
struct StepRecord {
  double t = 0.0, drift_position = 0.0, drift_velocity = 0.0;
  /// Sign changes of the fastest-reversing velocity from t0 up to this step (VelocityReversals):
  /// half of it counts the oscillations of the motion, whatever the output sampling.
  long velocity_reversals = 0;
};

/// Counts, per DOF, how often the velocity changes sign from one internal step to the next, and
/// reports the largest count. Velocities within 1e-3 of the DOF's largest |v| so far keep the
/// last sign: a velocity that chatters about zero (index3's v is out of the error test) is not
/// an oscillation.
class VelocityReversals {
 public:
  long operator()(const Eigen::Ref<const Eigen::VectorXd>& v);

 private:
  Eigen::VectorXd last_;  ///< last velocity per DOF beyond the dead band
  Eigen::VectorXd peak_;  ///< largest |v| per DOF so far
  Eigen::Matrix<long, Eigen::Dynamic, 1> count_;
  long most_ = 0;
};

/// One output row in full DOF space, as a streamed run hands it out (RunHooks::on_row).
struct TrajectoryRow {
  double t = 0.0;
  Eigen::VectorXd u, v, reaction, multiplier;
  /// u'' from the equations at this row (dae/formulations/acceleration.hpp); empty unless asked
  /// for.
  Eigen::VectorXd acceleration;
  double drift_position = 0.0, drift_velocity = 0.0;
  bool conservative = false;  ///< energy and kinetic are set
  double energy = 0.0, kinetic = 0.0;
  /// With the energies: the model's own energy scale (model_energy_scale at the first row).
  double energy_scale = 0.0;
  /// The energy balance at this row, when asked for (IntegratorOptions::energy_balance).
  std::optional<EnergyBalance> balance;
  /// Named points' global positions (a mapped row: dae/run/mapped_rows.hpp); else empty.
  Eigen::VectorXd points;
  /// Inside a passage near a singular configuration (dae/run/singular_passages.hpp): the row's
  /// reactions, multipliers and accelerations are not to be trusted.
  bool near_singular = false;
};

/// The per-row work of a trajectory: massless DOFs held by stiffness settled on their rows
/// (dae/interface/held_massless.hpp), reactions f_con = −A(t, u)ᵀλ, drifts, and for a
/// conservative model the energy and the kinetic energy; with `accelerations`, u'' from the
/// equations at the row (AccelerationFromForces). One evaluator of the model's own.
class RowAssembler {
 public:
  /// `energy_balance`: each row gets its balance, from the integrals handed to operator().
  explicit RowAssembler(const Model& model, bool accelerations = false,
                        bool energy_balance = false);
  /// `integrals`: the balance's integrals from t0 to t (EnergyTerms), when it is asked for.
  [[nodiscard]] TrajectoryRow operator()(double t, Eigen::VectorXd u, Eigen::VectorXd v,
                                         Eigen::VectorXd lambda,
                                         const Eigen::VectorXd& integrals = Eigen::VectorXd());

 private:
  const Model& model_;
  std::unique_ptr<MechanicalSystem> system_;
  ConstraintDrift drift_;
  /// Massless DOFs held by stiffness (linear models), or null: their u and v at a row are
  /// settled from their rows (HeldMassless::settle).
  std::shared_ptr<const HeldMassless> held_;
  std::optional<AccelerationFromForces> acceleration_;  ///< set when accelerations are asked for
  std::optional<bool> conservative_;                    ///< decided at the first row
  std::optional<EnergyTerms> energy_;                   ///< set when the balance is asked for
  std::optional<double> initial_energy_;                ///< T + V at the first row
  std::optional<double> energy_scale_;                  ///< model_energy_scale at the first row
};

struct Trajectory {
  std::vector<double> t;
  /// n x nt displacements and velocities; empty (no columns) for a streamed run, whose rows went
  /// to RunHooks::on_row: t, the drifts, energies and kinetic energies below stay.
  Eigen::MatrixXd u, v;
  Eigen::MatrixXd reaction;  ///< n x nt: f_con = −Aᵀλ, so M u'' + C u' + K u = f + f_con
  /// n x nt: u'' = M⁻¹(f + f_con) at each row (dae/formulations/acceleration.hpp); empty unless
  /// asked for (IntegratorOptions::accelerations) and for a streamed run.
  Eigen::MatrixXd acceleration;
  Eigen::MatrixXd multiplier;                      ///< m x nt: λ
  Eigen::VectorXd drift_position, drift_velocity;  ///< nt, max-norm constraint residuals
  /// nt total energies for a conservative model (MechanicalSystem::energy); empty otherwise.
  Eigen::VectorXd energy;
  /// nt kinetic energies ½ vᵀM v beside `energy` (the scale of its error); empty otherwise.
  Eigen::VectorXd kinetic;
  /// Beside `energy`: the model's own energy scale (model_energy_scale), so that the error of a
  /// model whose energies all stay near zero (at rest in an unstable equilibrium) is relative to
  /// something of the model's size, not to the roundoff of its energies.
  double energy_scale = 0.0;
  /// nt energy balances (IntegratorOptions::energy_balance); empty unless asked for.
  std::vector<EnergyBalance> balance;
  std::vector<StepRecord> steps;  ///< every internal step, when IntegratorOptions::record_steps
  /// Named points' global positions, (dimension × points) x nt, in a trajectory mapped to a
  /// model's OutputMap (mapped_trajectory, dae/run/mapped_rows.hpp); else empty.
  Eigen::MatrixXd points;
  /// nt flags: the rows inside a passage near a singular configuration (near_singular_rows);
  /// empty or all false for a run that watches for none (a constant constraint Jacobian).
  std::vector<bool> near_singular;
};

/// The work of the forces a model starts under over its size: ‖f(t, u, v)‖₁ · max(ℓ, ‖u‖∞), f the
/// applied forces (MechanicalSystem::force: loads, gravity, springs; or the loads alone, when
/// larger) and ℓ the system's coordinate scale (MechanicalSystem::coordinate_scale). The energy
/// the forces can exchange with the motion is of this order, whatever the potential's reference:
/// a pendulum of mass m and length L has m g L.
[[nodiscard]] double model_energy_scale(const Model& model, MechanicalSystem& system, double t,
                                        const Eigen::VectorXd& u, const Eigen::VectorXd& v);

/// The scale of energy errors: max(|E(0)|, max_t T(t), the model's energy_scale) (T the kinetic
/// energy); 0 without energies.
[[nodiscard]] double energy_error_scale(const Trajectory& traj);

/// Max-norm energy error max_t |E(t) − E(0)| relative to energy_error_scale (never zero for a
/// moving model or one under load: a model at rest in an unstable equilibrium, whose energies are
/// roundoff, is measured against its forces' work over its size). −1 without energies; NaN when
/// an energy leaves the double range (no figure can be given).
[[nodiscard]] double relative_energy_error(const Trajectory& traj);

/// What a streamed run keeps of its rows: times, drifts and energies (n-independent), gathered
/// with amortized growth as the rows come.
class RowLog {
 public:
  void add(const TrajectoryRow& row);
  /// The rows so far as a trajectory without its n x nt parts.
  [[nodiscard]] Trajectory trajectory() const;
  /// max |u| over the rows so far (0 before any).
  [[nodiscard]] double max_abs_displacement() const { return max_abs_u_; }

 private:
  std::vector<double> t_, drift_position_, drift_velocity_, energy_, kinetic_;
  std::vector<bool> near_singular_;
  double max_abs_u_ = 0.0;
  double energy_scale_ = 0.0;  ///< the rows' largest TrajectoryRow::energy_scale
  std::vector<EnergyBalance> balance_;
};

/// Row k of a trajectory that holds its rows whole, as a streamed run would have handed it out
/// (to evaluate checks on a run that kept its rows).
[[nodiscard]] TrajectoryRow row_of(const Trajectory& traj, Eigen::Index k);

/// A one-row trajectory holding the row whole (the last row of a streamed run, to score it).
[[nodiscard]] Trajectory trajectory_of(const TrajectoryRow& row);

/// Builds a trajectory from u, u' and λ at the output times: f_con = −A(t, u)ᵀλ, drifts and
/// energies from the model; with `accelerations`, u'' too; with `integrals` (one per time), the
/// energy balance (RowAssembler).
[[nodiscard]] Trajectory assemble_trajectory(const Model& model, const std::vector<double>& times,
                                             const std::vector<Eigen::VectorXd>& u,
                                             const std::vector<Eigen::VectorXd>& v,
                                             const std::vector<Eigen::VectorXd>& lambda,
                                             bool accelerations = false,
                                             const std::vector<Eigen::VectorXd>& integrals = {});

}  // namespace condyn
