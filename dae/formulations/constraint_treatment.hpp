#pragma once
/// The lightest treatment per constraint (the chapter's point: each class of constraint has its
/// cheapest method), for the mixed formulation (dae/formulations/eliminated_system.hpp):
///
/// - a single-freedom row (u_i = g(t)) is eliminated directly: it only removes an unknown;
/// - a group of linear multi-freedom rows (rows coupled through shared DOFs) is eliminated by
///   master-slave when its transform stays sparse: each slave s is replaced by |T_s| masters in
///   every equation that holds it, which adds about deg(s) (|T_s| − 1) nonzeros to the reduced
///   matrices (deg(s): the nonzeros of column s of M, C or K, the largest); multipliers add the
///   group's nonzeros of A instead. The group is eliminated when the first is at most the second;
/// - everything else keeps a multiplier: nonlinear rows, nonholonomic rows, and groups too large
///   for the transform's dense block per group (models/core/master_slave.hpp) or for its
///   dense work (rows² × DOFs beyond 1e8: the joint rows of a long chain of bodies).
///
/// Groups are decided on their own, so the cost of the choice follows the groups, not m x n.

#include <string>
#include <vector>

#include "models/core/master_slave.hpp"
#include "models/core/model.hpp"

namespace condyn {

struct ConstraintTreatment {
  /// Why a row got its treatment.
  enum class Reason {
    single_freedom,   ///< eliminated: u_i = g(t)
    sparse_group,     ///< eliminated by master-slave: the transform adds no more than A holds
    fills_in,         ///< multipliers: master-slave would add more nonzeros than the group's A
    group_too_large,  ///< multipliers: beyond the transform's dense block or work per group
    nonlinear,        ///< multipliers: the row depends nonlinearly on the state
    nonholonomic,     ///< multipliers: a velocity row with no displacement form
  };
  std::vector<int> eliminated, kept;  ///< constraint rows, ascending
  std::vector<Reason> reason;         ///< per constraint row
  /// The fill estimate against A's nonzeros, per constraint row of a multi-freedom group (the
  /// group's figures; 0 elsewhere).
  std::vector<long> fill, group_nonzeros;
  /// u = T q + G g_e(t) over the eliminated rows (G: n x eliminated.size(), in their order).
  MasterSlave transform;
};

[[nodiscard]] bool is_eliminated(ConstraintTreatment::Reason r);
/// A few words for `info`: "eliminated (single-freedom)", "multipliers (nonlinear)".
[[nodiscard]] std::string describe(ConstraintTreatment::Reason r);

/// Decides every row's treatment and builds the transform of the eliminated ones (slaves by
/// column pivoting, group by group).
[[nodiscard]] ConstraintTreatment treat_constraints(const Model& model);

/// What `info` prints: counts per reason, and the rows that keep multipliers (at most `limit`
/// named).
[[nodiscard]] std::string treatment_report(const Model& model, const ConstraintTreatment& t,
                                           std::size_t limit = 12);

}  // namespace condyn
