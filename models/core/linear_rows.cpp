#include "models/core/linear_rows.hpp"

#include <algorithm>

namespace condyn {

LinearRows::LinearRows(std::vector<Constraint> rows) : rows_(std::move(rows)) {
  for (const auto& c : rows_) {
    position_.push_back(c.level == ConstraintLevel::position);
    has_rhs_.push_back(!c.value.is_zero());
  }
}

int LinearRows::rows_with_time_functions() const {
  return static_cast<int>(std::count(has_rhs_.begin(), has_rhs_.end(), true));
}

double LinearRows::rhs(std::size_t i, int order, double t) const {
  return has_rhs_[i] ? rows_[i].value.derivative(order, t) : 0.0;
}

void LinearRows::position_residual(double t, const ConstRef& u, Ref phi) const {
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    double au = 0.0;
    if (position_[i]) {
      for (const auto& [d, a] : rows_[i].coefficients) au += a * u[d];
      au -= rhs(i, 0, t);
    }
    phi[static_cast<Eigen::Index>(i)] = au;
  }
}

void LinearRows::velocity_residual(double t, const ConstRef& v, Ref psi) const {
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    double av = 0.0;
    for (const auto& [d, a] : rows_[i].coefficients) av += a * v[d];
    psi[static_cast<Eigen::Index>(i)] = av - rhs(i, position_[i] ? 1 : 0, t);
  }
}

void LinearRows::acceleration_bias(double t, Ref gamma) const {
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    gamma[static_cast<Eigen::Index>(i)] = rhs(i, position_[i] ? 2 : 1, t);
  }
}

void LinearRows::append_triplets(int row0, std::vector<Eigen::Triplet<double>>& out) const {
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    for (const auto& [d, a] : rows_[i].coefficients) {
      out.emplace_back(row0 + static_cast<int>(i), d, a);
    }
  }
}

}  // namespace condyn
