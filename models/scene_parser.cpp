#include "models/scene_parser.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace condyn {

std::string scene_message(const std::string& file, const SourcePoint& where,
                          const std::string& problem) {
  std::string msg = file;
  if (where.line > 0) msg += ":" + std::to_string(where.line);
  msg += ": ";
  if (!where.path.empty()) msg += where.path + ": ";
  return msg + problem;
}

const char* to_string(Quantity q) {
  switch (q) {
    case Quantity::displacement:
      return "displacement";
    case Quantity::velocity:
      return "velocity";
    case Quantity::reaction:
      return "reaction";
    case Quantity::multiplier:
      return "multiplier";
    case Quantity::drift:
      return "drift";
    case Quantity::energy:
      return "energy";
  }
  return "?";
}

namespace {

/// Walks the TOML tree; knows the file name so every error can say where it is.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[nodiscard]] SourcePoint at(const toml::node& node, const std::string& path) const {
    return SourcePoint{path, static_cast<int>(node.source().begin.line)};
  }

  [[noreturn]] void fail(const toml::node& node, const std::string& path,
                         const std::string& problem) const {
    throw SceneError(scene_message(file_, at(node, path), problem));
  }

  void check_keys(const toml::table& table, const std::string& path,
                  std::initializer_list<std::string_view> allowed) const {
    for (const auto& [key, node] : table) {
      bool known = false;
      for (auto a : allowed) known = known || key.str() == a;
      if (!known) {
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(node, join(path, std::string(key.str())),
             "unknown key (expected one of: " + list + ")");
      }
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string index(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i + 1) + "]";
  }

  [[nodiscard]] const toml::table& table(const toml::node& node, const std::string& path) const {
    if (const auto* t = node.as_table()) return *t;
    fail(node, path, "expected a table");
  }
  [[nodiscard]] const toml::array& array(const toml::node& node, const std::string& path) const {
    if (const auto* a = node.as_array()) return *a;
    fail(node, path, "expected an array");
  }
  [[nodiscard]] double number(const toml::node& node, const std::string& path) const {
    double v = 0.0;
    if (const auto* f = node.as_floating_point()) {
      v = f->get();
    } else if (const auto* i = node.as_integer()) {
      v = static_cast<double>(i->get());
    } else {
      fail(node, path, "expected a number");
    }
    if (!std::isfinite(v)) fail(node, path, "must be finite");
    return v;
  }
  [[nodiscard]] double positive(const toml::node& node, const std::string& path) const {
    const double v = number(node, path);
    if (v <= 0.0) fail(node, path, "must be > 0 (got " + fmt(v) + ")");
    return v;
  }
  [[nodiscard]] std::string string(const toml::node& node, const std::string& path) const {
    if (const auto* s = node.as_string()) return s->get();
    fail(node, path, "expected a string");
  }
  [[nodiscard]] long integer(const toml::node& node, const std::string& path) const {
    if (const auto* i = node.as_integer()) return static_cast<long>(i->get());
    fail(node, path, "expected an integer");
  }
  [[nodiscard]] const toml::node& required(const toml::table& t, const std::string& path,
                                           std::string_view key) const {
    if (const auto* n = t.get(key)) return *n;
    fail(t, join(path, std::string(key)), "missing required key");
  }
  [[nodiscard]] std::vector<double> numbers(const toml::node& node, const std::string& path) const {
    std::vector<double> out;
    const auto& arr = array(node, path);
    for (std::size_t i = 0; i < arr.size(); ++i) out.push_back(number(*arr.get(i), index(path, i)));
    return out;
  }
  [[nodiscard]] std::vector<std::vector<double>> dense_matrix(const toml::node& node,
                                                              const std::string& path) const {
    std::vector<std::vector<double>> rows;
    const auto& arr = array(node, path);
    for (std::size_t i = 0; i < arr.size(); ++i)
      rows.push_back(numbers(*arr.get(i), index(path, i)));
    return rows;
  }

  /// DOF and constraint names become CSV column names (scene-format.md, "Output"), written as
  /// they are, unquoted: a name may not hold what would split or quote a field (a comma, a double
  /// quote), control characters (line breaks, tabs), nor begin or end with a space (CSV readers
  /// trim it). Everything else is the user's: spaces inside, slashes, UTF-8.
  static constexpr std::string_view kNameBreakers = ",\"";

  static std::string describe_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (c == ' ') return "a space";
    if (c == '\n' || c == '\r') return "a line break";
    if (c == '\t') return "a tab";
    if (u >= 0x80) return "a non-ASCII character";
    if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      return std::string("the control character ") + buf;
    }
    return std::string("'") + c + "'";
  }

  /// The name as a message can show it: control characters escaped.
  static std::string printable(const std::string& name) {
    std::string out;
    for (char c : name) {
      const auto u = static_cast<unsigned char>(c);
      if (u < 0x20 || u == 0x7f) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\x%02x", u);
        out += buf;
      } else {
        out += c;
      }
    }
    return out;
  }

  void check_name(const toml::node& node, const std::string& path, const std::string& name,
                  const char* what) const {
    const auto refuse = [&](const std::string& why) {
      fail(node, path,
           std::string(what) + " name '" + printable(name) + "' " + why +
               ": names become CSV column names and may not hold a comma, a double quote or a "
               "control character, nor begin or end with a space");
    };
    for (char c : name) {
      const auto u = static_cast<unsigned char>(c);
      if (u < 0x20 || u == 0x7f || kNameBreakers.find(c) != std::string_view::npos) {
        refuse("holds " + describe_char(c));
      }
    }
    if (!name.empty() && (name.front() == ' ' || name.back() == ' ')) {
      refuse(std::string(name.front() == ' ' ? "begins" : "ends") + " with a space");
    }
  }

  /// Every column a scene can produce (all quantities, whatever [output] asks now) must be
  /// distinct: the DOFs' columns (u, vel_u, reaction_u), the multipliers' (lambda_c) and the
  /// fixed ones. Names are checked here, where they have a line; the message names the later one.
  void check_columns(const toml::table& root, const SceneSpec& spec) const {
    std::map<std::string, std::string> owner = {{"t", "the time column"},
                                                {"drift_position", "a drift column"},
                                                {"drift_velocity", "a drift column"},
                                                {"energy", "an energy column"},
                                                {"energy_error", "an energy column"}};
    const auto claim = [&](const std::string& column, const std::string& who,
                           const toml::node& node, const std::string& path, const std::string& name,
                           const char* what) {
      const auto [it, fresh] = owner.emplace(column, who);
      if (!fresh) {
        fail(node, path,
             std::string(what) + " '" + name + "' gives the column '" + column + "', which is " +
                 "already " + it->second + " (CSV columns must be distinct under every quantity)");
      }
    };
    const auto* model = root.get_as<toml::table>("model");
    const auto* dofs = model != nullptr ? model->get_as<toml::array>("dofs") : nullptr;
    if (spec.model.type == ModelSpec::Type::matrix && dofs != nullptr) {
      for (std::size_t i = 0; i < spec.model.dofs.size(); ++i) {
        const std::string& d = spec.model.dofs[i];
        const std::string p = index("model.dofs", i);
        for (const auto& [prefix, quantity] :
             {std::pair<std::string, std::string>{"", "displacement"},
              {"vel_", "velocity"},
              {"reaction_", "reaction"}}) {
          claim(prefix + d, "the " + quantity + " column of DOF '" + d + "'", *dofs->get(i), p, d,
                "DOF");
        }
      }
    }
    // Rows a truss adds, named like constraints: fix_<dof> per supported DOF, rigid_i_j per
    // rigid member (build_model names them so).
    if (spec.model.type == ModelSpec::Type::truss2d ||
        spec.model.type == ModelSpec::Type::truss3d) {
      const char* axes = "xyz";
      for (int node : spec.model.supports) {
        for (int d = 0; d < spec.model.dimension; ++d) {
          const std::string row = std::string("fix_u") + axes[d] + std::to_string(node);
          owner.emplace("lambda_" + row,
                        "the multiplier column of the row '" + row + "' that model.supports adds");
        }
      }
      for (std::size_t e = 0; e < spec.model.members.size(); ++e) {
        const auto& m = spec.model.members[e];
        if (!m.rigid) continue;
        const std::string row =
            "rigid_" + std::to_string(m.node_i) + "_" + std::to_string(m.node_j);
        owner.emplace("lambda_" + row, "the multiplier column of the row '" + row + "' that " +
                                           index("model.members", e) + " adds");
      }
    }
    const auto* cons = root.get_as<toml::array>("constraint");
    for (std::size_t i = 0; i < spec.constraints.size() && cons != nullptr; ++i) {
      const std::string& c = spec.constraints[i].name;
      const auto& t = *cons->get(i)->as_table();
      const toml::node* where = t.get("name") != nullptr ? t.get("name") : cons->get(i);
      claim("lambda_" + c, "the multiplier column of constraint '" + c + "'", *where,
            join(index("constraint", i), "name"), c, "constraint");
    }
  }

  static std::string fmt(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
  }

  [[nodiscard]] TimeTerm term(const toml::node& node, const std::string& path) const {
    const auto& t = table(node, path);
    const std::string type = string(required(t, path, "type"), join(path, "type"));
    TimeTerm term;
    auto opt = [&](std::string_view key, double dflt) {
      const auto* n = t.get(key);
      return n ? number(*n, join(path, std::string(key))) : dflt;
    };
    if (type == "step") {
      check_keys(t, path, {"type", "amplitude", "start"});
      term.kind = TimeTerm::Kind::step;
      term.amplitude = opt("amplitude", 1.0);
      term.start = opt("start", 0.0);
    } else if (type == "polynomial") {
      check_keys(t, path, {"type", "coefficients"});
      term.kind = TimeTerm::Kind::polynomial;
      term.coefficients = numbers(required(t, path, "coefficients"), join(path, "coefficients"));
      if (term.coefficients.empty()) fail(node, join(path, "coefficients"), "must not be empty");
    } else if (type == "harmonic") {
      check_keys(t, path, {"type", "amplitude", "omega", "phase"});
      term.kind = TimeTerm::Kind::harmonic;
      term.amplitude = opt("amplitude", 1.0);
      term.omega = number(required(t, path, "omega"), join(path, "omega"));
      term.phase = opt("phase", 0.0);
    } else if (type == "exponential") {
      check_keys(t, path, {"type", "amplitude", "rate"});
      term.kind = TimeTerm::Kind::exponential;
      term.amplitude = opt("amplitude", 1.0);
      term.rate = number(required(t, path, "rate"), join(path, "rate"));
    } else {
      fail(*t.get("type"), join(path, "type"),
           "unknown time function '" + type +
               "' (expected step, polynomial, harmonic or exponential)");
    }
    return term;
  }

  [[nodiscard]] TimeFunction time_function(const toml::node& node, const std::string& path) const {
    if (node.is_number()) return TimeFunction::constant(number(node, path));
    if (node.is_table()) return TimeFunction({term(node, path)});
    if (const auto* arr = node.as_array()) {
      std::vector<TimeTerm> terms;
      for (std::size_t i = 0; i < arr->size(); ++i)
        terms.push_back(term(*arr->get(i), index(path, i)));
      if (terms.empty()) fail(node, path, "an empty list is not a time function (write 0)");
      return TimeFunction(std::move(terms));
    }
    fail(node, path, "expected a number, a time-function table or a list of them");
  }

  [[nodiscard]] std::vector<std::pair<std::string, double>> dof_values(
      const toml::node& node, const std::string& path) const {
    std::vector<std::pair<std::string, double>> out;
    const auto& t = table(node, path);
    for (const auto& [key, value] : t) {
      out.emplace_back(std::string(key.str()), number(value, join(path, std::string(key.str()))));
    }
    return out;
  }

  void read_truss(const toml::table& t, int dim, ModelSpec& model) const {
    const std::string path = "model";
    check_keys(t, path, {"type", "nodes", "masses", "members", "geometry", "gravity", "supports"});
    model.type = dim == 3 ? ModelSpec::Type::truss3d : ModelSpec::Type::truss2d;
    model.dimension = dim;
    const auto& nodes = array(required(t, path, "nodes"), "model.nodes");
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const std::string p = index("model.nodes", i);
      const auto xyz = numbers(*nodes.get(i), p);
      if (static_cast<int>(xyz.size()) != dim) {
        fail(*nodes.get(i), p, dim == 3 ? "a node is [x, y, z]" : "a node is [x, y]");
      }
      model.nodes.push_back({xyz[0], xyz[1], dim == 3 ? xyz[2] : 0.0});
    }
    if (model.nodes.empty()) fail(nodes, "model.nodes", "at least one node is needed");
    const auto& masses_node = required(t, path, "masses");
    model.masses = numbers(masses_node, "model.masses");
    if (model.masses.size() != model.nodes.size()) {
      fail(masses_node, "model.masses",
           "has " + std::to_string(model.masses.size()) + " entries for " +
               std::to_string(model.nodes.size()) + " nodes");
    }
    const auto& masses_arr = array(masses_node, "model.masses");
    for (std::size_t i = 0; i < model.masses.size(); ++i) {
      if (model.masses[i] < 0.0) {
        fail(*masses_arr.get(i), index("model.masses", i), "a mass must be >= 0");
      }
    }
    const auto node_number = [&](const toml::node& n, const std::string& p) {
      const long k = integer(n, p);
      if (k < 1 || k > static_cast<long>(model.nodes.size())) {
        fail(n, p,
             "node " + std::to_string(k) + " does not exist (nodes are 1.." +
                 std::to_string(model.nodes.size()) + ")");
      }
      return static_cast<int>(k);
    };
    const auto& members = array(required(t, path, "members"), "model.members");
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::string p = index("model.members", i);
      const auto& m = table(*members.get(i), p);
      check_keys(m, p, {"nodes", "EA", "rigid"});
      MemberSpec member;
      member.where = at(*members.get(i), p);
      const auto& ends_node = required(m, p, "nodes");
      const auto& ends = array(ends_node, join(p, "nodes"));
      if (ends.size() != 2) fail(ends_node, join(p, "nodes"), "a member joins two nodes [i, j]");
      member.node_i = node_number(*ends.get(0), index(join(p, "nodes"), 0));
      member.node_j = node_number(*ends.get(1), index(join(p, "nodes"), 1));
      if (member.node_i == member.node_j)
        fail(ends_node, join(p, "nodes"), "a member must join two different nodes");
      if (const auto* r = m.get("rigid")) {
        const auto* b = r->as_boolean();
        if (b == nullptr) fail(*r, join(p, "rigid"), "expected true or false");
        member.rigid = b->get();
      }
      if (member.rigid) {
        if (const auto* ea = m.get("EA")) {
          fail(*ea, join(p, "EA"), "a rigid member has no stiffness: remove EA or rigid");
        }
      } else {
        member.EA = positive(required(m, p, "EA"), join(p, "EA"));
      }
      model.members.push_back(member);
    }
    if (const auto* g = t.get("geometry")) {
      const std::string s = string(*g, "model.geometry");
      if (s != "linear" && s != "nonlinear") {
        fail(*g, "model.geometry", "expected 'linear' or 'nonlinear' (got '" + s + "')");
      }
      model.geometry = s == "linear" ? ModelSpec::Geometry::linear : ModelSpec::Geometry::nonlinear;
    }
    if (const auto* g = t.get("gravity")) {
      model.gravity = numbers(*g, "model.gravity");
      if (static_cast<int>(model.gravity.size()) != dim) {
        fail(*g, "model.gravity",
             "needs " + std::to_string(dim) + " components (one per direction)");
      }
    }
    if (const auto* sp = t.get("supports")) {
      const auto& arr = array(*sp, "model.supports");
      std::vector<bool> supported(model.nodes.size(), false);  // linear in the list's length
      for (std::size_t i = 0; i < arr.size(); ++i) {
        const int k = node_number(*arr.get(i), index("model.supports", i));
        if (supported[static_cast<std::size_t>(k - 1)]) {
          fail(*arr.get(i), index("model.supports", i),
               "node " + std::to_string(k) + " is listed twice");
        }
        supported[static_cast<std::size_t>(k - 1)] = true;
        model.supports.push_back(k);
      }
    }
  }

  void read_model(const toml::node& node, ModelSpec& model) const {
    const std::string path = "model";
    const auto& t = table(node, path);
    model.where = at(node, path);
    const std::string type = string(required(t, path, "type"), "model.type");
    if (type == "truss2d" || type == "truss3d") {
      read_truss(t, type == "truss3d" ? 3 : 2, model);
    } else if (type == "matrix") {
      check_keys(t, path, {"type", "dofs", "mass", "stiffness", "damping"});
      model.type = ModelSpec::Type::matrix;
      const auto& dofs = array(required(t, path, "dofs"), "model.dofs");
      std::set<std::string> seen;
      for (std::size_t i = 0; i < dofs.size(); ++i) {
        const std::string name = string(*dofs.get(i), index("model.dofs", i));
        if (name.empty())
          fail(*dofs.get(i), index("model.dofs", i), "a DOF name must not be empty");
        check_name(*dofs.get(i), index("model.dofs", i), name, "DOF");
        if (!seen.insert(name).second) {
          fail(*dofs.get(i), index("model.dofs", i), "duplicate DOF name '" + name + "'");
        }
        model.dofs.push_back(name);
      }
      if (model.dofs.empty()) fail(dofs, "model.dofs", "at least one DOF is needed");
      auto square = [&](std::string_view key, std::vector<std::vector<double>>& out) {
        const std::string p = join(path, std::string(key));
        const auto& mat = required(t, path, key);
        out = dense_matrix(mat, p);
        const std::size_t n = model.dofs.size();
        if (out.size() != n) {
          fail(mat, p,
               "has " + std::to_string(out.size()) + " rows for " + std::to_string(n) + " DOFs");
        }
        for (std::size_t i = 0; i < n; ++i) {
          if (out[i].size() != n) {
            fail(*array(mat, p).get(i), index(p, i),
                 "has " + std::to_string(out[i].size()) + " entries for " + std::to_string(n) +
                     " DOFs");
          }
        }
        for (std::size_t i = 0; i < n; ++i) {
          for (std::size_t j = 0; j < i; ++j) {
            const double a = out[i][j], b = out[j][i];
            // Symmetry to a few ulps of the entries' size: a scene writes these by hand.
            if (std::abs(a - b) > 1e-12 * std::max({std::abs(a), std::abs(b), 1e-300})) {
              fail(mat, p,
                   "is not symmetric: entry (" + std::to_string(i + 1) + "," +
                       std::to_string(j + 1) + ") = " + fmt(a) + " but (" + std::to_string(j + 1) +
                       "," + std::to_string(i + 1) + ") = " + fmt(b));
            }
          }
        }
      };
      square("mass", model.mass);
      square("stiffness", model.stiffness);
      if (t.contains("damping")) square("damping", model.damping);
    } else if (type == "sleigh") {
      check_keys(t, path, {"type", "mass", "inertia", "contact_offset"});
      model.type = ModelSpec::Type::sleigh;
      model.body_mass = positive(required(t, path, "mass"), "model.mass");
      model.inertia = positive(required(t, path, "inertia"), "model.inertia");
      if (const auto* a = t.get("contact_offset"))
        model.contact_offset = number(*a, "model.contact_offset");
    } else if (type == "andrews" || type == "car_axis" || type == "pendulum") {
      check_keys(t, path, {"type"});  // the published problem fixes every parameter
      model.type = type == "andrews"    ? ModelSpec::Type::andrews
                   : type == "car_axis" ? ModelSpec::Type::car_axis
                                        : ModelSpec::Type::pendulum;
    } else {
      fail(*t.get("type"), "model.type",
           "unknown model type '" + type +
               "' (expected truss2d, truss3d, matrix, sleigh, andrews, car_axis or pendulum)");
    }
  }

  void read_solve(const toml::node& node, SolveSpec& solve) const {
    const std::string path = "solve";
    const auto& t = table(node, path);
    solve.where = at(node, path);
    check_keys(t, path,
               {"t_end", "output_step", "scheme", "rtol", "atol", "atol_velocity",
                "atol_multiplier", "atol_mu", "baumgarte", "penalty", "slaves", "linear_solver",
                "redundant", "max_steps", "max_wall_time"});
    solve.t_end = positive(required(t, path, "t_end"), "solve.t_end");
    solve.output_step = positive(required(t, path, "output_step"), "solve.output_step");
    if (const auto* n = t.get("max_steps")) {
      // A whole number >= 1 (1e6 is accepted: a budget is often written so).
      const double v = number(*n, "solve.max_steps");
      if (!(v >= 1.0) || v != std::floor(v) || v > 1e18) {
        fail(*n, "solve.max_steps", "must be a whole number of steps >= 1 (got " + fmt(v) + ")");
      }
      solve.max_steps = static_cast<long>(v);
    }
    if (const auto* n = t.get("max_wall_time"))
      solve.max_wall_time = positive(*n, "solve.max_wall_time");
    if (const auto* n = t.get("scheme")) solve.scheme = parse_scheme(*n, "solve.scheme");
    if (const auto* n = t.get("rtol")) {
      solve.rtol = positive(*n, "solve.rtol");
      if (solve.rtol < kMinRtol || solve.rtol >= 1.0) {
        fail(*n, "solve.rtol",
             "is out of range: a relative tolerance lies in [" + fmt(kMinRtol) + ", 1) (got " +
                 fmt(solve.rtol) + ")");
      }
    }
    const auto atol_at = [&](const toml::node& n, const std::string& key) {
      const double v = positive(n, key);
      if (v < kMinAtol) {
        fail(n, key,
             "is too small: an absolute tolerance below " + fmt(kMinAtol) +
                 " gives error weights the integrator cannot hold in double precision (got " +
                 fmt(v) + ")");
      }
      return v;
    };
    if (const auto* n = t.get("atol")) solve.atol = atol_at(*n, "solve.atol");
    if (const auto* n = t.get("atol_velocity"))
      solve.atol_velocity = atol_at(*n, "solve.atol_velocity");
    if (const auto* n = t.get("atol_multiplier"))
      solve.atol_multiplier = atol_at(*n, "solve.atol_multiplier");
    if (const auto* n = t.get("atol_mu")) solve.atol_mu = atol_at(*n, "solve.atol_mu");
    if (const auto* n = t.get("baumgarte")) {
      const auto& b = table(*n, "solve.baumgarte");
      check_keys(b, "solve.baumgarte", {"alpha", "beta"});
      if (const auto* a = b.get("alpha"))
        solve.baumgarte_alpha = positive(*a, "solve.baumgarte.alpha");
      if (const auto* be = b.get("beta"))
        solve.baumgarte_beta = positive(*be, "solve.baumgarte.beta");
    }
    if (const auto* n = t.get("penalty")) {
      const auto& pt = table(*n, "solve.penalty");
      check_keys(pt, "solve.penalty", {"weight"});
      if (const auto* w = pt.get("weight"))
        solve.penalty_weight = positive(*w, "solve.penalty.weight");
    }
    if (const auto* n = t.get("slaves")) {
      const auto& arr = array(*n, "solve.slaves");
      for (std::size_t i = 0; i < arr.size(); ++i) {
        solve.slaves.push_back(string(*arr.get(i), index("solve.slaves", i)));
      }
    }
    if (const auto* n = t.get("linear_solver")) {
      const std::string s = string(*n, "solve.linear_solver");
      if (s != "klu" && s != "dense") fail(*n, "solve.linear_solver", "expected 'klu' or 'dense'");
      solve.dense_linear_solver = s == "dense";
    }
    if (const auto* n = t.get("redundant")) {
      const std::string s = string(*n, "solve.redundant");
      if (s != "refuse" && s != "drop") fail(*n, "solve.redundant", "expected 'refuse' or 'drop'");
      solve.drop_redundant = s == "drop";
    }
  }

  [[nodiscard]] Scheme parse_scheme(const toml::node& node, const std::string& path) const {
    const std::string s = string(node, path);
    if (const auto scheme = scheme_from_string(s)) return *scheme;
    fail(node, path, "unknown scheme '" + s + "' (expected " + scheme_names() + ")");
  }

  void read_output(const toml::node& node, OutputSpec& output) const {
    const std::string path = "output";
    const auto& t = table(node, path);
    output.where = at(node, path);
    check_keys(t, path, {"quantities", "file"});
    if (const auto* n = t.get("quantities")) {
      output.quantities.clear();
      const auto& arr = array(*n, "output.quantities");
      for (std::size_t i = 0; i < arr.size(); ++i) {
        const std::string p = index("output.quantities", i);
        const std::string s = string(*arr.get(i), p);
        bool found = false;
        for (Quantity q : {Quantity::displacement, Quantity::velocity, Quantity::reaction,
                           Quantity::multiplier, Quantity::drift, Quantity::energy}) {
          if (s == to_string(q)) {
            for (Quantity seen : output.quantities) {
              if (seen == q) fail(*arr.get(i), p, "'" + s + "' is listed twice");
            }
            output.quantities.push_back(q);
            found = true;
          }
        }
        if (!found) {
          fail(*arr.get(i), p,
               "unknown quantity '" + s +
                   "' (expected displacement, velocity, reaction, multiplier, drift or energy)");
        }
      }
    }
    if (const auto* n = t.get("file")) {
      output.file = string(*n, "output.file");
      if (output.file.empty()) fail(*n, "output.file", "must not be empty");
    }
  }

  [[nodiscard]] SceneSpec read(const toml::table& root) const {
    SceneSpec spec;
    spec.file = file_;
    check_keys(root, "", {"name", "model", "load", "constraint", "initial", "solve", "output"});
    if (const auto* n = root.get("name")) spec.name = string(*n, "name");
    read_model(required(root, "", "model"), spec.model);

    if (const auto* n = root.get("load")) {
      const auto& loads = array(*n, "load");
      for (std::size_t i = 0; i < loads.size(); ++i) {
        const std::string p = index("load", i);
        const auto& t = table(*loads.get(i), p);
        check_keys(t, p, {"dof", "value"});
        LoadSpec load;
        load.where = at(*loads.get(i), p);
        load.dof = string(required(t, p, "dof"), join(p, "dof"));
        load.value = time_function(required(t, p, "value"), join(p, "value"));
        spec.loads.push_back(std::move(load));
      }
    }
    if (const auto* n = root.get("constraint")) {
      const auto& cons = array(*n, "constraint");
      std::set<std::string> names;
      for (std::size_t i = 0; i < cons.size(); ++i) {
        const std::string p = index("constraint", i);
        const auto& t = table(*cons.get(i), p);
        check_keys(t, p, {"name", "terms", "level", "value"});
        ConstraintSpec c;
        c.where = at(*cons.get(i), p);
        c.name = "c" + std::to_string(i + 1);
        if (const auto* nm = t.get("name")) {
          c.name = string(*nm, join(p, "name"));
          if (c.name.empty()) fail(*nm, join(p, "name"), "must not be empty");
          check_name(*nm, join(p, "name"), c.name, "constraint");
        }
        if (!names.insert(c.name).second) {
          fail(*cons.get(i), p, "duplicate constraint name '" + c.name + "'");
        }
        const auto& terms_node = required(t, p, "terms");
        c.terms = dof_values(terms_node, join(p, "terms"));
        if (c.terms.empty())
          fail(terms_node, join(p, "terms"), "a constraint needs at least one term");
        if (const auto* lv = t.get("level")) {
          const std::string s = string(*lv, join(p, "level"));
          if (s == "position") {
            c.level = ConstraintSpec::Level::position;
          } else if (s == "velocity") {
            c.level = ConstraintSpec::Level::velocity;
          } else {
            fail(*lv, join(p, "level"), "expected 'position' or 'velocity'");
          }
        }
        if (const auto* v = t.get("value")) c.value = time_function(*v, join(p, "value"));
        spec.constraints.push_back(std::move(c));
      }
    }
    if (const auto* n = root.get("initial")) {
      const auto& t = table(*n, "initial");
      spec.initial.where = at(*n, "initial");
      check_keys(t, "initial", {"displacement", "velocity", "project"});
      if (const auto* pr = t.get("project")) {
        const auto* b = pr->as_boolean();
        if (b == nullptr) fail(*pr, "initial.project", "expected true or false");
        spec.initial.project = b->get();
      }
      if (const auto* d = t.get("displacement")) {
        spec.initial.displacement = dof_values(*d, "initial.displacement");
      }
      if (const auto* v = t.get("velocity"))
        spec.initial.velocity = dof_values(*v, "initial.velocity");
    }
    read_solve(required(root, "", "solve"), spec.solve);
    if (spec.solve.output_step > spec.solve.t_end) {
      fail(*root.get("solve"), "solve.output_step",
           "is larger than t_end (" + fmt(spec.solve.output_step) + " > " + fmt(spec.solve.t_end) +
               ")");
    }
    if (const auto* n = root.get("output")) read_output(*n, spec.output);
    check_columns(root, spec);
    return spec;
  }

 private:
  std::string file_;
};

// No scene key is more than a few tables deep (solve.baumgarte.alpha); 32 leaves room for anything.
constexpr int kMaxKeyDots = 32;

/// toml++ 3.3 builds (and tears down) the tables of a dotted key or table header recursively, and
/// overflows the stack on keys of tens of thousands of components (`a.a.a. ... = 1`, a segfault).
/// Its own limit (TOML_MAX_NESTED_VALUES, 256) covers nested arrays and inline tables only. So,
/// before parsing: no run of dot-separated key parts outside strings and comments may have more
/// than kMaxKeyDots dots. A number has at most one dot, so values never trip this.
void check_key_depth(const std::string& text, const std::string& file) {
  const std::size_t n = text.size();
  int line = 1, dots = 0;
  std::size_t i = 0;
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      dots = 0;
      ++i;
    } else if (c == '#') {  // a comment runs to the end of the line
      while (i < n && text[i] != '\n') ++i;
    } else if (c == '"' || c == '\'') {  // a string: skipped; a quoted key part continues a run
      const std::string triple(3, c);
      const bool multi = text.compare(i, 3, triple) == 0;
      i += multi ? 3 : 1;
      while (i < n) {
        if (text[i] == '\n') {
          if (!multi) break;  // unterminated: the parser reports it
          ++line;
        }
        if (c == '"' && text[i] == '\\') {  // an escape: skip the escaped character
          if (i + 1 < n && text[i + 1] == '\n') ++line;
          i += 2;
          continue;
        }
        if (multi && text.compare(i, 3, triple) == 0) {
          i += 3;
          while (i < n && text[i] == c) ++i;  // up to two quotes may end the content
          break;
        }
        if (!multi && text[i] == c) {
          ++i;
          break;
        }
        ++i;
      }
    } else {
      const auto u = static_cast<unsigned char>(c);
      if (c == '.') {
        if (++dots > kMaxKeyDots) {
          throw SceneError(scene_message(file, SourcePoint{"", line},
                                         "a dotted key or table header nests more than " +
                                             std::to_string(kMaxKeyDots) + " tables deep"));
        }
      } else if (std::isalnum(u) == 0 && c != '_' && c != '-' && c != '+' && c != ' ' &&
                 c != '\t') {
        dots = 0;  // '=', brackets, braces, commas, ... end a key
      }
      ++i;
    }
  }
}

}  // namespace

SceneSpec parse_scene_text(const std::string& text, const std::string& file) {
  check_key_depth(text, file);
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw SceneError(scene_message(file, SourcePoint{"", static_cast<int>(e.source().begin.line)},
                                   "TOML syntax error: " + std::string(e.description())));
  }
  return Reader(file).read(root);
}

SceneSpec parse_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path + ": cannot read the scene file");
  return parse_scene_text(text.str(), path);
}

}  // namespace condyn
