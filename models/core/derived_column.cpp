// [[derived]] columns' values (models/core/derived_column.hpp).

#include "models/core/derived_column.hpp"

#include <algorithm>
#include <stdexcept>

namespace condyn {

double derived_value(const DerivedColumn& column, const DerivedInputs& row) {
  double sum = 0.0;
  for (const DerivedTerm& term : column.terms) {
    const Eigen::Ref<const Eigen::VectorXd>* x = nullptr;
    switch (term.quantity) {
      case Quantity::displacement:
        x = &row.u;
        break;
      case Quantity::velocity:
        x = &row.v;
        break;
      case Quantity::acceleration:
        x = &row.acceleration;
        break;
      case Quantity::absolute_acceleration:
        x = &row.absolute_acceleration;
        break;
      case Quantity::reaction:
        x = &row.reaction;
        break;
      default:
        break;
    }
    if (x == nullptr || term.index >= x->size()) {
      throw std::logic_error("derived column '" + column.name + "': the row lacks its " +
                             to_string(term.quantity) + " values");
    }
    sum += term.coefficient * (*x)[term.index];
  }
  return sum;
}

bool reads_absolute_acceleration(const std::vector<DerivedColumn>& derived) {
  return std::any_of(derived.begin(), derived.end(), [](const DerivedColumn& column) {
    return std::any_of(column.terms.begin(), column.terms.end(), [](const DerivedTerm& term) {
      return term.quantity == Quantity::absolute_acceleration;
    });
  });
}

std::vector<Quantity> with_derived_quantities(std::vector<Quantity> quantities,
                                              const std::vector<DerivedColumn>& derived) {
  for (const DerivedColumn& column : derived) {
    for (const DerivedTerm& term : column.terms) {
      if (std::find(quantities.begin(), quantities.end(), term.quantity) == quantities.end()) {
        quantities.push_back(term.quantity);
      }
    }
  }
  return quantities;
}

}  // namespace condyn
