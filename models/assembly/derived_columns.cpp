// [[derived]] columns resolved against the built model (models/core/derived_column.hpp): each
// term's column found by its name as the CSV writes it, a term on an earlier derived column
// expanded into that column's terms; names that are no column, or a column of another kind, an
// absolute acceleration without [ground_motion], and derived names that are already a column are
// refused here, before any run.

#include <cmath>
#include <string_view>

#include "models/assembly/model_builder.hpp"
#include "models/core/result_columns.hpp"

namespace condyn {

namespace {

/// What kind of column `c` is, for a refusal ("a multiplier column").
std::string kind_of(const ResultColumn& c) {
  if (c.derived >= 0) return "a derived column";
  if (c.point >= 0) return "a named point's position column";
  switch (c.quantity) {
    case Quantity::displacement:
      return "a displacement column";
    case Quantity::velocity:
      return "a velocity column";
    case Quantity::acceleration:
      return "an acceleration column";
    case Quantity::absolute_acceleration:
      return "an absolute acceleration column";
    case Quantity::reaction:
      return "a reaction column";
    case Quantity::multiplier:
      return "a multiplier column";
    case Quantity::drift:
      return "a drift column";
    case Quantity::energy:
      return "an energy column";
  }
  return "a column";
}

/// Why a column of this kind is not a term, or "" when it is one.
std::string not_a_term(const ResultColumn& c) {
  if (c.point >= 0) {
    return ": a term names a displacement, velocity, acceleration or reaction column (a named "
           "point's position is not one of them: name the body's pose columns)";
  }
  switch (c.quantity) {
    case Quantity::displacement:
    case Quantity::velocity:
    case Quantity::acceleration:
    case Quantity::absolute_acceleration:  // build_derived refuses it without a moving ground
    case Quantity::reaction:
      return "";
    default:
      return ": a term names a displacement, velocity, acceleration or reaction column";
  }
}

}  // namespace

void ModelBuilder::build_derived() {
  for (const DerivedSpec& spec : spec_.derived) {
    const std::string who = "derived column '" + spec.name + "'";
    // A name the run already writes would make two columns of one name (or shadow a check's).
    if (const auto taken = find_column(model_, spec.name); taken || spec.name == "t") {
      fail({spec.where.path + ".name", spec.where.line},
           who + ": the name is already " + (taken ? kind_of(*taken) : "the time column") +
               " of the run (a derived column needs a name of its own)");
    }
    DerivedColumn column{spec.name, {}};
    for (const DerivedSpec::Term& term : spec.terms) {
      const SourcePoint key{spec.where.path + ".terms." + term.column,
                            term.line > 0 ? term.line : spec.where.line};
      // After the name's own check: a term on the name is the column itself only when the
      // name is no other column's.
      if (term.column == spec.name) fail(key, who + ": a column cannot be a term of itself");
      const auto found = find_column(model_, term.column);
      if (!found) fail(key, who + ": " + unknown_column(model_, term.column, all_columns(model_)));
      if (found->derived >= 0) {  // an earlier derived column (the parser refused later ones)
        for (DerivedTerm t : model_.derived[static_cast<std::size_t>(found->derived)].terms) {
          t.coefficient *= term.coefficient;
          if (!std::isfinite(t.coefficient)) {
            fail(key, who + ": " + fmt(term.coefficient) + " times the coefficients of '" +
                          term.column + "' overflows the double range");
          }
          column.terms.push_back(t);
        }
        continue;
      }
      if (const std::string why = not_a_term(*found); !why.empty()) {
        fail(key, who + ": '" + term.column + "' is " + kind_of(*found) + why);
      }
      // As [output] quantities and [[check]] refuse absolute_acceleration without a moving
      // ground: there is no r a_g(t) to add, and no acc_abs_ column.
      if (found->quantity == Quantity::absolute_acceleration && !model_.ground) {
        fail(key, who + ": '" + term.column +
                      "' needs [ground_motion]: without a moving ground the absolute "
                      "acceleration is the acceleration (name acc_" +
                      term.column.substr(std::string_view("acc_abs_").size()) + ")");
      }
      column.terms.push_back({found->quantity, found->index, term.coefficient});
    }
    model_.derived.push_back(std::move(column));
  }
}

}  // namespace condyn
