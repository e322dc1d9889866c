#pragma once
/// The OutputMap of a model whose rows [solve] redundant = "drop" reduced to a subset (the
/// RowSubsetSystem's kept rows): the wrapped map reads multipliers over every row of the full
/// system, so the kept rows' multipliers are placed at their rows and the dropped rows get 0.
/// The dropped rows' forces are then carried by the kept ones: a redundant set's reactions are
/// not unique (docs/limitations.md).

#include <memory>
#include <utility>
#include <vector>

#include "models/core/output_map.hpp"

namespace condyn {

class RowSubsetOutputs final : public OutputMap {
 public:
  /// `kept`: the kept rows' indices among the wrapped map's `rows`, increasing.
  RowSubsetOutputs(std::shared_ptr<const OutputMap> wrapped, std::vector<int> kept, int rows)
      : inner_(std::move(wrapped)), kept_(std::move(kept)), rows_(rows) {}

  [[nodiscard]] const std::vector<std::string>& names(Quantity q) const override {
    return inner_->names(q);
  }
  void displacement(double t, const Vector& u, const Vector& previous, Vector& out) const override {
    inner_->displacement(t, u, previous, out);
  }
  void velocity(double t, const Vector& u, const Vector& v, Vector& out) const override {
    inner_->velocity(t, u, v, out);
  }
  void acceleration(double t, const Vector& u, const Vector& v, const Vector& a,
                    Vector& out) const override {
    inner_->acceleration(t, u, v, a, out);
  }
  void reaction(double t, const Vector& u, const Vector& lambda, Vector& out) const override {
    Vector all = Vector::Zero(rows_);
    for (std::size_t k = 0; k < kept_.size(); ++k)
      all[kept_[k]] = lambda[static_cast<Eigen::Index>(k)];
    inner_->reaction(t, u, all, out);
  }
  [[nodiscard]] std::optional<int> point(std::string_view name) const override {
    return inner_->point(name);
  }
  void point_position(int index, const Vector& u, Eigen::Ref<Vector> out) const override {
    inner_->point_position(index, u, out);
  }
  [[nodiscard]] int dimension() const override { return inner_->dimension(); }

 private:
  std::shared_ptr<const OutputMap> inner_;
  std::vector<int> kept_;
  int rows_;
};

}  // namespace condyn
