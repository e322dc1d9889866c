#pragma once
/// The energy balance of a run (docs/energy.md): for M u'' = f_ext(t) − ∂V/∂u − C u' + f_con,
///
///   T(t) + V(t) + D(t) − W_loads(t) − W_constraints(t) = T(0) + V(0),
///
/// with T = ½u'ᵀM u', V the potential (strain) energy, D = ∫ u'ᵀC u' dt the energy dissipated by
/// damping, W_loads = ∫ f_extᵀu' dt the work of the applied loads (ground motion's −M r a_g
/// included: relative motion) and W_constraints = ∫ f_conᵀu' dt that of the constraint forces
/// (prescribed motion; zero for fixed, ideal constraints). The integrals are taken by the
/// integration loop over every internal step (IntegratorOptions::integrand), the rest at the row.

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "models/core/mechanical_system.hpp"
#include "models/core/model.hpp"
#include "models/core/output_quantity.hpp"

namespace condyn {

struct EnergyBalance {
  double kinetic = 0.0, potential = 0.0;  ///< T and V at the row
  double dissipated = 0.0;                ///< D from t0
  double work_loads = 0.0;                ///< W_loads from t0
  double work_constraints = 0.0;          ///< W_constraints from t0
  double initial = 0.0;                   ///< T + V at t0
  [[nodiscard]] double energy() const { return kinetic + potential; }
  /// What the balance misses: T + V + D − W_loads − W_constraints − (T + V)(t0).
  [[nodiscard]] double error() const {
    return energy() + dissipated - work_loads - work_constraints - initial;
  }
};

/// kEnergyColumns as strings (HDF5's energy_columns dataset).
[[nodiscard]] std::vector<std::string> energy_column_names();

/// Column k of kEnergyColumns (models/core/output_quantity.hpp) of a balance.
[[nodiscard]] double energy_column(const EnergyBalance& b, std::size_t k);

/// The balance's integrands and terms, on an evaluator of the model's own.
class EnergyTerms {
 public:
  /// Integrals a row needs (IntegratorOptions::integrand_size): D, W_loads, W_constraints.
  static constexpr int kIntegrals = 3;

  explicit EnergyTerms(const Model& model);
  /// u'ᵀC u', f_extᵀu', f_conᵀu' at (t, u, u') with multipliers λ (f_con = −Aᵀλ).
  [[nodiscard]] Eigen::VectorXd powers(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                       const Eigen::VectorXd& lambda);
  /// The integrals' gain over a jump du of the state at t (a load step; u the state after it):
  /// the loads' work f_ext(t+)ᵀdu, nothing dissipated or done by the constraints (a jump keeps
  /// them: it is between two consistent states).
  [[nodiscard]] Eigen::VectorXd jump_work(double t, const Eigen::VectorXd& u,
                                          const Eigen::VectorXd& du);
  /// The balance at a row: T and V here, the integrals as given (kIntegrals of them); `initial`
  /// is left to the caller (T + V of the first row).
  [[nodiscard]] EnergyBalance at(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                 const Eigen::VectorXd& integrals);

 private:
  const Model& model_;
  std::unique_ptr<MechanicalSystem> system_;
};

}  // namespace condyn
