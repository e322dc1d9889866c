// The stress suite's cases: what each family probes, and the scene text of every case, generated
// from the family's parameter. validation/studies/stress.cpp runs them.
#include "validation/studies/stress.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "dae/formulations/baumgarte_gains.hpp"
#include "models/assembly/build_model.hpp"
#include "models/core/model.hpp"
#include "models/scene/scene_parser.hpp"
#include "validation/references/embedded_scenes.hpp"
#include "validation/references/scientific.hpp"

namespace condyn {

namespace {

std::string full_precision(double v) {
  std::ostringstream s;
  s << std::setprecision(17) << v;
  return s.str();
}

/// A 4-mass chain x1..x4 on a ground spring, its base driven (x1 = 0.1 sin t) and its ends tied
/// (x4 − x2 = 0), a step load on x3: springs and masses as given.
std::string chain_scene(const std::string& name, const double (&k)[4], const double (&m)[4],
                        double t_end) {
  std::ostringstream s;
  s << "name = \"" << name << "\"\n[model]\ntype = \"matrix\"\ndofs = [\"x1\", \"x2\", \"x3\", "
    << "\"x4\"]\nmass = [\n";
  for (int i = 0; i < 4; ++i) {
    s << "  [";
    for (int j = 0; j < 4; ++j) s << (j ? ", " : "") << (i == j ? full_precision(m[i]) : "0.0");
    s << "],\n";
  }
  // K: ground spring k[0] on x1, k[i] between x_i and x_{i+1}.
  double K[4][4] = {};
  K[0][0] += k[0];
  for (int i = 0; i < 3; ++i) {
    K[i][i] += k[i + 1];
    K[i + 1][i + 1] += k[i + 1];
    K[i][i + 1] -= k[i + 1];
    K[i + 1][i] -= k[i + 1];
  }
  s << "]\nstiffness = [\n";
  for (auto& row : K) {
    s << "  [";
    for (int j = 0; j < 4; ++j) s << (j ? ", " : "") << full_precision(row[j]);
    s << "],\n";
  }
  s << "]\n[[load]]\ndof = \"x3\"\nvalue = { type = \"step\", amplitude = 1.0 }\n"
    << "[[constraint]]\nname = \"base\"\nterms = { x1 = 1.0 }\n"
    << "value = { type = \"harmonic\", amplitude = 0.1, omega = 1.0 }\n"
    << "[[constraint]]\nname = \"tie\"\nterms = { x4 = 1.0, x2 = -1.0 }\n"
    << "[initial]\nvelocity = { x1 = 0.1 }\n"
    << "[solve]\nt_end = " << full_precision(t_end)
    << "\noutput_step = " << full_precision(t_end / 50) << "\nrtol = 1e-8\natol = 1e-10\n";
  return s.str();
}

/// The chapter truss of §5.5.1 (built in), with extra lines appended to its [[load]]s and its
/// [solve] replaced.
std::string chapter_truss(const std::string& extra_loads, const std::string& solve) {
  std::string text = embedded_scene("chapter_5_5_1").text;
  text = text.substr(0, text.find("[solve]"));
  return text + extra_loads + solve;
}

/// Highest natural frequency of the constrained chapter truss (the Baumgarte default's scale).
double chapter_frequency() {
  const std::string text = chapter_truss("", "[solve]\nt_end = 1.0\noutput_step = 0.1\n");
  const SceneSpec spec = parse_scene_text(text, "chapter");
  return baumgarte_gains(build_model(spec), spec.solve).beta;
}

/// The four-bar A(0,0)-B-C-D(4,0): crank AB = 1 at 90°, coupler BC = 4, rocker CD = 1 + eps.
/// For eps = 0 it is a parallelogram whose links all fall on one line when the crank reaches
/// 180° (a change point: the constraint Jacobian loses rank); eps > 0 passes that point at a
/// distance of order eps. The crank turns at 2π rad/s; the other speeds come from projection.
std::string four_bar_scene(double eps) {
  const double bx = 0.0, by = 1.0, dx = 4.0, dy = 0.0, r1 = 4.0, r2 = 1.0 + eps;
  // C: the intersection of the circles about B (radius r1) and D (radius r2) near (4, 1).
  const double d = std::hypot(dx - bx, dy - by);
  const double a = (r1 * r1 - r2 * r2 + d * d) / (2 * d);
  const double h = std::sqrt(std::max(0.0, r1 * r1 - a * a));
  const double px = bx + a * (dx - bx) / d, py = by + a * (dy - by) / d;
  const double cx = px - h * (dy - by) / d, cy = py + h * (dx - bx) / d;
  std::ostringstream s;
  s << "name = \"four-bar near its change point, eps = " << eps << "\"\n[model]\n"
    << "type = \"truss2d\"\nnodes = [[0.0, 0.0], [0.0, 1.0], [" << full_precision(cx) << ", "
    << full_precision(cy) << "], [4.0, 0.0]]\nmasses = [0.0, 1.0, 1.0, 0.0]\nsupports = [1, 4]\n"
    << "members = [{ nodes = [1, 2], rigid = true }, { nodes = [2, 3], rigid = true }, "
    << "{ nodes = [3, 4], rigid = true }]\n"
    << "[initial]\nvelocity = { ux2 = " << full_precision(-2 * std::numbers::pi)
    << " }\nproject = true\n"
    << "[solve]\nt_end = 1.0\noutput_step = 0.01\nrtol = 1e-8\natol = 1e-10\n";
  return s.str();
}

/// Three unit masses on ground springs with two constraints whose normals meet at angle theta:
/// x = 0 and cos θ x + sin θ y = 0 (θ = 0: the same row twice). A step load on y.
std::string redundant_scene(double theta) {
  std::ostringstream s;
  s << "name = \"two constraints at angle " << theta << "\"\n[model]\ntype = \"matrix\"\n"
    << "dofs = [\"x\", \"y\", \"z\"]\nmass = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n"
    << "stiffness = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]\n"
    << "[[load]]\ndof = \"y\"\nvalue = { type = \"step\", amplitude = 1.0 }\n"
    << "[[load]]\ndof = \"z\"\nvalue = { type = \"step\", amplitude = 1.0 }\n"
    << "[[constraint]]\nname = \"first\"\nterms = { x = 1.0 }\n"
    << "[[constraint]]\nname = \"second\"\nterms = { x = " << full_precision(std::cos(theta))
    << ", y = " << full_precision(std::sin(theta)) << " }\n"
    << "[solve]\nt_end = 10.0\noutput_step = 0.1\nrtol = 1e-8\natol = 1e-10\n";
  return s.str();
}

/// One unit mass on a unit spring tied to a second one (x2 − x1 = 0), for N periods.
std::string long_scene(double periods) {
  std::ostringstream s;
  const double t_end =
      periods * 2 * std::numbers::pi;  // the constrained pair oscillates at 1 rad/s
  s << "name = \"two tied masses over " << periods << " periods\"\n[model]\ntype = \"matrix\"\n"
    << "dofs = [\"x1\", \"x2\"]\nmass = [[1.0, 0.0], [0.0, 1.0]]\n"
    << "stiffness = [[1.0, 0.0], [0.0, 1.0]]\n"
    << "[[constraint]]\nname = \"tie\"\nterms = { x2 = 1.0, x1 = -1.0 }\n"
    << "[initial]\ndisplacement = { x1 = 1.0, x2 = 1.0 }\n"
    << "[solve]\nt_end = " << full_precision(t_end)
    << "\noutput_step = " << full_precision(t_end / 100)
    << "\nrtol = 1e-5\natol = 1e-7\n[output]\nquantities = [\"displacement\", \"drift\", "
    << "\"energy\"]\n";
  return s.str();
}

}  // namespace

const std::vector<StressFamily>& stress_families() {
  static const std::vector<StressFamily> families = {
      {"stiffness", "spring stiffnesses spanning 1 to R in one chain (R = 1 ... 1e12)",
       "stiffly stable BDF should pay for stiffness in steps, not accuracy; the schemes that do "
       "not hold the position constraint, and penalty (its default weight scales with the "
       "stiffest spring), break first"},
      {"mass_ratio", "masses spanning 1 to 1/r (r = 1 ... 1e8), and a massless DOF",
       "light masses add fast modes: more steps, and error where they ring; a massless DOF that "
       "its springs hold is algebraic: the multiplier schemes, elimination and penalty integrate "
       "it as a DAE, projection as an index-reduced ODE with its row as an invariant (against "
       "the statically condensed exact solution)"},
      {"penalty_weight", "penalty weight w from 1e2 to 1e12 times the largest stiffness",
       "the error falls like 1/w while the penalty springs ring at sqrt(w/m); at large w BDF damps "
       "the ringing and the error settles at the integration error"},
      {"baumgarte_gains",
       "Baumgarte alpha = beta from 1 to 1e12 times the pendulum's natural frequency (pi rad/s)",
       "small gains correct the drift slowly; large ones make the system stiff until the step "
       "size collapses: there is no problem-independent choice"},
      {"long_horizon", "1e4 and 1e5 periods of the slowest mode at rtol 1e-5",
       "judged by the position drift (limit 1e-6): bounded under every multiplier scheme here "
       "(linear constraints); the phase error against the exact solution, and BDF's numerical "
       "damping of the energy, grow for every scheme (reported, not judged)"},
      {"redundancy", "two constraints whose normals meet at angle theta (1e-2 ... 1e-8, and 0)",
       "theta = 0 is refused with both constraints named; small angles are accepted, with "
       "multipliers growing like 1/theta; penalty cannot enforce the nearly dependent direction "
       "(its stiffness there is w theta^2)"},
      {"dead_point",
       "a four-bar whose coupler and rocker pass within eps of alignment (eps = 1e-1 ... 1e-4)",
       "the multiplier schemes and projection pass near the singular configuration; index3 is the "
       "least accurate; too close, even the tight reference run fails"},
      {"high_frequency",
       "a harmonic load at 1 to 1000 times the highest natural frequency, and a step load at t = 1",
       "every scheme that holds the constraints holds, at a cost in steps that grows with the "
       "forcing frequency"},
  };
  return families;
}

namespace {

/// The cases of the wanted families (all when none is named), in the order stress runs them.
class CaseList {
 public:
  explicit CaseList(const std::vector<std::string>& families) : families_(families) {}

  [[nodiscard]] bool wanted(const std::string& f) const {
    if (families_.empty()) return true;
    for (const auto& name : families_)
      if (name == f) return true;
    return false;
  }

  /// Adds a case of a wanted family; returns it for family-specific settings (nullptr otherwise).
  StressCase* add(const std::string& family, const std::string& label, double parameter,
                  const std::string& text, std::vector<Scheme> schemes = {},
                  long max_steps = 1000000) {
    if (!wanted(family)) return nullptr;
    StressCase c;
    c.family = family;
    c.id = family + "_" +
           std::to_string(1 + std::count_if(cases.begin(), cases.end(), [&](const StressCase& o) {
                            return o.family == family;
                          }));
    c.label = label;
    c.parameter = parameter;
    // The file stress writes is this text: the lines its messages name are the file's.
    c.scene_text = "# condyn stress, family " + family + ", " + label +
                   ": run it with build/condyn run FILE --scheme S\n" + text;
    c.schemes = std::move(schemes);
    c.max_steps = max_steps;
    cases.push_back(std::move(c));
    return &cases.back();
  }

  std::vector<StressCase> cases;

 private:
  const std::vector<std::string>& families_;
};

/// stiffness and mass_ratio: the chain with springs, then masses, spanning a ratio.
void add_chain_cases(CaseList& list) {
  for (double R : {1.0, 1e4, 1e8, 1e12}) {
    const double k[4] = {1.0, std::cbrt(R), std::cbrt(R) * std::cbrt(R), R};
    const double m[4] = {1.0, 1.0, 1.0, 1.0};
    list.add("stiffness", "R = " + scientific(R, 0), R,
             chain_scene("chain, stiffness ratio " + scientific(R, 0), k, m, 5.0));
  }
  const double k_mass[4] = {1.0, 10.0, 10.0, 10.0};
  for (double r : {1.0, 1e4, 1e8}) {
    const double m[4] = {1.0, 1.0 / std::cbrt(r), 1.0 / (std::cbrt(r) * std::cbrt(r)), 1.0 / r};
    list.add("mass_ratio", "r = " + scientific(r, 0), r,
             chain_scene("chain, mass ratio " + scientific(r, 0), k_mass, m, 5.0));
  }
  const double massless[4] = {1.0, 1.0, 0.0, 1.0};
  list.add("mass_ratio", "m3 = 0", 0.0, chain_scene("chain, massless x3", k_mass, massless, 5.0));
}

/// penalty_weight: the chapter truss under penalty, its weight a multiple of the stiffest K_ii.
void add_penalty_weight_cases(CaseList& list) {
  if (!list.wanted("penalty_weight")) return;
  const std::string solve = "[solve]\nt_end = 5.0\noutput_step = 0.1\nrtol = 1e-8\natol = 1e-10\n";
  const Model truss = build_model(parse_scene_text(chapter_truss("", solve), "chapter"));
  double kmax = 0.0;
  for (int i = 0; i < truss.dofs(); ++i) kmax = std::max(kmax, truss.K->coeff(i, i));
  for (double f : {1e2, 1e4, 1e6, 1e8, 1e10, 1e12}) {
    list.add("penalty_weight", "w = " + scientific(f, 0) + " max K_ii", f,
             chapter_truss("", solve + "penalty = { weight = " + full_precision(f * kmax) + " }\n"),
             {Scheme::penalty});
  }
}

/// baumgarte_gains: the pendulum of period 2 under Baumgarte, its gains a multiple of its
/// frequency scale.
void add_baumgarte_cases(CaseList& list) {
  for (double f : {1.0, 1e1, 1e2, 1e3, 1e4, 1e6, 1e8, 1e10, 1e12}) {
    // The pendulum of period 2: its constraint is nonlinear, so there is drift to correct; its
    // frequency scale is 2π / period = π rad/s.
    const std::string g = full_precision(f * std::numbers::pi);
    list.add("baumgarte_gains", "gains = " + scientific(f, 0) + " omega", f,
             "name = \"pendulum of period 2, Baumgarte gains " + scientific(f, 0) +
                 " x pi\"\n[model]\ntype = \"pendulum\"\n[solve]\nt_end = 2.0\n"
                 "output_step = 0.02\nrtol = 1e-8\natol = 1e-10\nbaumgarte = { alpha = " +
                 g + ", beta = " + g + " }\n",
             {Scheme::baumgarte}, 200000);
  }
}

/// long_horizon, redundancy and dead_point: drift over many periods, nearly dependent
/// constraints, a four-bar near its dead point.
void add_constraint_cases(CaseList& list) {
  for (double periods : {1e4, 1e5}) {
    if (StressCase* c = list.add("long_horizon", scientific(periods, 0) + " periods", periods,
                                 long_scene(periods), {}, 20000000)) {
      c->drift_limit = 1e-6;
    }
  }
  for (double theta : {1e-2, 1e-4, 1e-6, 1e-8, 0.0}) {
    list.add("redundancy", "theta = " + (theta > 0 ? scientific(theta, 0) : std::string("0")),
             theta, redundant_scene(theta));
  }
  list.add("redundancy", "theta = 0, dropped", 0.0,
           redundant_scene(0.0) + "redundant = \"drop\"\n");  // the [solve] table ends the text
  for (double eps : {1e-1, 1e-2, 1e-3, 1e-4}) {
    list.add("dead_point", "eps = " + scientific(eps, 0), eps, four_bar_scene(eps), {}, 400000);
  }
}

/// high_frequency: the chapter truss under a harmonic load at multiples of its highest natural
/// frequency, and a step load.
void add_high_frequency_cases(CaseList& list) {
  if (!list.wanted("high_frequency")) return;
  const double omega = chapter_frequency();
  for (double f : {1.0, 10.0, 100.0, 1000.0}) {
    std::ostringstream loads;
    loads << "[[load]]\ndof = \"ux3\"\nvalue = { type = \"harmonic\", amplitude = 1.0, "
          << "omega = " << full_precision(f * omega) << " }\n[[load]]\ndof = \"uy3\"\n"
          << "value = { type = \"step\", amplitude = 0.5, start = 1.0 }\n";
    list.add("high_frequency", "omega = " + scientific(f, 0) + " omega_max", f,
             chapter_truss(loads.str(),
                           "[solve]\nt_end = 3.0\noutput_step = 0.05\n"
                           "rtol = 1e-8\natol = 1e-10\n"));
  }
}

}  // namespace

std::vector<StressCase> stress_cases(const std::vector<std::string>& families) {
  for (const auto& f : families) {
    bool known = false;
    for (const auto& sf : stress_families()) known = known || sf.name == f;
    if (!known) {
      std::string names;
      for (const auto& sf : stress_families()) names += (names.empty() ? "" : ", ") + sf.name;
      throw std::invalid_argument("unknown stress family '" + f + "' (expected " + names + ")");
    }
  }
  CaseList list(families);
  add_chain_cases(list);
  add_penalty_weight_cases(list);
  add_baumgarte_cases(list);
  add_constraint_cases(list);
  add_high_frequency_cases(list);
  return std::move(list.cases);
}

}  // namespace condyn
