#include "src/info_report.hpp"

#include <algorithm>
#include <iomanip>

#include "dae/baumgarte_gains.hpp"
#include "dae/elimination.hpp"
#include "dae/model_scales.hpp"
#include "dae/solve.hpp"
#include "models/classification.hpp"

namespace condyn {

namespace {

std::string join_dofs(const Model& model, const std::vector<int>& dofs) {
  std::string s;
  for (int d : dofs) s += (s.empty() ? "" : ", ") + model.dof_names[static_cast<std::size_t>(d)];
  return s.empty() ? "none" : s;
}

}  // namespace

void print_info(std::ostream& out, const Model& model, Scheme requested) {
  out << "scene: " << model.file << (model.name.empty() ? "" : "  (" + model.name + ")") << "\n";
  if (!model.description.empty()) out << "model: " << model.description << "\n";
  if (!model.initial_projection.empty())
    out << "initial state: " << model.initial_projection << "\n";
  for (const auto& w : model.warnings) out << "warning: " << w << "\n";
  for (const auto& d : model.dropped_constraints)
    out << "dropped redundant constraint " << d << "\n";
  out << "\n";
  const auto classes = classify_constraints(model);
  if (classes.empty()) {
    out << "constraints: none (the model is unconstrained)\n";
  } else {
    out << "constraints (classes of the chapter's Tables 5.1-5.2):\n";
    int width = 6;
    for (const auto& c : classes) width = std::max(width, static_cast<int>(c.name.size()) + 2);
    out << "  " << std::left << std::setw(width) << "name" << std::setw(5) << "" << std::setw(34)
        << "kind" << std::setw(12) << "time" << std::setw(16) << "rhs" << std::setw(11) << "form"
        << "DOFs\n";
    for (const auto& c : classes) {
      out << "  " << std::left << std::setw(width) << c.name << std::setw(5)
          << (c.single_freedom ? "SFC" : "MFC") << std::setw(34) << c.holonomy() << std::setw(12)
          << (c.rheonomic ? "rheonomic" : "scleronomic") << std::setw(16)
          << (c.homogeneous ? "homogeneous" : "nonhomogeneous") << std::setw(11)
          << (c.linear ? "linear" : "nonlinear");
      for (std::size_t k = 0; k < c.dofs.size(); ++k) out << (k ? ", " : "") << c.dofs[k];
      out << "\n";
      if (!c.note.empty())
        out << "  " << std::setw(width) << ""
            << "  " << c.note << "\n";
    }
    const bool integrable_velocity_rows =
        std::any_of(model.constraints.begin(), model.constraints.end(), [](const Constraint& c) {
          return c.level == ConstraintSpec::Level::velocity && !c.nonholonomic;
        });
    if (integrable_velocity_rows) {
      out << "  (linear velocity-level constraints are classed by their integrated form a·u = "
             "a·u(0) + ∫h)\n";
    }
  }
  const int n = model.dofs(), m = model.constraint_count();
  out << "\nmodel: "
      << (model.is_nonlinear() ? "nonlinear (matrices: linearization at t = 0), " : "") << n
      << " DOFs, " << m << " constraints; nonzeros M " << model.M.nonZeros() << ", C "
      << model.C.nonZeros() << ", K " << model.K.nonZeros() << ", A " << model.A.nonZeros() << "\n";
  const SchemeChoice choice = choose_scheme(model, requested);
  const auto refusal = scheme_refusal(model, choice.scheme);
  out << "scheme: " << to_string(choice.scheme) << " (" << choice.reason
      << (refusal ? "; not applicable to this scene, see below" : "") << ")\n";
  if (choice.scheme == Scheme::elimination && !refusal) {
    const ReducedSystem reduced = reduce(model);
    const auto& ms = reduced.transform;
    out << "elimination: slaves " << join_dofs(model, ms.slaves) << "; masters "
        << join_dofs(model, ms.masters) << " (slaves "
        << (model.solve.slaves.empty() ? "chosen by column pivoting on A"
                                       : "named in [solve] slaves")
        << ")\n";
  }
  if (choice.scheme == Scheme::baumgarte)
    out << "baumgarte: " << baumgarte_gains(model).rule << "\n";
  out << "tolerances: rtol " << model.solve.rtol << "; " << absolute_tolerances(model).rule << "\n";
  out << "\nsystem each scheme integrates:\n";
  out << "  " << std::left << std::setw(13) << "scheme" << std::setw(10) << "unknowns"
      << "Jacobian nonzeros\n";
  for (Scheme s : kSchemes) {
    out << "  " << std::left << std::setw(13) << to_string(s);
    try {
      const SystemSize size = system_size(model, s);
      out << std::setw(10) << size.unknowns << size.jacobian_nonzeros;
    } catch (const std::exception& e) {
      out << "not applicable: " << e.what();
    }
    out << (s == choice.scheme ? "   <- selected" : "") << "\n";
  }
}

}  // namespace condyn
