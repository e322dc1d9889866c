#include "models/scene/scene_readers.hpp"

#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <utility>

namespace condyn {

namespace {

/// DOF and constraint names become CSV column names (scene-format.md, "Output"), written as
/// they are, unquoted: a name may not hold what would split or quote a field (a comma, a double
/// quote), control characters (line breaks, tabs), nor begin or end with a space (CSV readers
/// trim it). Everything else is the user's: spaces inside, slashes, UTF-8.
constexpr std::string_view kNameBreakers = ",\"";

std::string describe_char(char c) {
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
std::string printable(const std::string& name) {
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

}  // namespace

void SceneReader::check_name(const toml::node& node, const std::string& path,
                             const std::string& name, const char* what) const {
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
/// distinct: the DOFs' columns (u, vel_u, acc_u, reaction_u), the multipliers' (lambda_c) and the
/// fixed ones. Names are checked here, where they have a line; the message names the later one.
void SceneReader::check_columns(const toml::table& root, const SceneSpec& spec) const {
  std::map<std::string, std::string> owner = {{"t", "the time column"},
                                              {"drift_position", "a drift column"},
                                              {"drift_velocity", "a drift column"}};
  for (const auto column : kEnergyColumns) owner[std::string(column)] = "an energy column";
  // `claimant`: who gives the column, as the message names it ("DOF 'x'").
  const auto claim = [&](const std::string& column, const std::string& who, const toml::node& node,
                         const std::string& path, const std::string& claimant) {
    const auto [it, fresh] = owner.emplace(column, who);
    if (!fresh) {
      fail(node, path,
           claimant + " gives the column '" + column + "', which is " + "already " + it->second +
               " (CSV columns must be distinct under every quantity)");
    }
  };
  // " (what, line N)", " (what)" for a node with no line (a scene from a Python dict), nothing
  // when there is neither.
  const auto note = [](const std::string& what, const toml::node& node) {
    const auto line = node.source().begin.line;
    const std::string at = line > 0 ? "line " + std::to_string(line) : std::string();
    if (what.empty() && at.empty()) return std::string();
    return " (" + what + (!what.empty() && !at.empty() ? ", " : "") + at + ")";
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
            {"acc_", "acceleration"},
            {"acc_abs_", "absolute acceleration"},
            {"reaction_", "reaction"}}) {
        claim(prefix + d, "the " + quantity + " column of DOF '" + d + "'", *dofs->get(i), p,
              "DOF '" + d + "'");
      }
    }
  }
  // Rows a truss adds, named like constraints: fix_<dof> per supported DOF, rigid_i_j per
  // rigid member (build_model names them so).
  if (spec.model.type == ModelSpec::Type::truss2d || spec.model.type == ModelSpec::Type::truss3d) {
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
      const std::string row = "rigid_" + std::to_string(m.node_i) + "_" + std::to_string(m.node_j);
      owner.emplace("lambda_" + row, "the multiplier column of the row '" + row + "' that " +
                                         index("model.members", e) + " adds");
    }
  }
  const auto* cons = root.get_as<toml::array>("constraint");
  for (std::size_t i = 0; i < spec.constraints.size() && cons != nullptr; ++i) {
    const std::string& c = spec.constraints[i].name;
    const auto& t = *cons->get(i)->as_table();
    const bool named = t.get("name") != nullptr;
    const toml::node* where = named ? t.get("name") : cons->get(i);
    // Which constraint, where, and whether its name is the default one.
    const std::string who =
        index("constraint", i) + " '" + c + "'" + note(named ? "" : "its default name", *where);
    claim("lambda_" + c, "the multiplier column of " + who, *where,
          named ? join(index("constraint", i), "name") : index("constraint", i), who);
  }
  const auto* blocks = root.get_as<toml::array>("constraint_block");
  for (std::size_t i = 0; i < spec.constraint_blocks.size() && blocks != nullptr; ++i) {
    const auto& b = spec.constraint_blocks[i];
    const auto& t = *blocks->get(i)->as_table();
    const bool named = t.get("name") != nullptr;
    const toml::node* where = named ? t.get("name") : blocks->get(i);
    const std::string path =
        named ? join(index("constraint_block", i), "name") : index("constraint_block", i);
    for (Eigen::Index k = 1; k <= b.A.matrix.rows(); ++k) {
      const std::string c = b.prefix + std::to_string(k);
      // Row k of a block is named prefix + k: say so, and whether the prefix is the default.
      const std::string who = "row " + std::to_string(k) + " of " + index("constraint_block", i) +
                              ", '" + c + "'" +
                              note(std::string(named ? "its name" : "its default prefix") + " '" +
                                       b.prefix + "' and the row number",
                                   *where);
      claim("lambda_" + c, "the multiplier column of " + who, *where, path, who);
    }
  }
}

}  // namespace condyn
