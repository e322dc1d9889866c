#pragma once
/// Built-in benchmark models with published reference solutions (../shared/reference/
/// external-benchmarks.md): Andrews' squeezing mechanism and the car axis from the Test Set for
/// IVP Solvers (Mazzia, Magherini, Iavernaro, release 2.4, 2008), and the pendulum of period 2.
/// A scene selects one with [model] type = "andrews" | "car_axis" | "pendulum".

#include "models/core/benchmark_model.hpp"

namespace condyn {

[[nodiscard]] BenchmarkModel make_andrews();
[[nodiscard]] BenchmarkModel make_car_axis();
[[nodiscard]] BenchmarkModel make_pendulum();

}  // namespace condyn
