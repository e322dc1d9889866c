// A user's own checks, evaluated on rows as they are computed (validation/studies/user_checks.hpp).

#include "validation/studies/user_checks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "dae/run/singular_passages.hpp"
#include "dae/run/solve.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/number_cell.hpp"
#include "models/scene/scene_parser.hpp"

namespace condyn {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Each figure exact (a check's verdict compares doubles: 6 digits showed "max |x| = 1, bound 1"
/// for a FAIL of 1 against 0.9999999).
std::string fmt(double v) { return shortest_number(v); }

/// What a check's figure is held against: its bound (max_abs) or its tolerance.
double bound_of(const CheckSpec& c) {
  return c.form == CheckSpec::Form::max_abs ? c.bound : c.tolerance;
}

SourcePoint quantity_key(const CheckSpec& c) { return {c.where.path + ".quantity", c.where.line}; }

}  // namespace

CheckEvaluator::CheckEvaluator(const Model& model, const std::vector<CheckSpec>& checks,
                               const std::string& file)
    : model_(&model), checks_(checks) {
  for (const auto& c : checks_) {
    const auto column = find_column(model, c.quantity);
    if (!column)
      throw SceneError(scene_message(file, quantity_key(c),
                                     unknown_column(model, c.quantity, all_columns(model))));
    // As [output] quantities refuses absolute_acceleration without a moving ground.
    if (column->quantity == Quantity::absolute_acceleration && !model.ground) {
      throw SceneError(scene_message(
          file, quantity_key(c),
          "'" + c.quantity +
              "' needs [ground_motion]: without a moving ground the absolute acceleration is the "
              "acceleration (check acc_" +
              c.quantity.substr(8) + ")"));
    }
    State s;
    s.column = *column;
    if (s.column.point >= 0) {
      // Its place among the points the mapped rows carry (dimension() values per point).
      const auto it = std::find(points_.begin(), points_.end(), s.column.point);
      const auto place = static_cast<int>(it - points_.begin());
      if (it == points_.end()) points_.push_back(s.column.point);
      s.column.index += place * model.outputs->dimension();
    }
    states_.push_back(s);
  }
  if (model.outputs) mapper_.emplace(*model.outputs, points_, reads_reactions(quantities()));
}

std::vector<Quantity> CheckEvaluator::quantities() const {
  std::vector<Quantity> out;
  std::vector<DerivedColumn> derived;  // the derived columns the checks read
  for (const auto& s : states_) {
    if (s.column.derived >= 0) {
      derived.push_back(model_->derived[static_cast<std::size_t>(s.column.derived)]);
    } else if (std::find(out.begin(), out.end(), s.column.quantity) == out.end()) {
      out.push_back(s.column.quantity);
    }
  }
  return with_derived_quantities(out, derived);
}

double CheckEvaluator::value(const TrajectoryRow& row, const CheckColumn& c) const {
  const auto at = [&](const Eigen::VectorXd& x) { return c.index < x.size() ? x[c.index] : kNaN; };
  if (c.point >= 0) return at(row.points);
  if (c.derived >= 0) {
    return model_->derived_values(row.t, row.u, row.v, row.acceleration, row.reaction)[c.derived];
  }
  switch (c.quantity) {
    case Quantity::displacement:
      return at(row.u);
    case Quantity::velocity:
      return at(row.v);
    case Quantity::acceleration:
      return at(row.acceleration);
    case Quantity::absolute_acceleration:
      if (c.index >= row.acceleration.size()) return kNaN;
      return model_->absolute_acceleration(row.t, row.acceleration)[c.index];
    case Quantity::reaction:
      return at(row.reaction);
    case Quantity::multiplier:
      return at(row.multiplier);
    case Quantity::drift:
      return c.index == 0 ? row.drift_position : row.drift_velocity;
    case Quantity::energy:
      if (!row.balance) return kNaN;
      return energy_column(*row.balance, static_cast<std::size_t>(c.index));
  }
  return kNaN;
}

void CheckEvaluator::add(const TrajectoryRow& run_row) {
  const TrajectoryRow* mapped = &run_row;
  if (mapper_) {
    mapped_ = run_row;
    mapper_->map(mapped_);
    mapped = &mapped_;
  }
  const TrajectoryRow& row = *mapped;
  for (std::size_t k = 0; k < checks_.size(); ++k) {
    const CheckSpec& c = checks_[k];
    State& s = states_[k];
    const double v = value(row, s.column);
    switch (c.form) {
      case CheckSpec::Form::at_value:
        // `at` is an output time (read_checks.cpp): the row nearest to it is that row.
        if (!s.seen || std::abs(row.t - c.at) < s.distance) {
          s.distance = std::abs(row.t - c.at);
          s.figure = v;
          s.seen = true;
        }
        break;
      case CheckSpec::Form::max_abs:
        // A NaN makes the figure NaN for good (the check then fails).
        s.figure = (std::isnan(v) || std::isnan(s.figure)) ? kNaN : std::max(s.figure, std::abs(v));
        s.seen = true;
        break;
      case CheckSpec::Form::reference: {
        const auto& ref = *c.reference;
        // Reference rows up to this row's time, interpolated linearly between the last row and
        // this one (or this row's value at its own time).
        while (s.next < ref.times.size() && ref.times[s.next] <= row.t + 1e-12 * std::abs(row.t)) {
          const double tr = ref.times[s.next];
          double computed = v;
          if (s.has_previous && row.t > s.previous_t && tr < row.t) {
            computed = s.previous_value +
                       (v - s.previous_value) * (tr - s.previous_t) / (row.t - s.previous_t);
          }
          const double diff = std::abs(computed - ref.values[s.next]);
          s.figure = (std::isnan(diff) || std::isnan(s.figure)) ? kNaN : std::max(s.figure, diff);
          s.seen = true;
          ++s.next;
        }
        s.previous_t = row.t;
        s.previous_value = v;
        s.has_previous = true;
        break;
      }
    }
  }
}

std::vector<CheckOutcome> CheckEvaluator::outcomes() const {
  std::vector<CheckOutcome> out;
  for (std::size_t k = 0; k < checks_.size(); ++k) {
    const CheckSpec& c = checks_[k];
    const State& s = states_[k];
    CheckOutcome o;
    o.quantity = c.quantity;
    o.form = c.form;
    o.computed = s.seen ? s.figure : kNaN;
    o.bound = bound_of(c);
    std::string text;
    switch (c.form) {
      case CheckSpec::Form::at_value: {
        const double computed = o.computed;
        o.computed = std::abs(computed - c.value);
        text = c.quantity + " at t = " + fmt(c.at) + ": " + fmt(computed) + ", expected " +
               fmt(c.value) + " +- " + fmt(c.tolerance) + " (off by " + fmt(o.computed) + ")";
        break;
      }
      case CheckSpec::Form::max_abs:
        text = "max |" + c.quantity + "| = " + fmt(o.computed) + ", bound " + fmt(c.bound);
        break;
      case CheckSpec::Form::reference: {
        const std::size_t rows = c.reference->times.size();
        text = "max |" + c.quantity + " - reference| over " + std::to_string(rows) + " rows of " +
               c.reference->file + " = " + fmt(o.computed) + ", tolerance " + fmt(c.tolerance);
        if (s.next < rows) text += " (" + std::to_string(rows - s.next) + " rows not reached)";
        break;
      }
    }
    // NaN compares false: a check whose figure could not be formed fails.
    o.passed = o.computed <= o.bound &&
               (c.form != CheckSpec::Form::reference || s.next == c.reference->times.size());
    if (std::isnan(o.computed)) text += " (no finite value: the run wrote NaN or never reached it)";
    o.text = std::move(text);
    out.push_back(std::move(o));
  }
  return out;
}

std::vector<CheckOutcome> unevaluated_outcomes(const std::vector<CheckSpec>& checks) {
  std::vector<CheckOutcome> out;
  for (const CheckSpec& c : checks) {
    CheckOutcome o;
    o.quantity = c.quantity;
    o.form = c.form;
    o.computed = kNaN;
    o.bound = bound_of(c);
    o.passed = false;
    o.text = "not evaluated: the run failed before t_end";
    out.push_back(std::move(o));
  }
  return out;
}

bool SceneCheckResult::passed() const {
  return failure.empty() && drift.empty() &&
         std::all_of(outcomes.begin(), outcomes.end(),
                     [](const CheckOutcome& o) { return o.passed; });
}

SceneCheckResult run_scene_checks(const std::string& path, const SceneCheckOptions& options) {
  return run_scene_checks(parse_scene_file(path, SceneNeeds{.checks = true}), options);
}

namespace {

void add_once(std::vector<Quantity>& quantities, Quantity q) {
  if (std::find(quantities.begin(), quantities.end(), q) == quantities.end()) {
    quantities.push_back(q);
  }
}

}  // namespace

void add_check_quantities(SceneSpec& spec) {
  // energy and energy_error are the energy quantity's whatever the model: asked for before the
  // build, which refuses it where it has no meaning.
  for (const auto& c : spec.checks) {
    for (const auto column : kEnergyColumns) {
      if (c.quantity == column) add_once(spec.output.quantities, Quantity::energy);
    }
  }
}

std::vector<Quantity> with_check_quantities(std::vector<Quantity> quantities,
                                            const CheckEvaluator& evaluator) {
  for (Quantity q : evaluator.quantities()) add_once(quantities, q);
  return quantities;
}

SceneCheckResult check_verdict(const std::string& file, const SolveSpec& settings,
                               const SolveResult& result, const CheckEvaluator& evaluator,
                               std::vector<std::string> warnings) {
  SceneCheckResult out;
  out.scene = file;
  out.warnings = std::move(warnings);
  // A run that left its mechanism's branch passes or fails its checks as computed; the warning
  // stands beside the verdicts (and in the JUnit report's system-err), as in `run`.
  for (auto& w : singular_passage_warnings(result.summary.singular_passages)) {
    out.warnings.push_back(std::move(w));
  }
  out.scheme = to_string(result.scheme);
  out.steps = result.summary.steps;
  out.wall_s = result.summary.wall_seconds;
  if (!result.ok()) {
    out.failure = std::string(to_string(result.failure->kind)) + ": " + result.failure->message;
    return out;
  }
  out.outcomes = evaluator.outcomes();
  if (const auto drift = result.summary.drift_warning(settings.rtol, settings.atol)) {
    out.drift = drift->substr(drift->find(' ') + 1);  // without its "warning: "
  }
  return out;
}

SceneCheckResult run_scene_checks(SceneSpec spec, const SceneCheckOptions& options) {
  if (spec.checks.empty()) {
    throw SceneError(no_checks_message(spec.file));
  }
  std::string set_aside;  // SolveSpec::override_scheme's note, if any
  if (options.scheme) set_aside = spec.solve.override_scheme(*options.scheme, options.scheme_where);
  if (options.step) spec.solve.step = *options.step;
  // The settings with the overrides, checked together as run checks them: a Newmark-family
  // scheme without a step, a step beyond t_end are bad input (exit 2), not a failed run.
  try {
    spec.solve.validate();
  } catch (const std::invalid_argument& e) {
    throw SceneError(spec.file + ": " + e.what());
  }
  add_check_quantities(spec);
  BuildReport report;
  const Model model = build_model(spec, report);
  if (!set_aside.empty()) report.warnings.insert(report.warnings.begin(), set_aside);
  CheckEvaluator evaluator(model, spec.checks, spec.file);
  RunHooks hooks = hooks_for(with_check_quantities(spec.output.quantities, evaluator));
  hooks.on_row = [&evaluator](const TrajectoryRow& row) { evaluator.add(row); };
  const SolveResult result = solve(model, spec.solve, hooks);
  return check_verdict(spec.file, spec.solve, result, evaluator, std::move(report.warnings));
}

}  // namespace condyn
