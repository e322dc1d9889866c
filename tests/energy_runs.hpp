#pragma once
// The runs that test the energy balance share (tests/dae/test_energy_balance.cpp and its
// validation-tier cases, test_energy_balance_validation.cpp): a scene's text with the runs'
// [solve] and [output] tables, its balances row by row (streamed or assembled), and a run's
// largest balance error with its scale.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "dae/run/solve.hpp"
#include "dae/run/trajectory.hpp"
#include "models/assembly/build_model.hpp"
#include "models/scene/scene_parser.hpp"
#include "tests/solve_helpers.hpp"

namespace condyn::test::energy {

inline std::string scene(const std::string& model_and_loads, const std::string& solve_extra = "") {
  return model_and_loads + "[solve]\nt_end = 3.0\noutput_step = 0.1\nrtol = 1e-10\natol = 1e-12\n" +
         solve_extra + "[output]\nquantities = [\"displacement\", \"energy\"]\n";
}

/// The run's balances (streamed or assembled, as `streamed` says) and its times.
struct Balances {
  std::vector<double> t;
  std::vector<EnergyBalance> b;
};

inline Balances balances(const std::string& text, Scheme scheme, bool streamed) {
  const SceneSpec spec = parse_scene_text(text, "energy.toml");
  const Model model = build_model(spec);
  RunHooks hooks = hooks_for(spec.output.quantities);
  REQUIRE(hooks.energy_balance);
  Balances out;
  if (streamed) {
    hooks.on_row = [&out](const TrajectoryRow& row) {
      REQUIRE(row.balance.has_value());
      out.t.push_back(row.t);
      out.b.push_back(*row.balance);
    };
  }
  const SolveResult r = test::solved(model, test::under(spec.solve, scheme), hooks);
  if (!streamed) {
    out.t = r.trajectory.t;
    out.b = r.trajectory.balance;
  }
  REQUIRE(out.b.size() == out.t.size());
  return out;
}

/// The largest balance error of a run, and the largest of its terms (the scale).
inline std::pair<double, double> worst(const Balances& run) {
  double error = 0.0, scale = 0.0;
  for (const auto& b : run.b) {
    error = std::max(error, std::abs(b.error()));
    for (double x : {b.kinetic, b.potential, b.dissipated, b.work_loads, b.work_constraints})
      scale = std::max(scale, std::abs(x));
  }
  return {error, scale};
}

/// The largest balance error of `model`'s run at rtol 1e-6, the loose run a tight one (scene()'s
/// rtol 1e-10) is compared with.
inline double loose_error(const std::string& model, Scheme scheme, bool streamed) {
  std::string loose = scene(model);
  loose.replace(loose.find("rtol = 1e-10"), 12, "rtol = 1e-6");
  return worst(balances(loose, scheme, streamed)).first;
}

}  // namespace condyn::test::energy
