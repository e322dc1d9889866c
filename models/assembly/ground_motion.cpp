// [ground_motion]: one pattern load −M r a_g(t) (scene-format.md, "Ground motion"). In
// coordinates relative to the ground, u = u_abs − r u_g, the equations M ü + C u̇ + K u = f become
// M ü + C u̇ + K u = f − M r a_g: rigid motion along r stretches no bar (K r = 0 for a truss
// direction; a matrix model's r is the user's to choose so) and is damped by no relative
// velocity. One sparse vector, built in O(nnz(M)), however many DOFs the ground moves.

#include <cmath>

#include "models/assembly/model_builder.hpp"

namespace condyn {

void ModelBuilder::add_ground_motion(std::vector<double>& total) {
  if (!spec_.ground_motion) return;
  const GroundMotionSpec& g = *spec_.ground_motion;
  const SourcePoint acceleration_at{"ground_motion.acceleration", g.where.line};
  check_time_function(g.acceleration, acceleration_at);
  const TimeFunction acceleration = acting_in_run(g.acceleration, acceleration_at);
  report_ground_records(acceleration);
  const int n = model_.dofs();
  const Eigen::VectorXd r = influence_vector();
  const Eigen::VectorXd mr = model_.M * r;
  const double bound = magnitude_bound(acceleration, spec_.solve.t_end);
  Load load{-1, acceleration, Eigen::SparseVector<double>(n)};
  for (int d = 0; d < n; ++d) {
    if (mr[d] == 0.0) continue;
    auto& sum = total[static_cast<std::size_t>(d)];
    sum += std::abs(mr[d]) * bound;
    if (!std::isfinite(sum)) {
      fail(acceleration_at, "the loads on DOF '" + model_.dof_names[static_cast<std::size_t>(d)] +
                                "' add up to more than the double range (about 1.8e308)");
    }
    load.pattern.insertBack(d) = -mr[d];
  }
  if (load.pattern.nonZeros() == 0) {
    fail(g.where, "M r is zero: the DOFs the ground moves carry no mass, so it loads nothing");
  }
  model_.loads.push_back(std::move(load));
  model_.ground = Model::Ground{r, acceleration};
}

}  // namespace condyn
