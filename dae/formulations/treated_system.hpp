#pragma once
/// The system a scheme with a multiplier per kept row integrates (the multiplier schemes and the
/// Newmark family): the model's own, or under the mixed treatment the system with its cheap
/// linear rows eliminated (dae/formulations/eliminated_system.hpp); and how that system's state
/// is observed: u and u' in full space, every row's λ.

#include <Eigen/Dense>
#include <functional>
#include <optional>

#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/eliminated_system.hpp"
#include "dae/formulations/row_multipliers.hpp"
#include "dae/formulations/scheme_run.hpp"
#include "models/core/model.hpp"

namespace condyn {

class TreatedSystem {
 public:
  /// `mixed`: the rows to eliminate (null, or none eliminated: the model's own system).
  TreatedSystem(const Model& model, const ConstraintTreatment* mixed);
  TreatedSystem(const TreatedSystem&) = delete;
  TreatedSystem& operator=(const TreatedSystem&) = delete;
  ~TreatedSystem() = default;

  /// The system integrated.
  [[nodiscard]] const MechanicalSystem& system() const;
  /// Whether rows were eliminated.
  [[nodiscard]] bool mixed() const { return reduced_.has_value(); }
  /// The model's u0 or v0 in the integrated system's coordinates.
  [[nodiscard]] Eigen::VectorXd initial(const Eigen::VectorXd& x) const;

  /// The kept rows' λ in a state y.
  using KeptMultipliers = std::function<Eigen::VectorXd(const Eigen::VectorXd& y)>;
  /// Sets observe.full_state and observe.multipliers for a state y = [u; v; ...] of the integrated
  /// system (y' = [u'; u''; ...]) whose kept rows' λ is `lambda(y)`: under the mixed treatment u
  /// and u' are expanded and the eliminated rows' λ follow from the full equations. With
  /// `row_multipliers` observe.row_multipliers too (observe_row_multipliers). This object must
  /// outlive the run.
  void observe(const KeptMultipliers& lambda, bool row_multipliers, Observation& observe);

 private:
  const Model& model_;
  std::optional<EliminatedSystem> reduced_, observer_;  ///< the observer: its own evaluator
  std::optional<AccelerationLevelMultipliers> at_rows_;
};

}  // namespace condyn
