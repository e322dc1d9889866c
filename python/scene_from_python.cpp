// A Python dict → toml::table (and matrices by name), parsed by the scene parser itself: the
// dict is read exactly as a file with the same content would be, and refused with the same
// messages. numpy and scipy.sparse matrices go over as sparse Eigen matrices, never dense and
// never through a file.

#include "python/scene_from_python.hpp"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "models/scene/matrix_market.hpp"
#include "models/scene/scene_parser.hpp"
#include "models/scene/scene_table.hpp"

namespace py = pybind11;

namespace condyn::python {

namespace {

/// Nested dicts and lists deeper than this are refused (the parser's own limit for files).
constexpr int kMaxDepth = 32;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw SceneError(scene_message(kDictFile, SourcePoint{path, 0}, problem));
}

std::string type_name(const py::handle& value) {
  return py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>();
}

/// A str as UTF-8. A lone surrogate (U+D800 to U+DFFF) has no UTF-8 form: refused naming `path`
/// and, before the problem, `subject` ("a key ").
std::string text_of(const py::handle& s, const std::string& path, const std::string& subject = "") {
  try {
    return s.cast<std::string>();
  } catch (const py::cast_error&) {
    fail(path, subject +
                   "is not valid text: it holds a lone surrogate (U+D800 to U+DFFF), which "
                   "has no UTF-8 form");
  }
}

/// A file name (a str or an os.PathLike) as the system's bytes: os.fsencode, so that a name read
/// from the system with undecodable bytes (Python's surrogateescape) opens the same file.
std::string file_name_of(const py::handle& name, const std::string& path) {
  py::object bytes;
  try {
    bytes = py::module_::import("os").attr("fsencode")(name);
  } catch (const py::error_already_set&) {
    fail(path, "is not a file name this system can encode (a lone surrogate?)");
  }
  if (!py::isinstance<py::bytes>(bytes)) fail(path, "is not a file name");
  return bytes.cast<std::string>();
}

bool is_sparse(const py::handle& value) {
  return py::hasattr(value, "tocoo") && py::hasattr(value, "shape") && py::hasattr(value, "nnz");
}

/// Keys whose value is a matrix: a numpy array or scipy.sparse matrix there becomes one.
bool takes_matrix(const std::string& parent, const std::string& key) {
  if (parent == "model") return key == "mass" || key == "stiffness" || key == "damping";
  if (parent.rfind("load[", 0) == 0) return key == "pattern";
  if (parent == "ground_motion") return key == "influence";
  if (parent.rfind("constraint_block[", 0) == 0) return key == "file" || key == "value";
  return false;
}

/// Whether `data` is a numpy masked array with an entry masked: its data there is no value (tolist
/// gives None, the raw buffer whatever was stored).
bool has_masked(const py::handle& data) {
  return py::isinstance<py::array>(data) && py::hasattr(data, "mask") &&
         py::module_::import("numpy.ma").attr("is_masked")(data).cast<bool>();
}

constexpr const char* kMasked =
    "a masked numpy value is not a scene value (fill the masked entries first)";

/// Real entries as float64 (integers converted); anything else refused, booleans included: a
/// mask passed by mistake would be a matrix of ones and zeros.
py::array_t<double> real_entries(const py::handle& data, const std::string& path) {
  if (has_masked(data)) fail(path, kMasked);
  const auto array = py::array::ensure(data);
  if (!array) fail(path, "the entries are not an array of numbers");
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    fail(path, "entries must be real numbers (the array's dtype is " +
                   py::str(array.dtype()).cast<std::string>() + ")");
  }
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
}

std::vector<long long> indices(const py::handle& data) {
  const auto a = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(data);
  return {a.data(), a.data() + a.size()};
}

/// A matrix's size refused before anything of it is held, by the checks a file's size line gets
/// (models/scene/matrix_market.hpp): a scipy.sparse matrix of 10⁸ x 10⁸ with 3 entries was held
/// (and its 10⁸ DOFs named) in full before the scene was refused for another reason.
void check_size(long long rows, long long cols, double entries, bool rows_are_dofs,
                const std::string& path) {
  if (rows < 1 || cols < 1) {
    fail(path, "the matrix is " + std::to_string(rows) + " x " + std::to_string(cols) +
                   ": it has no entries");
  }
  if (const auto refusal = size_range_refusal(rows, cols)) fail(path, *refusal);
  if (const auto refusal = holding_refusal(rows, cols, entries, rows_are_dofs)) {
    fail(path, "the array is " + std::to_string(rows) + " x " + std::to_string(cols) + " with " +
                   std::to_string(static_cast<long long>(entries)) +
                   " stored entries: " + *refusal);
  }
}

/// A scipy.sparse matrix or a numpy array (1-D: a column) as a sparse matrix; zeros of a dense
/// array are not stored, duplicates of a sparse one are summed (as a Matrix Market file's are).
/// `rows_are_dofs`: M, C or K, whose size is also checked against integrating that many DOFs.
Eigen::SparseMatrix<double> sparse_of(const py::handle& value, const std::string& path,
                                      bool rows_are_dofs) {
  std::vector<Eigen::Triplet<double>> entries;
  long long rows = 0, cols = 0;
  if (is_sparse(value)) {
    const auto shape = value.attr("shape").cast<py::tuple>();
    if (shape.size() != 2) fail(path, "a sparse matrix must have 2 dimensions");
    rows = shape[0].cast<long long>();
    cols = shape[1].cast<long long>();
    check_size(rows, cols, value.attr("nnz").cast<double>(), rows_are_dofs, path);
    const py::object coo = value.attr("tocoo")();
    const auto r = indices(coo.attr("row")), c = indices(coo.attr("col"));
    const auto v = real_entries(coo.attr("data"), path);
    entries.reserve(r.size());
    for (std::size_t k = 0; k < r.size(); ++k) {
      entries.emplace_back(static_cast<Eigen::Index>(r[k]), static_cast<Eigen::Index>(c[k]),
                           v.data()[k]);
    }
  } else {
    // The declared size first, as if every entry were zero: a strided view (numpy's
    // broadcast_to) declares 10⁸ x 10⁸ in a few bytes, and real_entries copies it whole.
    const auto declared = py::array::ensure(value);
    if (declared && declared.ndim() >= 1 && declared.ndim() <= 2) {
      rows = declared.shape(0);
      cols = declared.ndim() == 2 ? declared.shape(1) : 1;
      check_size(rows, cols, 0.0, rows_are_dofs, path);
    }
    const auto a = real_entries(value, path);
    if (a.ndim() != 1 && a.ndim() != 2) {
      fail(path, "a matrix must have 1 or 2 dimensions (this array has " +
                     std::to_string(a.ndim()) + ")");
    }
    rows = a.shape(0);
    cols = a.ndim() == 2 ? a.shape(1) : 1;
    const double* x = a.data();
    const auto size = static_cast<std::size_t>(rows * cols);
    // NaN != 0: kept, so the parser refuses it.
    const auto stored = std::count_if(x, x + size, [](double e) { return e != 0.0; });
    check_size(rows, cols, static_cast<double>(stored), rows_are_dofs, path);
    entries.reserve(static_cast<std::size_t>(stored));
    for (std::size_t k = 0; k < size; ++k) {
      if (x[k] != 0.0) {
        entries.emplace_back(static_cast<Eigen::Index>(k) / cols,
                             static_cast<Eigen::Index>(k) % cols, x[k]);
      }
    }
  }
  Eigen::SparseMatrix<double> m(rows, cols);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  return m;
}

/// Whether `value` (a dict) is a tabulated time function: its `file` may then be an array.
bool is_table_function(const py::handle& value) {
  const auto d = py::reinterpret_borrow<py::dict>(value);
  return d.contains("type") && py::isinstance<py::str>(d["type"]) &&
         py::str(d["type"]).equal(py::str("table"));
}

/// An nt x 2 array of (time, value) samples as the CSV text a table file would hold (17
/// significant digits: every double reads back exactly), for the file reader's own parser.
std::string table_text(const py::handle& data, const std::string& path) {
  const auto a = real_entries(data, path);
  if (a.ndim() != 2 || a.shape(1) != 2) {
    fail(path, "a table's samples as an array must be n x 2 (time, value); this one is " +
                   std::string(a.ndim() == 2
                                   ? std::to_string(a.shape(0)) + " x " + std::to_string(a.shape(1))
                                   : std::to_string(a.ndim()) + "-dimensional"));
  }
  std::string text = "t,value\n";
  char cell[32];
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    for (py::ssize_t j = 0; j < 2; ++j) {
      std::snprintf(cell, sizeof cell, "%.17g", a.data()[2 * i + j]);
      text += cell;
      text += j == 0 ? ',' : '\n';
    }
  }
  return text;
}

class Converter {
 public:
  explicit Converter(ArrayInputs& arrays) : arrays_(arrays) {}

  toml::table table(const py::handle& value, const std::string& path, int depth) {
    if (!py::isinstance<py::dict>(value)) {
      fail(path, "expected a dict (a table), got " + type_name(value));
    }
    toml::table out;
    for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(k)) {
        fail(path, "keys must be strings (got a " + type_name(k) + " key)");
      }
      const auto key = text_of(k, path, "a key ");
      const std::string p = path.empty() ? key : path + "." + key;
      if (key == "file" && py::isinstance<py::array>(v) && is_table_function(value)) {
        // A recorded time function's samples, kept by name as a table file's text.
        const std::string name = "<array " + p + ">";
        arrays_.tables[name] = table_text(v, p);
        out.insert(key, name);
      } else if ((py::isinstance<py::array>(v) || is_sparse(v)) && takes_matrix(path, key)) {
        // Kept by name; the scene gets `file = NAME` (constraint_block.file) or `{ file = NAME }`.
        const std::string name = "<array " + (key == "file" ? path : p) + ">";
        arrays_.matrices[name] = sparse_of(v, p, path == "model");
        if (key == "file") {
          out.insert(key, name);
        } else {
          toml::table file;
          file.insert("file", name);
          out.insert(key, std::move(file));
        }
      } else {
        insert_value(out, key, v, p, depth);
      }
    }
    return out;
  }

 private:
  /// One scene value; a plain function (no generic sink), so nesting costs no instantiation.
  using Value = std::variant<bool, std::string, int64_t, double, toml::table, toml::array>;

  Value emit(const py::handle& v, const std::string& p, int depth) {
    if (depth > kMaxDepth) fail(p, "dicts and lists nest more than 32 deep");
    if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
    const bool file_key = p.size() > 5 && p.compare(p.size() - 5, 5, ".file") == 0;
    // Before numpy's scalars: numpy's str_ is a str (and has a dtype, of kind 'U').
    if (py::isinstance<py::str>(v)) return file_key ? file_name_of(v, p) : text_of(v, p);
    // numpy's bool scalar is no Python bool, and its __float__ would make True a coefficient of 1.
    if (py::hasattr(v, "dtype") && !py::isinstance<py::array>(v)) {
      const std::string kind = py::str(v.attr("dtype").attr("kind")).cast<std::string>();
      if (kind == "b") return v.attr("item")().cast<bool>();
      // Only numbers: a complex one's __float__ drops the imaginary part (with a warning only),
      // a timedelta64's or datetime64's would be a duration or a date.
      if (kind != "i" && kind != "u" && kind != "f") {
        fail(p, "a numpy " + py::str(v.attr("dtype")).cast<std::string>() +
                    " is not a scene value (numbers, strings, booleans, lists, dicts, numpy "
                    "arrays)");
      }
    }
    if (PyComplex_Check(v.ptr())) fail(p, "a complex number is not a scene value");
    if (py::hasattr(v, "__fspath__")) {
      // A pathlib.Path (any os.PathLike) for a file key, as the scene argument itself takes one.
      if (!py::isinstance<py::str>(py::module_::import("os").attr("fspath")(v))) {
        fail(p, "a file path must be text, not bytes");
      }
      return file_name_of(v, p);
    }
    if (py::isinstance<py::dict>(v)) return table(v, p, depth + 1);
    if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v) ||
        py::isinstance<py::array>(v)) {
      // A masked entry (numpy.ma.masked) would come out of tolist() as None.
      if (has_masked(v)) fail(p, kMasked);
      const py::object items =
          py::isinstance<py::array>(v) ? v.attr("tolist")() : py::reinterpret_borrow<py::object>(v);
      if (!py::isinstance<py::list>(items) && !py::isinstance<py::tuple>(items)) {
        return emit(items, p, depth);  // a 0-d array: its scalar
      }
      toml::array out;
      std::size_t i = 0;
      for (const auto& item : items) {
        const std::string ip = p + "[" + std::to_string(++i) + "]";
        std::visit([&out](auto&& x) { out.push_back(std::forward<decltype(x)>(x)); },
                   emit(item, ip, depth + 1));
      }
      return out;
    }
    if (py::isinstance<py::int_>(v) || (py::hasattr(v, "__index__") && !is_sparse(v))) {
      try {
        return static_cast<int64_t>(
            py::int_(py::reinterpret_borrow<py::object>(v)).cast<long long>());
      } catch (const py::cast_error&) {
        fail(p, "the integer " + py::str(v).cast<std::string>() + " is out of range");
      }
    }
    if (py::isinstance<py::float_>(v) || py::hasattr(v, "__float__")) {
      double x = 0.0;
      try {
        x = py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>();
      } catch (const py::error_already_set& e) {  // its __float__ raised (an overflow, a type)
        fail(p, "a " + type_name(v) + " that is not a number: " + std::string(e.what()));
      }
      // A Decimal or Fraction below the double range becomes 0: refused, as the TOML reader
      // refuses 1e-400.
      if (x == 0.0 && PyObject_RichCompareBool(v.ptr(), py::int_(0).ptr(), Py_NE) == 1) {
        fail(p, py::str(v).cast<std::string>() +
                    " is nonzero but below the smallest double (4.9e-324) in magnitude, and "
                    "would be read as 0 (write 0 if 0 is meant)");
      }
      PyErr_Clear();  // a comparison that raised leaves the value as converted
      return x;
    }
    if (is_sparse(v)) {
      fail(p,
           "a scipy.sparse matrix is taken only by model.mass, model.stiffness, "
           "model.damping, load.pattern, ground_motion.influence, constraint_block.file and "
           "constraint_block.value");
    }
    fail(p, "a " + type_name(v) +
                " is not a scene value (numbers, strings, booleans, lists, dicts, numpy arrays)");
  }

  void insert_value(toml::table& out, const std::string& key, const py::handle& v,
                    const std::string& p, int depth) {
    std::visit([&](auto&& x) { out.insert(key, std::forward<decltype(x)>(x)); }, emit(v, p, depth));
  }

  ArrayInputs& arrays_;
};

}  // namespace

py::str system_text(const std::string& text) {
  PyObject* decoded =
      PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "surrogateescape");
  if (decoded == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(decoded);
}

SceneSpec parse_python_scene(const py::handle& scene, SceneNeeds needs) {
  if (py::isinstance<py::dict>(scene)) {
    ArrayInputs arrays;
    const toml::table root = Converter(arrays).table(scene, "", 0);
    return parse_scene_table(root, kDictFile, arrays, needs);
  }
  const py::module_ os = py::module_::import("os");
  py::object path;
  try {
    path = os.attr("fspath")(scene);
  } catch (const py::error_already_set&) {
    throw py::type_error("condyn: a scene is a path (str or os.PathLike) or a dict, not a " +
                         type_name(scene));
  }
  // A bytes path is the file system's own name, as open() takes it.
  if (py::isinstance<py::bytes>(path)) return parse_scene_file(path.cast<std::string>(), needs);
  py::object bytes;
  try {
    bytes = os.attr("fsencode")(path);
  } catch (const py::error_already_set&) {
    throw SceneError(
        "condyn: the scene path is not a file name this system can encode (a lone "
        "surrogate?)");
  }
  return parse_scene_file(bytes.cast<std::string>(), needs);
}

}  // namespace condyn::python
