// A matrix model's coordinates file (docs/scenes.md, "Node coordinates of a matrix model"): node
// ids, positions and the DOFs that move each node, as FE programs export a node table.

#include "models/core/node_map.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "models/core/line_reader.hpp"
#include "models/core/nearest_names.hpp"
#include "models/core/number_cell.hpp"

namespace condyn {

namespace {

constexpr std::array<std::string_view, 7> kNodeColumns = {"node",  "x",     "y",    "z",
                                                          "dof_x", "dof_y", "dof_z"};

/// The cells of a line, split at commas, blanks around each dropped.
std::vector<std::string> cells_of(std::string_view line) {
  std::vector<std::string> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    std::string_view cell =
        line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
    while (!cell.empty() && (cell.front() == ' ' || cell.front() == '\t')) cell.remove_prefix(1);
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\t')) cell.remove_suffix(1);
    out.emplace_back(cell);
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

/// Where each of kNodeColumns is in the header (nullopt: absent); refuses an unknown or repeated
/// one.
std::array<std::optional<std::size_t>, 7> header_columns(const std::vector<std::string>& header,
                                                         int line) {
  std::array<std::optional<std::size_t>, 7> at{};
  for (std::size_t c = 0; c < header.size(); ++c) {
    const auto* known = std::find(kNodeColumns.begin(), kNodeColumns.end(), header[c]);
    if (known == kNodeColumns.end()) {
      throw NodeMapError(line, "unknown column '" + shown_cell(header[c]) +
                                   "' (expected node, x, y and optionally z, dof_x, dof_y, dof_z)");
    }
    auto& slot = at[static_cast<std::size_t>(known - kNodeColumns.begin())];
    if (slot) throw NodeMapError(line, "the column '" + header[c] + "' is named twice");
    slot = c;
  }
  for (std::size_t k = 0; k < 3; ++k) {
    if (!at[k]) {
      throw NodeMapError(line, "the header has no column '" + std::string(kNodeColumns[k]) +
                                   "' (expected node, x, y and optionally z, dof_x, dof_y, dof_z)");
    }
  }
  if (at[6] && !at[3]) throw NodeMapError(line, "a column dof_z needs a column z");
  return at;
}

/// Who claimed each DOF, so that none moves two nodes or two axes.
class DofClaims {
 public:
  explicit DofClaims(const std::vector<std::string>& names) : names_(names) {
    for (std::size_t d = 0; d < names.size(); ++d) index_.emplace(names[d], d);
    owner_.resize(names.size());
  }
  /// Whether `name` is a DOF of the model.
  [[nodiscard]] bool known(const std::string& name) const { return index_.count(name) != 0; }
  void claim(const std::string& name, const std::string& who, int line) {
    const auto it = index_.find(name);
    if (it == index_.end()) {
      const auto near = nearest_names(name, names_);
      throw NodeMapError(line,
                         "no such DOF '" + shown_cell(name) + "'" +
                             (near.empty() ? "" : " (the nearest: " + joined_names(near) + ")"));
    }
    auto& owner = owner_[it->second];
    if (!owner.empty()) {
      throw NodeMapError(line, "DOF '" + name + "' moves " + owner + " already; " + who +
                                   " needs a DOF of its own");
    }
    owner = who;
  }

 private:
  const std::vector<std::string>& names_;
  std::unordered_map<std::string, std::size_t> index_;
  std::vector<std::string> owner_;
};

constexpr std::array<const char*, 3> kAxisNames = {"x", "y", "z"};

/// The DOF a template names for `node` ("ux{node}" → "ux12").
std::string from_template(const std::string& pattern, const std::string& node) {
  std::string out = pattern;
  for (std::size_t at = out.find("{node}"); at != std::string::npos;
       at = out.find("{node}", at + node.size())) {
    out.replace(at, 6, node);
  }
  return out;
}

/// The file read line by line: the header, then a node a row.
class NodeMapReader {
 public:
  NodeMapReader(const std::vector<std::string>& dof_names, const DofTemplates& templates)
      : templates_(templates), claims_(dof_names) {
    by_template_ =
        std::any_of(templates.begin(), templates.end(), [](const auto& t) { return !t.empty(); });
    for (std::size_t a = 0; a < 3; ++a) {
      if (!templates[a].empty() && templates[a].find("{node}") == std::string::npos) {
        throw NodeMapError(0, std::string("the DOF name for ") + kAxisNames[a] + ", '" +
                                  templates[a] + "', holds no {node} (where the node's id goes)");
      }
    }
  }

  void line(const std::vector<std::string>& cells, int n) {
    if (at_) {
      row(cells, n);
    } else {
      header(cells, n);
    }
  }

  NodeMap finish() {
    if (map_.nodes.empty()) throw NodeMapError(0, "no nodes (a header, then one row per node)");
    for (std::size_t a = 0; a < 3 && by_template_; ++a) {
      if (!templates_[a].empty() && !template_used_[a]) {
        throw NodeMapError(0, std::string("the DOF name for ") + kAxisNames[a] + ", '" +
                                  templates_[a] + "', names no DOF of any node (node " +
                                  map_.nodes.front() + " gives '" +
                                  from_template(templates_[a], map_.nodes.front()) + "')");
      }
    }
    const bool moves = std::any_of(map_.dofs.begin(), map_.dofs.end(), [](const auto& d) {
      return !d[0].empty() || !d[1].empty() || !d[2].empty();
    });
    if (!moves) throw NodeMapError(0, "no node has a DOF: nothing would move");
    return std::move(map_);
  }

 private:
  void header(const std::vector<std::string>& cells, int n) {
    at_ = header_columns(cells, n);
    width_ = cells.size();
    map_.dimension = (*at_)[3] ? 3 : 2;
    const bool columns = (*at_)[4] || (*at_)[5] || (*at_)[6];
    if (columns && by_template_) {
      throw NodeMapError(n, "the file has dof_ columns and the scene gives dofs: give one");
    }
    if (map_.dimension == 2 && !templates_[2].empty()) {
      throw NodeMapError(n, "the scene gives a DOF name for z but the file has no column z");
    }
    if (!columns && !by_template_) {
      throw NodeMapError(n,
                         "no dof_x, dof_y columns, and the scene gives no dofs = { x = "
                         "\"ux{node}\", ... }: say which DOF moves each node");
    }
  }

  void row(const std::vector<std::string>& cells, int n) {
    if (cells.size() != width_) {
      throw NodeMapError(n, "has " + std::to_string(cells.size()) + " cells, the header " +
                                std::to_string(width_));
    }
    const auto& at = *at_;
    const std::string& id = cells[*at[0]];
    if (id.empty()) throw NodeMapError(n, "the node id is empty");
    if (const auto [it, fresh] = seen_.emplace(id, n); !fresh) {
      throw NodeMapError(n, "node '" + shown_cell(id) + "' is listed twice (also on line " +
                                std::to_string(it->second) + ")");
    }
    std::array<double, 3> x{};
    std::array<std::string, 3> dofs;
    for (std::size_t a = 0; a < static_cast<std::size_t>(map_.dimension); ++a) {
      const std::string& cell = cells[*at[1 + a]];
      if (const NumberCell kind = parse_number_cell(cell, x[a]); kind != NumberCell::ok) {
        throw NodeMapError(n, std::string(kAxisNames[a]) + " '" + shown_cell(cell) + "' " +
                                  number_cell_problem(kind));
      }
      if (!std::isfinite(x[a])) {
        throw NodeMapError(
            n, std::string(kAxisNames[a]) + " '" + shown_cell(cell) + "' is not finite");
      }
      const std::string who = "node " + id + " along " + kAxisNames[a];
      if (by_template_) {
        const std::string name =
            templates_[a].empty() ? std::string() : from_template(templates_[a], id);
        if (!claims_.known(name)) continue;  // none: a node held fixed, its DOF condensed out
        claims_.claim(name, who, n);
        template_used_[a] = true;
        dofs[a] = name;
      } else if (at[4 + a] && !cells[*at[4 + a]].empty()) {
        dofs[a] = cells[*at[4 + a]];
        claims_.claim(dofs[a], who, n);
      }
    }
    map_.nodes.push_back(id);
    map_.position.push_back(x);
    map_.dofs.push_back(std::move(dofs));
  }

  const DofTemplates& templates_;
  bool by_template_ = false;
  DofClaims claims_;
  std::optional<std::array<std::optional<std::size_t>, 7>> at_;  // the header's columns
  std::size_t width_ = 0;
  std::unordered_map<std::string, int> seen_;  // node id → its line
  std::array<bool, 3> template_used_{};
  NodeMap map_;
};

}  // namespace

NodeMap read_node_map(std::istream& in, const std::vector<std::string>& dof_names,
                      const DofTemplates& templates) {
  NodeMapReader reader(dof_names, templates);
  LineReader lines(in);
  std::string_view line;
  while (lines.next(line)) {
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line[first] == '#') continue;
    reader.line(cells_of(line), lines.line_number());
  }
  if (lines.failed()) throw NodeMapError(0, "the file could not be read");
  return reader.finish();
}

}  // namespace condyn
