#include "src/reports/info_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iterator>
#include <map>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "dae/formulations/baumgarte_gains.hpp"
#include "dae/formulations/constraint_treatment.hpp"
#include "dae/formulations/model_scales.hpp"
#include "dae/formulations/partitioned_ode.hpp"
#include "dae/formulations/reduced_ode.hpp"
#include "dae/formulations/reduced_system.hpp"
#include "dae/run/factorization_choice.hpp"
#include "dae/run/scheme_memory.hpp"
#include "dae/run/solve.hpp"
#include "models/core/classification.hpp"
#include "models/core/load_library.hpp"
#include "models/core/number_cell.hpp"
#include "models/core/result_columns.hpp"
#include "src/reports/wrapped_lines.hpp"

namespace condyn {

namespace {

/// Up to this many constraints the table lists each; beyond, the first kShortenedConstraints
/// and a count per class (10⁴ ties of a 10⁶-DOF lattice are not read row by row).
constexpr std::size_t kMaxListedConstraints = 60;
constexpr std::size_t kShortenedConstraints = 40;

/// The loads and their time functions (the first kMaxListedLoads; a table as
/// table(FILE:COLUMN, N samples)*scale), and the ground motion's acceleration.
void print_loads(std::ostream& out, const Model& model) {
  constexpr std::size_t kMaxListedLoads = 10;
  if (model.ground) {
    out << wrapped_text("ground motion: ", "a_g(t) = " + model.ground->acceleration.describe() +
                                               " (its load −M r a_g(t) is among the loads)");
  }
  if (model.loads.empty()) return;
  out << "loads: " << model.loads.size() << "\n";
  for (std::size_t i = 0; i < std::min(model.loads.size(), kMaxListedLoads); ++i) {
    const Load& load = model.loads[i];
    const std::string target =
        load.dof >= 0 ? model.dof_names[static_cast<std::size_t>(load.dof)]
                      : "pattern (" + std::to_string(load.pattern.nonZeros()) + " DOFs)";
    out << wrapped_text("  " + target + ": ", load.value.describe());
  }
  if (model.loads.size() > kMaxListedLoads) {
    out << "  ... and " << model.loads.size() - kMaxListedLoads << " more\n";
  }
}

/// "0.333 u2 - 0.333 u1": a [[derived]] column's terms (those on other derived columns expanded,
/// as the builder resolved them).
std::string derived_formula(const Model& model, const DerivedColumn& column) {
  std::ostringstream s;
  s.precision(6);
  for (std::size_t k = 0; k < column.terms.size(); ++k) {
    const DerivedTerm& term = column.terms[k];
    const double c = term.coefficient;
    if (k > 0) s << (c < 0.0 ? " - " : " + ");
    if (k == 0 && c < 0.0) s << "-";
    if (std::abs(c) != 1.0) s << std::abs(c) << " ";
    s << column_name(model, term.quantity, term.index);
  }
  return s.str();
}

/// The [[derived]] columns and their formulas (the first kMaxListed).
void print_derived(std::ostream& out, const Model& model) {
  constexpr std::size_t kMaxListed = 10;
  if (model.derived.empty()) return;
  out << "derived columns: " << model.derived.size() << "\n";
  for (std::size_t i = 0; i < std::min(model.derived.size(), kMaxListed); ++i) {
    const DerivedColumn& column = model.derived[i];
    out << wrapped_text("  " + column.name + " = ", derived_formula(model, column));
  }
  if (model.derived.size() > kMaxListed) {
    out << "  ... and " << model.derived.size() - kMaxListed << " more\n";
  }
}

std::vector<std::string> names_of(const Model& model, const std::vector<int>& dofs) {
  std::vector<std::string> out;
  out.reserve(dofs.size());
  for (int d : dofs) out.push_back(model.dof_names[static_cast<std::size_t>(d)]);
  return out;
}

/// A constraint's DOFs in its table row: the first few, then counted.
std::string short_list(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 8;
  std::string s;
  for (std::size_t k = 0; k < names.size() && k < kShown; ++k) s += (k ? ", " : "") + names[k];
  if (names.size() > kShown) s += " ... and " + std::to_string(names.size() - kShown) + " more";
  return s;
}

/// The selected scheme's memory estimate against the machine's available memory.
void print_memory(std::ostream& out, const std::optional<MemoryEstimate>& selected) {
  if (!selected) return;
  const std::optional<double> available = available_memory_bytes();
  out << wrapped_text(
      "memory: ", "about " + format_bytes(selected->bytes) + " to integrate under the selected " +
                      "scheme (at least " + format_bytes(selected->lower_bound) + "; " +
                      factor_name(*selected) + " predicted at " +
                      shortest_number(selected->factor_entries) + " entries)" +
                      (available ? ", " + format_bytes(*available) + " available" : std::string()));
  // What `run` would warn of before starting (check_run_memory), said here before a run is tried.
  if (!available) return;
  if (const auto warning = memory_warning(*selected, "the selected scheme", *available))
    out << wrapped_text("warning: ", *warning);
}

/// The scene, its description, and what building the model noted and warned of.
void print_build_notes(std::ostream& out, const Model& model, const BuildReport& report) {
  out << wrapped_text("scene: ", model.file + (model.name.empty() ? "" : " (" + model.name + ")"));
  if (!model.description.empty()) out << wrapped_text("model: ", model.description);
  // One line per DOF the projection moved: printed as it is.
  if (!report.initial_projection.empty())
    out << "initial state: " << report.initial_projection << "\n";
  for (const auto& w : report.warnings) out << wrapped_text("warning: ", w);
  for (const auto& d : report.dropped_constraints)
    out << "dropped redundant constraint " << d << "\n";
  if (!report.damping.empty()) out << wrapped_text("damping: ", report.damping);
  if (!report.massless_dofs.empty()) out << wrapped_text("massless DOFs: ", report.massless_dofs);
  for (const auto& r : report.ground_records) out << wrapped_text("ground motion record: ", r);
  for (const auto& j : report.joints) out << wrapped_text("joint: ", j);
}

/// The table of constraint classes: every row, or above kMaxListedConstraints (unless
/// `every_constraint`) the first kShortenedConstraints and a count per class.
void print_constraints(std::ostream& out, const Model& model, const SolveSpec& settings,
                       bool every_constraint) {
  const auto classes = classify_constraints(model, settings.t_end);
  if (classes.empty()) {
    out << "constraints: none (the model is unconstrained)\n";
    return;
  }
  out << "constraints (classes of the chapter's Tables 5.1-5.2):\n";
  // A large model's table is its first rows and a count per class, unless every row is asked.
  const bool shortened = !every_constraint && classes.size() > kMaxListedConstraints;
  const std::size_t listed = shortened ? kShortenedConstraints : classes.size();
  int width = 6;
  for (std::size_t i = 0; i < listed; ++i) {
    width = std::max(width, static_cast<int>(classes[i].name.size()) + 2);
  }
  // The kind column as wide as its longest entry ("pseudo-nonholonomic (integrable)" is 32).
  int kind_width = 6;
  for (const auto& c : classes) {
    kind_width = std::max(kind_width, static_cast<int>(c.holonomy().size()) + 2);
  }
  const auto class_columns = [kind_width](std::ostream& o, const ConstraintClass& c) {
    o << std::setw(5) << (c.single_freedom ? "SFC" : "MFC") << std::setw(kind_width) << c.holonomy()
      << std::setw(12) << (c.rheonomic ? "rheonomic" : "scleronomic") << std::setw(16)
      << (c.homogeneous ? "homogeneous" : "nonhomogeneous") << std::setw(11)
      << (c.linear ? "linear" : "nonlinear");
  };
  out << "  " << std::left << std::setw(width) << "name" << std::setw(5) << ""
      << std::setw(kind_width) << "kind" << std::setw(12) << "time" << std::setw(16) << "rhs"
      << std::setw(11) << "form"
      << "DOFs\n";
  for (std::size_t i = 0; i < listed; ++i) {
    const ConstraintClass& c = classes[i];
    std::ostringstream row;
    row << "  " << std::left << std::setw(width) << c.name;
    class_columns(row, c);
    out << wrapped_text(row.str(), short_list(c.dofs));
    if (!c.note.empty()) {
      out << wrapped_text(std::string(static_cast<std::size_t>(width) + 4, ' '), c.note);
    }
  }
  if (shortened) {
    out << "  ... and " << classes.size() - listed << " more (" << classes.size()
        << " in all; info --all-constraints lists every one); count per class:\n";
    std::map<std::string, std::size_t> count;
    for (const auto& c : classes) {
      std::ostringstream key;
      key << std::left;
      class_columns(key, c);
      std::string text = key.str();
      text.erase(text.find_last_not_of(' ') + 1);
      ++count[text];
    }
    for (const auto& [key, number] : count) {
      out << "  " << std::left << std::setw(width) << number << key << "\n";
    }
  }
  const bool integrable_velocity_rows = std::any_of(
      model.constraints.begin(), model.constraints.end(),
      [](const Constraint& c) { return c.level == ConstraintLevel::velocity && !c.nonholonomic; });
  if (integrable_velocity_rows) {
    out << "  (linear velocity-level constraints are classed by their integrated form a·u = "
           "a·u(0) + ∫h)\n";
  }
}

/// Coordinate partitioning's choice at the start (dae/formulations/partitioned_ode.hpp).
void print_partition(std::ostream& out, const Model& model) {
  const PartitionedOde ode(model, 0.0);
  const CoordinatePartition& p = ode.partition();
  out << "elimination: coordinate partitioning, " << p.independent.size()
      << (p.independent.size() == 1 ? " independent coordinate (" : " independent coordinates (")
      << "chosen by column pivoting on A(0, u0); re-partitioned where they stop determining the "
         "configuration well), "
      << p.dependent.size() << " dependent, solved by Newton at every evaluation\n"
      << wrapped_list("  independent: ", names_of(model, p.independent))
      << wrapped_list("  dependent: ", names_of(model, p.dependent));
}

/// Elimination sized once, before the choice is printed: its row in the table of schemes (the
/// plan has made auto's fallback to GGL when the reduction cannot be integrated).
struct EliminationSizing {
  std::optional<SystemSize> size;
  std::string refused;
};

EliminationSizing size_elimination(const Model& model, const SolveSpec& settings,
                                   SchemeDecisions& decisions) {
  EliminationSizing elimination;
  SolveSpec as_elimination = settings;
  as_elimination.scheme = Scheme::elimination;
  as_elimination.treatment = SolveSpec::Treatment::multipliers;
  try {
    if (!scheme_refusal(model, Scheme::elimination)) {
      elimination.size = decisions.size(as_elimination);
    }
  } catch (const std::exception& e) {
    elimination.refused = e.what();
  }
  return elimination;
}

/// The table of the system each scheme integrates (unknowns, Jacobian nonzeros, memory), the
/// chosen one marked; returns the chosen one's memory estimate, when it could be sized.
std::optional<MemoryEstimate> print_scheme_table(std::ostream& out, const Model& model,
                                                 const SolveSpec& settings,
                                                 SchemeDecisions& decisions,
                                                 const SchemeChoice& choice, bool chose_mixed,
                                                 const EliminationSizing& elimination,
                                                 const FactorizationChoice& factorization) {
  // Each scheme pure (a multiplier per row), and each multiplier scheme mixed as well; a scheme
  // of fixed step (the Newmark family, rattle) when it is the one chosen (they are not in the
  // default list).
  std::vector<Scheme> schemes(std::begin(kSchemes), std::end(kSchemes));
  if (fixed_step(choice.scheme)) schemes.push_back(choice.scheme);
  const auto shown = [&](Scheme s, bool mixed) {
    return !mixed || (mixes(s) && model.constraint_count() > 0);
  };
  const auto row_name = [&](Scheme s, bool mixed) {
    std::string name = std::string(to_string(s)) + (mixed ? " mixed" : "");
    if (newmark_family(s) &&
        settings.newmark_family.constraints == NewmarkConstraints::stabilized) {
      name += " stabilized";  // [u; v; λ; μ]: dae/integrators/stabilized_newmark_newton.hpp
    }
    return name;
  };
  // The first column as wide as its longest name and a space ("generalized_alpha stabilized").
  std::size_t width = 17;
  for (Scheme s : schemes) {
    for (const bool mixed : {false, true}) {
      if (shown(s, mixed)) width = std::max(width, row_name(s, mixed).size() + 1);
    }
  }
  out << "\nsystem each scheme integrates:\n";
  out << "  " << std::left << std::setw(static_cast<int>(width)) << "scheme" << std::setw(10)
      << "unknowns" << std::setw(19) << "Jacobian nonzeros"
      << "memory\n";
  SchemeMemory scheme_memory(model);
  std::optional<MemoryEstimate> selected;
  for (Scheme s : schemes) {
    for (const bool mixed : {false, true}) {
      if (!shown(s, mixed)) continue;
      std::string name = row_name(s, mixed);
      name.resize(width, ' ');
      out << "  " << name;
      const char* marker = s == choice.scheme && mixed == chose_mixed ? "   <- selected" : "";
      try {
        SolveSpec as_scheme = settings;
        as_scheme.scheme = s;
        as_scheme.treatment =
            mixed ? SolveSpec::Treatment::mixed : SolveSpec::Treatment::multipliers;
        if (s == Scheme::elimination && !elimination.refused.empty()) {
          throw std::invalid_argument(elimination.refused);
        }
        const SystemSize size = s == Scheme::elimination && elimination.size
                                    ? *elimination.size
                                    : decisions.size(as_scheme);
        // The selected scheme's factor is the run's: CHOLMOD's when the plan chose it.
        const MemoryEstimate estimate =
            scheme_memory(size, *marker != '\0' ? factorization : FactorizationChoice{});
        if (*marker != '\0') selected = estimate;
        out << std::setw(10) << size.unknowns << std::setw(19) << size.jacobian_nonzeros
            << format_bytes(estimate.bytes) << marker << "\n";
      } catch (const std::exception& e) {
        // Out of memory while building it says nothing of the scheme's applicability.
        const bool memory = dynamic_cast<const std::bad_alloc*>(&e) != nullptr;
        // Continuation lines indented under the reason; the marker ends the first line.
        std::string wrapped =
            wrapped_text("  " + name + (memory ? "not sized: " : "not applicable: "),
                         memory ? "out of memory while building its system (the run would need "
                                  "more than this process may have)"
                                : e.what())
                .substr(2 + name.size());
        wrapped.insert(wrapped.find('\n'), marker);
        out << wrapped;
      }
    }
  }
  return selected;
}

/// The factorization a run would use and why; where the run's condensed Newton matrix is
/// symmetric positive definite and the choice did not analyse it (KLU named, or the full
/// Jacobian), also what each factorization of that matrix would take.
void print_factorization(std::ostream& out, const RunPlan& run_plan) {
  if (run_plan.refusal) return;
  std::string text = run_plan.factorization.reason;
  const bool analysed =
      text.find("KLU (amd)") != std::string::npos || run_plan.factorization.cholmod_unavailable;
  const auto newton = analysed ? nullptr : symmetric_newton_system(run_plan);
  if (const auto* matrix = newton ? newton->symmetric_matrix() : nullptr) {
    text += "; its condensed matrix K + cj C + cj^2 M (symmetric positive definite): ";
    try {
      text += analyse_factorizations(*matrix).describe();
    } catch (const LibraryUnavailable& e) {
      text += e.what();
    }
  }
  out << wrapped_text("factorization: ", text);
  if (const auto warning = factorization_time_warning(run_plan.factorization))
    out << wrapped_text("warning: ", *warning);
}

}  // namespace

void print_info(std::ostream& out, const Model& model, const BuildReport& report,
                const SolveSpec& settings, bool every_constraint) {
  print_build_notes(out, model, report);
  out << "\n";
  print_constraints(out, model, settings, every_constraint);
  const int n = model.dofs(), m = model.constraint_count();
  std::ostringstream model_size;
  model_size << (model.is_nonlinear() ? "nonlinear (matrices: linearization at t = 0), " : "") << n
             << " DOFs, " << m << (m == 1 ? " constraint" : " constraints") << "; nonzeros M "
             << model.M.nonZeros() << ", C " << model.C.nonZeros() << ", K " << model.K->nonZeros()
             << ", A " << model.A.nonZeros();
  out << "\n" << wrapped_text("model: ", model_size.str());
  print_loads(out, model);
  print_derived(out, model);
  // The plan a run would make, from the decisions `info` sizes every scheme with (the treatment,
  // the reduction: each made once).
  SchemeDecisions decisions(model);
  RunPlan run_plan = plan(model, settings, decisions);
  const EliminationSizing elimination = size_elimination(model, settings, decisions);
  const SchemeChoice choice{run_plan.scheme, run_plan.reason};
  const auto refusal = scheme_refusal(model, choice.scheme);
  out << "scheme: " << to_string(choice.scheme) << " (" << choice.reason
      << (refusal ? "; not applicable to this scene, see below" : "") << ")\n";
  if (choice.scheme == Scheme::elimination && !refusal && !run_plan.refusal &&
      model.is_nonlinear()) {
    print_partition(out, model);
  } else if (choice.scheme == Scheme::elimination && !refusal) {
    const ReducedSystem& reduced = *decisions.reduced(settings.slaves);
    const auto& ms = reduced.transform;
    out << "elimination: " << ms.slaves.size() << (ms.slaves.size() == 1 ? " slave (" : " slaves (")
        << (settings.slaves.empty() ? "chosen by column pivoting on A" : "named in [solve] slaves")
        << "), " << ms.masters.size() << (ms.masters.size() == 1 ? " master\n" : " masters\n")
        << wrapped_list("  slaves: ", names_of(model, ms.slaves))
        << wrapped_list("  masters: ", names_of(model, ms.masters));
  }
  print_factorization(out, run_plan);
  // Elimination is sized already: the other schemes' peak without it.
  decisions.release_reduced();
  run_plan.reduced.reset();
  run_plan.reduced_ode.reset();
  const bool chose_mixed = run_plan.mixed();
  if (chose_mixed && !refusal) {
    out << "constraint treatment (mixed): " << treatment_report(model, *run_plan.treatment);
  }
  if (choice.scheme == Scheme::baumgarte) out << wrapped_text("baumgarte: ", run_plan.gains.rule);
  if (fixed_step(choice.scheme)) {
    // The family's parameters and fixed step, as the run's summary notes them (run_plan.cpp).
    const std::string prefix = std::string(to_string(choice.scheme)) + ": ";
    for (const RunNote& note : run_plan.notes) {
      if (note.kind == RunNote::Kind::scheme_setting && note.text.starts_with(prefix))
        out << wrapped_text(prefix, note.text.substr(prefix.size()));
    }
  }
  std::ostringstream rtol;
  rtol << "rtol " << settings.rtol << "; ";
  out << wrapped_text("tolerances: ", rtol.str() + run_plan.tolerances.rule);
  print_memory(out, print_scheme_table(out, model, settings, decisions, choice, chose_mixed,
                                       elimination, run_plan.factorization));
}

}  // namespace condyn
