#include "validation/references/chapter_report.hpp"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "dae/formulations/reduced_system.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/eigen_decompositions.hpp"
#include "models/scene/scene_parser.hpp"
#include "validation/references/embedded_scenes.hpp"

namespace condyn {

namespace {

/// Entry (i, j) of a printed row-major matrix.
double printed_at(const PrintedMatrix& p, int i, int j) {
  return p.values[static_cast<std::size_t>(i) * static_cast<std::size_t>(p.cols) +
                  static_cast<std::size_t>(j)];
}

// The chapter prints integers (EA = 200√2 enters only through 200√2/(10√2) = 20); 1e-9 relative
// absorbs the 15-digit √2 in the scene and nothing else.
constexpr double kPrintedTolerance = 1e-9;

/// A chapter case's model and the slaves its scene names for the master-slave transformation.
struct CaseModel {
  Model model;
  std::vector<std::string> slaves;
};

CaseModel case_model(const std::string& scene, const std::vector<double>* masses = nullptr) {
  SceneSpec spec = parse_scene_text(embedded_scene(scene).text, "<embedded:" + scene + ">");
  if (masses != nullptr) spec.model.masses = *masses;
  return {build_model(spec), spec.solve.slaves};
}

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& m, const std::vector<int>& rows) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), m.cols());
  for (std::size_t k = 0; k < rows.size(); ++k)
    out.row(static_cast<Eigen::Index>(k)) = m.row(rows[k]);
  return out;
}

Eigen::MatrixXd computed(ChapterQuantity q, const Model& model, const ReducedSystem& r) {
  Eigen::MatrixXd T(r.transform.T);  // not const: returned by value below
  const Eigen::MatrixXd G(r.transform.G), M(model.M), K(*model.K);
  const auto& S = r.transform.slaves;
  switch (q) {
    case ChapterQuantity::struck_mass:
      return M * T;
    case ChapterQuantity::struck_stiffness:
      return K * T;
    case ChapterQuantity::transform:
      return T;
    case ChapterQuantity::reduced_mass:
      return Eigen::MatrixXd(r.M);
    case ChapterQuantity::reduced_stiffness:
      return Eigen::MatrixXd(r.K);
    case ChapterQuantity::reduced_loads: {
      // The chapter's loads are steps: evaluated where every one of them is on.
      const auto steps = model.breakpoints(std::numeric_limits<double>::infinity());
      return T.transpose() * model.applied_forces(steps.empty() ? 0.0 : steps.back());
    }
    case ChapterQuantity::reduced_transfer_g:
      return Eigen::MatrixXd(r.FK);
    case ChapterQuantity::reduced_transfer_gdd:
      return Eigen::MatrixXd(r.FM);
    case ChapterQuantity::transfer_g:
      return -K * G;
    case ChapterQuantity::transfer_gdd:
      return -M * G;
    case ChapterQuantity::recovery_stiffness:
      return rows_of(K * T, S);
    case ChapterQuantity::recovery_g:
      return rows_of(K * G, S);
    case ChapterQuantity::recovery_gdd:
      return rows_of(M * G, S);
  }
  return {};
}

MatrixComparison compare(const PrintedMatrix& p, const Eigen::MatrixXd& c) {
  MatrixComparison out{p, c, {}};
  if (c.rows() != p.rows || c.cols() != p.cols) {
    out.differing.emplace_back(-1, -1);  // shape mismatch: flagged as a whole
    return out;
  }
  const double scale = std::max(c.cwiseAbs().maxCoeff(), 1.0);
  for (int i = 0; i < p.rows; ++i) {
    for (int j = 0; j < p.cols; ++j) {
      const double printed = printed_at(p, i, j);
      if (std::abs(printed - c(i, j)) > kPrintedTolerance * scale) out.differing.emplace_back(i, j);
    }
  }
  return out;
}

std::string num(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << (std::abs(v) < 1e-12 ? 0.0 : v);
  return s.str();
}

bool all_agree(const std::vector<MatrixComparison>& cs) {
  for (const auto& c : cs) {
    if (!c.differing.empty()) return false;
  }
  return true;
}

std::vector<MatrixComparison> compare_case(const PrintedCase& pc, const CaseModel& cm,
                                           bool mass_dependent_only) {
  const ReducedSystem r = reduce(cm.model, cm.slaves);
  std::vector<MatrixComparison> out;
  for (const auto& p : pc.matrices) {
    if (mass_dependent_only && !p.mass_dependent) continue;
    out.push_back(compare(p, computed(p.quantity, cm.model, r)));
  }
  return out;
}

/// The printed entries that differ from the assembled ones, one erratum per matrix.
void entry_errata(const std::vector<MatrixComparison>& comparisons, ChapterReport& report) {
  for (const auto& c : comparisons) {
    if (c.differing.empty()) continue;
    std::string d = c.printed.what + ":";
    for (const auto& [i, j] : c.differing) {
      if (i < 0) {
        d += " shape differs";
        continue;
      }
      d += " entry (" + std::to_string(i + 1) + "," + std::to_string(j + 1) + ") printed " +
           num(printed_at(c.printed, i, j)) + ", assembled " + num(c.computed(i, j)) + ";";
    }
    report.errata.push_back({c.printed.equation, d});
  }
}

/// Eq. 5.14 (§5.5.3): the velocity constraints integrated with zero initial values.
void check_eq_5_14(const Model& model, ChapterCaseReport& cr, ChapterReport& report) {
  const auto& eq = chapter_eq_5_14();
  for (std::size_t k = 0; k < eq.size() && k < model.constraints.size(); ++k) {
    const auto& c = model.constraints[k];
    const std::string dof = model.dof_names[static_cast<std::size_t>(c.coefficients.front().first)];
    TimeTerm poly;
    poly.coefficients = eq[k].coefficients;
    double worst = 0.0;
    for (double t : {0.5, 1.0, 2.0, 3.0}) {
      worst = std::max(worst, std::abs(poly.value(t) - c.position_value.value(t)));
    }
    std::string note = "5.14: " + dof + "(t) = " + c.position_value.describe() + "; printed '" +
                       eq[k].dof + " = " + poly.describe() + "'";
    if (worst > kPrintedTolerance) note += " [function differs by " + num(worst) + "]";
    if (eq[k].dof != dof) {
      note += " [label differs]";
      std::string d = "printed '" + eq[k].dof + " = " + poly.describe();
      d += "', but integrating the constraint on " + dof + " gives " + dof + " = ";
      d += c.position_value.describe();
      report.errata.push_back({"5.14", d});
    }
    cr.notes.push_back(note);
  }
}

/// §5.6.1 says "The transformed stiffness matrix M̂ has rank 2 and nullity 1".
void check_rank_claim_5_6_1(const CaseModel& cm, ChapterCaseReport& cr, ChapterReport& report) {
  const ReducedSystem r = reduce(cm.model, cm.slaves);
  const auto rank = [](const Eigen::SparseMatrix<double>& s) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu{Eigen::MatrixXd(s)};
    lu.setThreshold(1e-10);
    return static_cast<int>(lu.rank());
  };
  const int rm = rank(r.M), rk = rank(r.K);
  cr.notes.push_back("§5.6.1 text: rank M̂ = " + std::to_string(rm) + ", rank K̂ = " +
                     std::to_string(rk) + " (printed: \"M̂ has rank 2 and nullity 1\")");
  if (rm != 2 && rk == 2) {
    report.errata.push_back({"§5.6.1 text", "says M̂ has rank 2 and nullity 1; assembled rank M̂ = " +
                                                std::to_string(rm) + ", rank K̂ = " +
                                                std::to_string(rk) + ": the claim holds for K̂"});
  }
}

/// Eq. 5.26 as printed, Tᵀ(f − Kg), has no g'' term; 5.28 prints g'' coefficients (§5.6.2).
void check_eq_5_26(const PrintedCase& pc, const CaseModel& cm, ChapterCaseReport& cr,
                   ChapterReport& report) {
  const ReducedSystem r = reduce(cm.model, cm.slaves);
  for (const auto& p : pc.matrices) {
    if (p.quantity != ChapterQuantity::reduced_transfer_gdd) continue;
    const Eigen::MatrixXd formula_5_26 = Eigen::MatrixXd::Zero(r.FM.rows(), r.FM.cols());
    const bool printed_matches_5_26 = compare(p, formula_5_26).differing.empty();
    const bool printed_matches_full = compare(p, Eigen::MatrixXd(r.FM)).differing.empty();
    cr.notes.push_back(std::string("5.26 vs 5.28: printed 5.28 g'' coefficients ") +
                       (printed_matches_full ? "match" : "do not match") +
                       " Tᵀ(f − Kg − M g''), and " +
                       (printed_matches_5_26 ? "match" : "do not match") + " 5.26's Tᵀ(f − Kg)");
    if (printed_matches_full && !printed_matches_5_26) {
      report.errata.push_back({"5.26",
                               "prints Tᵀ(f − Kg); the reduced force is Tᵀ(f − Kg − M g''), as "
                               "5.28's own g'' terms show"});
    }
  }
}

/// Masses: each section's mass-dependent printed matrices, evaluated with the other section's
/// masses. If both sections agree with their own masses and disagree with the other's, no single
/// M satisfies the chapter.
void check_masses(const std::vector<PrintedCase>& printed, ChapterReport& report) {
  auto masses_of = [](const std::string& scene) {
    return parse_scene_text(embedded_scene(scene).text, scene).model.masses;
  };
  const auto own55 = masses_of("chapter_5_5_1"), own56 = masses_of("chapter_5_6_1");
  bool own_ok = true, swapped_ok = true;
  for (const auto& pc : printed) {
    const bool in55 = pc.section.rfind("§5.5", 0) == 0;
    const auto& other = in55 ? own56 : own55;
    own_ok = own_ok && all_agree(compare_case(pc, case_model(pc.scene), true));
    swapped_ok = swapped_ok && all_agree(compare_case(pc, case_model(pc.scene, &other), true));
  }
  if (own_ok && !swapped_ok && own55 != own56) {
    auto list = [](const std::vector<double>& m) {
      std::string s;
      for (double v : m) s += (s.empty() ? "" : ", ") + num(v);
      return "(" + s + ")";
    };
    report.errata.push_back(
        {"masses", "the §5.5 equations (5.6-5.12) imply m = " + list(own55) +
                       ", the §5.6 equations (5.21, 5.28) imply m = " + list(own56) +
                       "; neither set reproduces the other "
                       "section's printed mass terms"});
  }
}

}  // namespace

ChapterReport chapter_report() {
  ChapterReport report;
  const auto& printed = chapter_printed();
  for (const auto& pc : printed) {
    ChapterCaseReport cr{pc.scene, pc.section, {}, {}};
    const CaseModel cm = case_model(pc.scene);
    cr.comparisons = compare_case(pc, cm, false);
    entry_errata(cr.comparisons, report);
    if (pc.scene == "chapter_5_5_3") check_eq_5_14(cm.model, cr, report);
    if (pc.scene == "chapter_5_6_1") check_rank_claim_5_6_1(cm, cr, report);
    if (pc.scene == "chapter_5_6_2") check_eq_5_26(pc, cm, cr, report);
    report.cases.push_back(std::move(cr));
  }
  check_masses(printed, report);
  return report;
}

void print_case_matrices(std::ostream& out, const ChapterCaseReport& report) {
  for (const auto& c : report.comparisons) {
    out << "  eq. " << c.printed.equation << "  " << c.printed.what << "   (printed | assembled"
        << (c.differing.empty() ? ", all entries agree)" : ", * marks a differing entry)") << "\n";
    for (int i = 0; i < c.printed.rows; ++i) {
      out << "    [";
      for (int j = 0; j < c.printed.cols; ++j) {
        bool bad = false;
        for (const auto& d : c.differing) bad = bad || (d.first == i && d.second == j);
        out << std::right << std::setw(7) << num(printed_at(c.printed, i, j)) << (bad ? "*" : " ");
      }
      out << "]   [";
      for (int j = 0; j < c.computed.cols() && i < c.computed.rows(); ++j) {
        out << std::right << std::setw(7) << num(c.computed(i, j)) << " ";
      }
      out << "]\n";
    }
  }
  for (const auto& note : report.notes) out << "  " << note << "\n";
}

void print_errata(std::ostream& out, const std::vector<Erratum>& errata) {
  out << "Errata found by the code (" << errata.size() << "):\n";
  for (const auto& e : errata) out << "  - " << e.where << ": " << e.description << "\n";
  out << "  (the chapter's equation cross-references, e.g. \"differentiate (5.23)\" in §5.6.1, are "
         "text and not checked by the program)\n";
}

}  // namespace condyn
