// A system with some of another's constraint rows (models/systems/row_subset_system.hpp).

#include "models/systems/row_subset_system.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace condyn {

RowSubsetSystem::RowSubsetSystem(const MechanicalSystem& wrapped, std::vector<int> kept)
    : inner_(wrapped.clone()) {
  const int m = inner_->constraints();
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (kept[k] < 0 || kept[k] >= m || (k > 0 && kept[k] <= kept[k - 1])) {
      throw std::invalid_argument(
          "RowSubsetSystem: the kept rows must increase strictly within [0, " + std::to_string(m) +
          "); entry " + std::to_string(k) + " is " + std::to_string(kept[k]));
    }
  }
  auto rows = std::make_shared<Rows>();
  rows->new_row.assign(static_cast<std::size_t>(m), -1);
  const auto& position = inner_->position_rows();
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const auto row = static_cast<std::size_t>(kept[k]);
    rows->new_row[row] = static_cast<int>(k);
    rows->position.push_back(position[row]);
  }
  rows->kept = std::move(kept);
  rows_ = std::move(rows);
  all_rows_.setZero(m);
}

RowSubsetSystem::RowSubsetSystem(const RowSubsetSystem& other)
    : MechanicalSystem(other),
      rows_(other.rows_),
      inner_(other.inner_->clone()),
      all_rows_(other.all_rows_) {}

MechanicalSystem& RowSubsetSystem::inner(double t) {
  // The wrapped evaluator's own segment is this one's: steps_at(t) is its start, or t outside
  // an integration, where a step is on when start <= t either way.
  inner_->begin_segment(steps_at(t));
  return *inner_;
}

void RowSubsetSystem::select(Ref out) const {
  const auto& kept = rows_->kept;
  for (std::size_t k = 0; k < kept.size(); ++k)
    out[static_cast<Eigen::Index>(k)] = all_rows_[kept[k]];
}

void RowSubsetSystem::RowSelection::plan(const Rows& rows, const Sparse& block) {
  starts_.assign(block.outerIndexPtr(), block.outerIndexPtr() + block.outerSize() + 1);
  indices_.assign(block.innerIndexPtr(), block.innerIndexPtr() + block.nonZeros());
  std::vector<Eigen::Triplet<double>> pattern;
  for (Eigen::Index j = 0; j < block.outerSize(); ++j) {
    for (Sparse::InnerIterator it(block, j); it; ++it) {
      const int row = rows.new_row[static_cast<std::size_t>(it.row())];
      if (row >= 0) pattern.emplace_back(row, static_cast<int>(j), 1.0);
    }
  }
  result_.resize(static_cast<Eigen::Index>(rows.kept.size()), block.cols());
  result_.setFromTriplets(pattern.begin(), pattern.end());
  result_.makeCompressed();
  // Each kept entry's place in the result (whose rows are sorted within a column), found by
  // search: nothing assumed of the order of the block's own entries.
  source_.assign(static_cast<std::size_t>(result_.nonZeros()), 0);
  const Sparse::StorageIndex* result_rows = result_.innerIndexPtr();
  for (Eigen::Index j = 0; j < block.outerSize(); ++j) {
    for (Sparse::InnerIterator it(block, j); it; ++it) {
      const int row = rows.new_row[static_cast<std::size_t>(it.row())];
      if (row < 0) continue;
      const Sparse::StorageIndex* place = std::lower_bound(
          result_rows + result_.outerIndexPtr()[j], result_rows + result_.outerIndexPtr()[j + 1],
          static_cast<Sparse::StorageIndex>(row));
      source_[static_cast<std::size_t>(place - result_rows)] =
          static_cast<Eigen::Index>(&it.value() - block.valuePtr());
    }
  }
}

const RowSubsetSystem::Sparse& RowSubsetSystem::RowSelection::operator()(const Rows& rows,
                                                                         const Sparse& block) {
  // Compressed storage is what the pattern comparison and the value copy read.
  Sparse compressed;
  const Sparse* b = &block;
  if (!block.isCompressed()) {
    compressed = block;
    compressed.makeCompressed();
    b = &compressed;
  }
  const bool same = static_cast<Eigen::Index>(indices_.size()) == b->nonZeros() &&
                    static_cast<Eigen::Index>(starts_.size()) == b->outerSize() + 1 &&
                    std::equal(starts_.begin(), starts_.end(), b->outerIndexPtr()) &&
                    std::equal(indices_.begin(), indices_.end(), b->innerIndexPtr());
  if (!same) plan(rows, *b);
  double* values = result_.valuePtr();
  for (std::size_t k = 0; k < source_.size(); ++k) values[k] = b->valuePtr()[source_[k]];
  return result_;
}

const RowSubsetSystem::Sparse& RowSubsetSystem::mass(double t, ConstRef u) {
  return inner(t).mass(t, u);
}

void RowSubsetSystem::force(double t, ConstRef u, ConstRef v, Ref f) { inner(t).force(t, u, v, f); }

const RowSubsetSystem::Sparse& RowSubsetSystem::stiffness(double t, ConstRef u, ConstRef v) {
  return inner(t).stiffness(t, u, v);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::damping(double t, ConstRef u, ConstRef v) {
  return inner(t).damping(t, u, v);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::constraint_jacobian(double t, ConstRef u) {
  return a_(*rows_, inner(t).constraint_jacobian(t, u));
}

void RowSubsetSystem::position_residual(double t, ConstRef u, Ref phi) {
  inner(t).position_residual(t, u, all_rows_);
  select(phi);
}

void RowSubsetSystem::velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) {
  inner(t).velocity_residual(t, u, v, all_rows_);
  select(psi);
}

void RowSubsetSystem::acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) {
  inner(t).acceleration_bias(t, u, v, all_rows_);
  select(gamma);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::mass_jacobian(double t, ConstRef u, ConstRef a) {
  return inner(t).mass_jacobian(t, u, a);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::constraint_force_jacobian(double t, ConstRef u,
                                                                          ConstRef w) {
  // A_Kᵀ w = Aᵀ w_full with the dropped rows' multipliers 0.
  all_rows_.setZero();
  const auto& kept = rows_->kept;
  for (std::size_t k = 0; k < kept.size(); ++k)
    all_rows_[kept[k]] = w[static_cast<Eigen::Index>(k)];
  return inner(t).constraint_force_jacobian(t, u, all_rows_);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::constraint_product_jacobian(double t, ConstRef u,
                                                                            ConstRef a) {
  const Sparse& j = inner(t).constraint_product_jacobian(t, u, a);
  return j.size() == 0 ? empty() : product_jacobian_(*rows_, j);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::velocity_residual_jacobian(double t, ConstRef u,
                                                                           ConstRef v) {
  const Sparse& j = inner(t).velocity_residual_jacobian(t, u, v);
  return j.size() == 0 ? empty() : velocity_jacobian_(*rows_, j);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::acceleration_bias_jacobian_u(double t, ConstRef u,
                                                                             ConstRef v) {
  const Sparse& j = inner(t).acceleration_bias_jacobian_u(t, u, v);
  return j.size() == 0 ? empty() : bias_jacobian_u_(*rows_, j);
}

const RowSubsetSystem::Sparse& RowSubsetSystem::acceleration_bias_jacobian_v(double t, ConstRef u,
                                                                             ConstRef v) {
  const Sparse& j = inner(t).acceleration_bias_jacobian_v(t, u, v);
  return j.size() == 0 ? empty() : bias_jacobian_v_(*rows_, j);
}

std::optional<double> RowSubsetSystem::energy(double t, ConstRef u, ConstRef v) {
  return inner(t).energy(t, u, v);
}

std::optional<MechanicalSystem::EnergyParts> RowSubsetSystem::energy_parts(double t, ConstRef u,
                                                                           ConstRef v) {
  return inner(t).energy_parts(t, u, v);
}

}  // namespace condyn
