#pragma once
/// One passage of a run near a singular configuration, as the run's summary carries it
/// (dae/run/singular_passages.hpp measures it).

namespace condyn {

/// One passage: the internal steps at which the rows' conditioning stayed below kNearSingular
/// times the best conditioning of the run's earlier steps.
struct SingularPassage {
  /// Below this fraction of the best conditioning the run has had so far a configuration is near
  /// singular: on the parallelogram four-bar σ is about half the crank's angle from the collinear
  /// position in radians (0.05 of its best: under 0.1 rad, some 6°), and λ's sensitivity to the
  /// state's error is then more than 400 times what it was. Relative, because a long chain's rows
  /// are ill-conditioned in any configuration (σ about π/(2N) for N links in a line: 5e-4 at
  /// 3,000 links) without being near a change of rank.
  static constexpr double kNearSingular = 0.05;
  /// Above this share of the motion's kinetic energy forbidden after the passage, the run left
  /// the branch it was on. The motion before is extrapolated to the step after the passage from
  /// the two steps before it, so a smooth passage keeps nearly all of it (below 0.07 on the
  /// parallelogram and N-four-bar scenes under GGL, projection, index1 and index2 from rtol 1e-3
  /// to 1e-8), where a change of branch loses sin² of the angle between the branches (0.5 to 1
  /// there).
  static constexpr double kBranchShare = 0.25;
  double t_enter = 0.0;  ///< the first step below kNearSingular times the best so far
  double t_leave = 0.0;  ///< the first step back above it (left_open: the run ended inside)
  bool left_open = false;
  double t_closest = 0.0;  ///< the step of the smallest conditioning
  double closest = 1.0;    ///< that smallest conditioning, σ_min of the scaled rows (0: singular)
  /// The share of the kinetic energy of the motion just before the passage that the
  /// configuration just after it does not allow (0: the same free motions; −1: not judged, the
  /// run ended inside or the mechanism was at rest).
  double branch_change = -1.0;
  [[nodiscard]] bool left_branch() const { return branch_change > kBranchShare; }
};

}  // namespace condyn
