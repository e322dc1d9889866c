#include "dae/formulations/scheme_run.hpp"

namespace condyn {

Observation::FullState full_state_prefix(int n) {
  return [n](double, const Eigen::VectorXd& y) {
    return std::make_pair(Eigen::VectorXd(y.head(n)), Eigen::VectorXd(y.segment(n, n)));
  };
}

}  // namespace condyn
