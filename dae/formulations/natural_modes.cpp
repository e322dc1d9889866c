// The constrained model's natural modes (natural_modes.hpp): elimination's reduction, the
// pencil's modes, the shapes expanded and the participating masses under ground motion.

#include "dae/formulations/natural_modes.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "dae/formulations/reduced_system.hpp"

namespace condyn {

namespace {

void refuse_nonlinear(const Model& model) {
  if (model.is_nonlinear()) {
    throw ModesUnavailable(
        ModesUnavailable::Why::nonlinear,
        "natural modes need a linear model: this one is nonlinear (large displacements, rigid "
        "members, a mechanism or a built-in model), whose small oscillations depend on its "
        "state and its constraint forces, which condyn does not linearize");
  }
}

}  // namespace

NaturalModes natural_modes(const Model& model, std::optional<int> asked, ModeSolver solver) {
  refuse_nonlinear(model);
  const ReducedSystem reduced = reduce(model);
  const Eigen::SparseMatrix<double>& T = reduced.transform.T;
  NaturalModes out;
  out.available = mode_count(reduced.M);
  if (out.available == 0)
    throw ModesUnavailable(ModesUnavailable::Why::no_mass,
                           "the model has no mass: it has no natural modes");
  const int count = asked.value_or(std::min(kDefaultModeCount, out.available));
  if (count < 1 || count > out.available) {
    const int massless = static_cast<int>(reduced.M.cols()) - out.available;
    throw ModeCountError(
        "must be from 1 to the number of modes of the constrained model, " +
        std::to_string(out.available) + " (" + std::to_string(model.dofs()) + " DOFs, " +
        std::to_string(model.constraint_count()) + " constraints" +
        (massless > 0 ? ", " + std::to_string(massless) + " motions without mass" : "") +
        "); got " + std::to_string(count));
  }
  const PencilModes modes = lowest_modes(reduced.K, reduced.M, count, solver);
  out.dense = modes.dense;
  out.omega = modes.omega2.cwiseSqrt();
  out.shapes = T * modes.shapes;
  for (Eigen::Index j = 0; j < out.shapes.cols(); ++j) {  // the full shape's largest entry > 0
    Eigen::Index at = 0;
    out.shapes.col(j).cwiseAbs().maxCoeff(&at);
    if (out.shapes(at, j) < 0.0) out.shapes.col(j) *= -1.0;
  }
  if (model.ground) {
    const Eigen::VectorXd Mr = model.M * model.ground->r;
    out.total_mass = mass_along(reduced.M, T.transpose() * Mr);
    if (!(out.total_mass > 0.0)) {
      throw ModesUnavailable(
          ModesUnavailable::Why::no_participation,
          "the influence vector moves no mass the constraints let move: no mode participates");
    }
    const Eigen::VectorXd gamma = out.shapes.transpose() * Mr;
    out.mass_ratio = gamma.cwiseAbs2() / out.total_mass;
    out.mass_ratio_cumulative = out.mass_ratio;
    for (Eigen::Index j = 1; j < count; ++j)
      out.mass_ratio_cumulative[j] += out.mass_ratio_cumulative[j - 1];
  }
  return out;
}

}  // namespace condyn
