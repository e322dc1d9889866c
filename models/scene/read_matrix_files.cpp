// Scene keys that name Matrix Market files (scene-format.md, "Matrices and vectors from files"):
// the matrix model's M, K, C given by files and [[constraint_block]] (Rayleigh damping:
// read_rayleigh.cpp). Files are read here, at parse time, so a bad file is refused with the
// scene's key and line.

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "models/core/number_cell.hpp"
#include "models/scene/matrix_market.hpp"
#include "models/scene/scene_readers.hpp"

namespace condyn {

namespace {

/// The first pair (i, j) where a differs from aᵀ by more than a few ulps of the pair's size; none
/// when a is symmetric. Sparse: O(nnz log nnz), no dense n x n.
std::optional<std::array<Eigen::Index, 2>> asymmetry(const Eigen::SparseMatrix<double>& a) {
  const Eigen::SparseMatrix<double> at = a.transpose();
  for (Eigen::Index k = 0; k < a.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(a, k); it; ++it) {
      const double x = it.value(), y = at.coeff(it.row(), it.col());
      // The inline rows' rule (read_model.cpp): a few ulps of the entries' size.
      if (std::abs(x - y) > 1e-12 * std::max({std::abs(x), std::abs(y), 1e-300})) {
        return std::array<Eigen::Index, 2>{it.row(), it.col()};
      }
    }
  }
  return std::nullopt;
}

/// "entry (i,j) = a but (j,i) = b (…)", 1-based, each value to round-trip precision and their
/// difference relative to the tolerance, so that values alike to ten digits are told apart.
std::string asymmetry_text(Eigen::Index i, Eigen::Index j, double a, double b) {
  const double size = std::max({std::abs(a), std::abs(b), 1e-300});
  return "entry (" + std::to_string(i + 1) + "," + std::to_string(j + 1) +
         ") = " + shortest_number(a) + " but (" + std::to_string(j + 1) + "," +
         std::to_string(i + 1) + ") = " + shortest_number(b) + " (they differ by " +
         shortest_number(std::abs(a - b) / size) + " of their size; symmetric means within 1e-12)";
}

}  // namespace

FileMatrix SceneReader::matrix_file(const toml::node& node, const std::string& path,
                                    const MarketExpectation& expect) const {
  const auto& t = table(node, path);
  check_keys(t, path, {"file"});
  const auto& file_node = required(t, path, "file");
  return read_market(file_node, join(path, "file"), expect);
}

MarketExpectation SceneReader::pattern_size() const {
  MarketExpectation e;
  if (matrix_dofs_ == 0) return e;
  e.rows = matrix_dofs_;
  e.cols = 1;
  e.because = "a load pattern is n x 1 (n = " + std::to_string(matrix_dofs_) + " DOFs)";
  return e;
}

MarketExpectation SceneReader::block_size() const {
  MarketExpectation e;
  e.rows_need_entries = true;
  if (matrix_dofs_ == 0) return e;
  e.cols = matrix_dofs_;
  e.because = "a constraint block needs one column per DOF (" + std::to_string(matrix_dofs_) + ")";
  return e;
}

FileMatrix SceneReader::read_market(const toml::node& file_node, const std::string& key,
                                    const MarketExpectation& expect) const {
  const bool rows_need_entries = expect.rows_need_entries;
  FileMatrix out;
  out.file = file_name(file_node, key);
  out.where = at(file_node, key);
  if (arrays_ != nullptr) {
    if (const auto it = arrays_->matrices.find(out.file); it != arrays_->matrices.end()) {
      // A matrix handed over in memory: the file reader's own check of entries, finiteness,
      // reported under the key the array was given for (its name is "<array KEY>"), not the
      // `file` key the module put in its place.
      out.matrix = it->second;
      const std::size_t prefix = std::string_view("<array ").size();
      const std::string array_key = out.in_memory() && out.file.ends_with('>')
                                        ? out.file.substr(prefix, out.file.size() - prefix - 1)
                                        : key;
      // A block's or a pattern's size first, as a file's size line is checked before its
      // entries (the model's matrices are checked against each other once all are read).
      if (!expect.rows_are_dofs && ((expect.rows > 0 && out.matrix.rows() != expect.rows) ||
                                    (expect.cols > 0 && out.matrix.cols() != expect.cols))) {
        fail(file_node, array_key,
             "is " + std::to_string(out.matrix.rows()) + " x " + std::to_string(out.matrix.cols()) +
                 " but " + expect.because);
      }
      if (rows_need_entries && out.matrix.nonZeros() < out.matrix.rows()) {
        fail(file_node, array_key,
             "has " + std::to_string(out.matrix.rows()) + " rows but " +
                 std::to_string(out.matrix.nonZeros()) +
                 " stored entries, so some row has none: every constraint row needs a coefficient");
      }
      for (Eigen::Index k = 0; k < out.matrix.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator e(out.matrix, k); e; ++e) {
          if (!std::isfinite(e.value())) {
            fail(file_node, array_key,
                 "entry (" + std::to_string(e.row() + 1) + "," + std::to_string(e.col() + 1) +
                     ") is " + fmt(e.value()) + ": entries must be finite");
          }
        }
      }
      return out;
    }
  }
  // Relative to the scene file's folder (a scene given as text: the working directory).
  const std::filesystem::path resolved =
      std::filesystem::path(file_).parent_path() / std::filesystem::path(out.file);
  input_files_.push_back(resolved.string());
  try {
    out.matrix = read_matrix_market(resolved.string(), expect).matrix;
  } catch (const MatrixMarketError& e) {
    const std::string where =
        resolved.string() + (e.line() > 0 ? ":" + std::to_string(e.line()) : std::string());
    fail(file_node, key, where + ": " + e.what());
  }
  return out;
}

namespace {

using MatrixFiles = std::array<std::pair<std::string_view, FileMatrix*>, 3>;

/// Refuses a table under mass, stiffness or damping that is none of the forms (an empty one, a
/// misspelt key), naming every form.
void refuse_unknown_tables(const TomlAccess& r, const toml::table& t, const std::string& path) {
  for (const std::string_view key : {"mass", "stiffness", "damping"}) {
    const auto* n = t.get(key);
    if (n == nullptr || !n->is_table()) continue;
    const auto& entries = *n->as_table();
    if (entries.contains("file") ||
        (key == "damping" && (entries.contains("rayleigh") || entries.contains("modal")))) {
      continue;
    }
    r.fail(*n, TomlAccess::join(path, std::string(key)),
           std::string(entries.empty() ? "is an empty table" : "is a table without a known key") +
               ": expected rows ([[...], ...]) or { file = \"" +
               (key == "mass"        ? "M"
                : key == "stiffness" ? "K"
                                     : "C") +
               ".mtx\" }" +
               (key == "damping" ? std::string(", { rayleigh = [a0, a1] } or { modal = ratio }")
                                 : std::string()));
  }
}

/// The matrices given by files, read in the order of `files`, each checked at its size line
/// against the names' count, else against the first file's size; returns the first (null when
/// none is a file).
const FileMatrix* read_matrix_files(const SceneReader& r, const toml::table& t,
                                    const std::string& path, const MatrixFiles& files) {
  const auto is_file = [&](std::string_view key) {
    const auto* n = t.get(key);
    return n != nullptr && n->is_table() && n->as_table()->contains("file") &&
           !n->as_table()->contains("rayleigh") && !n->as_table()->contains("modal");
  };
  const FileMatrix* first = nullptr;
  // The size each must declare, checked at its size line: the names' count, else the first's.
  MarketExpectation expected;
  expected.rows_are_dofs = true;
  if (const auto* d = t.get("dofs"); d != nullptr && d->is_array() && !d->as_array()->empty()) {
    expected.rows = expected.cols = static_cast<long long>(d->as_array()->size());
    expected.because = "model.dofs names " + std::to_string(expected.rows) + " DOFs";
  }
  for (const auto& [key, out] : files) {
    if (key != "damping") (void)r.required(t, path, key);
    if (!is_file(key)) continue;
    *out = r.matrix_file(*t.get(key), TomlAccess::join(path, std::string(key)), expected);
    if (first != nullptr) continue;
    first = out;
    if (expected.rows == 0 && out->matrix.rows() == out->matrix.cols()) {
      expected.rows = expected.cols = out->matrix.rows();
      const SourcePoint where = r.at(*t.get(key), TomlAccess::join(path, std::string(key)));
      expected.because = out->file + " (" + where.path +
                         (where.line > 0 ? ", line " + std::to_string(where.line) : "") + ") is " +
                         std::to_string(expected.rows) + " x " + std::to_string(expected.rows);
      expected.advice =
          "mass, stiffness and damping must have one size; is one of the two files the wrong "
          "one, or its size line wrong?";
    }
  }
  return first;
}

/// model.dofs: names, each a valid and distinct DOF name, at least one.
std::vector<std::string> read_dof_names(const SceneReader& r, const toml::table& t,
                                        const std::string& path) {
  std::vector<std::string> names;
  const auto& dofs = r.array(r.required(t, path, "dofs"), "model.dofs");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    const std::string at = TomlAccess::index("model.dofs", i);
    const std::string name = r.string(*dofs.get(i), at);
    if (name.empty()) r.fail(*dofs.get(i), at, "a DOF name must not be empty");
    r.check_name(*dofs.get(i), at, name, "DOF");
    if (!seen.insert(name).second) r.fail(*dofs.get(i), at, "duplicate DOF name '" + name + "'");
    names.push_back(name);
  }
  if (names.empty()) r.fail(dofs, "model.dofs", "at least one DOF is needed");
  return names;
}

/// Each matrix given by a file: n x n (`first` the first file read) and symmetric.
void check_file_matrices(const TomlAccess& r, const toml::table& t, const std::string& path,
                         const MatrixFiles& files, const FileMatrix* first, Eigen::Index n) {
  for (const auto& [key, out] : files) {
    if (!out->given()) continue;
    const auto& node = *t.get(key)->as_table()->get("file");
    // A matrix handed over in memory (Python) is named by its own key, not the `file` key the
    // module put in its place.
    const bool in_memory = out->in_memory();
    const std::string p = in_memory
                              ? TomlAccess::join(path, std::string(key))
                              : TomlAccess::join(TomlAccess::join(path, std::string(key)), "file");
    const std::string name = in_memory ? "the array" : out->file;
    const auto& a = out->matrix;
    if (a.rows() != n || a.cols() != n) {
      const std::string size =
          name + " is " + std::to_string(a.rows()) + " x " + std::to_string(a.cols());
      if (t.contains("dofs")) r.fail(node, p, size + " for " + std::to_string(n) + " DOFs");
      if (out == first) r.fail(node, p, size + ": a square matrix is needed");
      r.fail(node, p,
             size + " but " + first->file + " is " + std::to_string(n) + " x " + std::to_string(n));
    }
    if (const auto ij = asymmetry(a)) {
      const auto [i, j] = *ij;
      r.fail(node, p,
             name + " is not symmetric: " + asymmetry_text(i, j, a.coeff(i, j), a.coeff(j, i)));
    }
  }
}

/// The inline matrix at `key`: `rows` rows of `rows` entries, symmetric.
void read_square(const TomlAccess& r, const toml::table& t, const std::string& path,
                 std::string_view key, std::size_t rows, std::vector<std::vector<double>>& out,
                 SourcePoint& where) {
  const std::string p = TomlAccess::join(path, std::string(key));
  const auto& mat = r.required(t, path, key);
  where = r.at(mat, p);
  out = r.dense_matrix(mat, p);
  if (out.size() != rows) {
    r.fail(mat, p,
           "has " + std::to_string(out.size()) + " rows for " + std::to_string(rows) + " DOFs");
  }
  for (std::size_t i = 0; i < rows; ++i) {
    if (out[i].size() != rows) {
      r.fail(*r.array(mat, p).get(i), TomlAccess::index(p, i),
             "has " + std::to_string(out[i].size()) + " entries for " + std::to_string(rows) +
                 " DOFs");
    }
  }
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const double a = out[i][j], b = out[j][i];
      // Symmetry to a few ulps of the entries' size: a scene writes these by hand.
      if (std::abs(a - b) > 1e-12 * std::max({std::abs(a), std::abs(b), 1e-300})) {
        r.fail(mat, p,
               "is not symmetric: " + asymmetry_text(static_cast<Eigen::Index>(i),
                                                     static_cast<Eigen::Index>(j), a, b));
      }
    }
  }
}

}  // namespace

void SceneReader::read_matrix_model(const toml::table& t, ModelSpec& model) const {
  const std::string path = "model";
  check_keys(t, path, {"type", "dofs", "mass", "stiffness", "damping", "coordinates"});
  model.type = ModelSpec::Type::matrix;
  refuse_unknown_tables(*this, t, path);
  // Files first: when `dofs` is omitted their size fixes n.
  const MatrixFiles files{{{"mass", &model.mass_file},
                           {"stiffness", &model.stiffness_file},
                           {"damping", &model.damping_file}}};
  const FileMatrix* first = read_matrix_files(*this, t, path, files);
  if (const auto* d = t.get("dofs"); d != nullptr || first == nullptr) {
    model.dofs = read_dof_names(*this, t, path);
  } else {
    const auto n = static_cast<std::size_t>(first->matrix.rows());
    model.dofs.reserve(n);
    for (std::size_t i = 1; i <= n; ++i) model.dofs.push_back("u" + std::to_string(i));
  }
  const auto n = static_cast<Eigen::Index>(model.dofs.size());
  matrix_dofs_ = n;  // load patterns and constraint blocks are checked against it as read
  check_file_matrices(*this, t, path, files, first, n);
  const std::size_t rows = model.dofs.size();
  if (!model.mass_file.given())
    read_square(*this, t, path, "mass", rows, model.mass, model.mass_where);
  if (!model.stiffness_file.given()) {
    read_square(*this, t, path, "stiffness", rows, model.stiffness, model.stiffness_where);
  }
  if (const auto* d = t.get("damping"); d != nullptr && !model.damping_file.given()) {
    if (d->is_table()) {
      read_rayleigh(*d, "model.damping", model);
    } else {
      read_square(*this, t, path, "damping", rows, model.damping, model.damping_where);
    }
  }
  if (const auto* c = t.get("coordinates")) read_coordinates(*c, model);
}

void SceneReader::read_constraint_blocks(const toml::node& node,
                                         std::vector<ConstraintBlockSpec>& out) const {
  const auto& blocks = array(node, "constraint_block");
  std::set<std::string> prefixes;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const std::string p = index("constraint_block", i);
    const auto& t = table(*blocks.get(i), p);
    check_keys(t, p, {"file", "name", "value", "scale"});
    ConstraintBlockSpec b;
    b.where = at(*blocks.get(i), p);
    b.prefix = "block" + std::to_string(i + 1) + "_";
    if (const auto* nm = t.get("name")) {
      b.prefix = string(*nm, join(p, "name"));
      if (b.prefix.empty()) fail(*nm, join(p, "name"), "must not be empty");
      check_name(*nm, join(p, "name"), b.prefix, "constraint");
    }
    if (!prefixes.insert(b.prefix).second) {
      fail(*blocks.get(i), p, "duplicate constraint block name '" + b.prefix + "'");
    }
    b.A = read_market(required(t, p, "file"), join(p, "file"), block_size());
    if (const auto* v = t.get("value")) {
      MarketExpectation value;
      value.rows = b.A.matrix.rows();
      value.cols = 1;
      value.because = "the right-hand side of " + b.A.file + " (" +
                      std::to_string(b.A.matrix.rows()) + " rows) must be " +
                      std::to_string(b.A.matrix.rows()) + " x 1";
      b.g = matrix_file(*v, join(p, "value"), value);
      if (b.g.matrix.cols() != 1 || b.g.matrix.rows() != b.A.matrix.rows()) {
        fail(*v->as_table()->get("file"), join(join(p, "value"), "file"),
             b.g.file + " is " + std::to_string(b.g.matrix.rows()) + " x " +
                 std::to_string(b.g.matrix.cols()) + ": the right-hand side of " + b.A.file + " (" +
                 std::to_string(b.A.matrix.rows()) + " rows) must be " +
                 std::to_string(b.A.matrix.rows()) + " x 1");
      }
    }
    if (const auto* s = t.get("scale")) b.scale = time_function(*s, join(p, "scale"));
    out.push_back(std::move(b));
  }
}

}  // namespace condyn
