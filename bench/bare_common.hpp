#pragma once
// What the bare drivers of bench/ share (no condyn code): a CSC matrix read from a Matrix Market
// file, its transpose and product, a SUNDIALS flag check and the process's clocks.

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bare {

using Clock = std::chrono::steady_clock;

/// A compressed sparse column matrix, rows sorted within each column.
struct Csc {
  long rows = 0, cols = 0;
  std::vector<long> ptr;  // cols + 1
  std::vector<long> idx;
  std::vector<double> val;
};

/// Reads a Matrix Market file: `coordinate real general|symmetric` or `array real general`.
inline Csc read_mtx(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  std::getline(in, line);
  std::string banner, object, format, field, symmetry;
  std::istringstream(line) >> banner >> object >> format >> field >> symmetry;
  if (banner != "%%MatrixMarket" || object != "matrix" || field != "real")
    throw std::runtime_error(path + ": line 1: expected '%%MatrixMarket matrix ... real ...'");
  const bool symmetric = symmetry == "symmetric";
  if (!symmetric && symmetry != "general")
    throw std::runtime_error(path + ": line 1: symmetry must be general or symmetric");
  while (std::getline(in, line) && (line.empty() || line[0] == '%')) {
  }
  std::istringstream size(line);
  long rows = 0, cols = 0, entries = 0;
  size >> rows >> cols;
  std::vector<long> ri, ci;
  std::vector<double> vi;
  if (format == "coordinate") {
    size >> entries;
    if (!size || rows <= 0 || cols <= 0 || entries < 0)
      throw std::runtime_error(path + ": bad size line '" + line + "'");
    ri.reserve(static_cast<std::size_t>(symmetric ? 2 * entries : entries));
    ci.reserve(ri.capacity());
    vi.reserve(ri.capacity());
    for (long e = 0; e < entries; ++e) {
      long r = 0, c = 0;
      double v = 0.0;
      if (!(in >> r >> c >> v) || r < 1 || r > rows || c < 1 || c > cols)
        throw std::runtime_error(path + ": bad or missing entry " + std::to_string(e + 1));
      ri.push_back(r - 1);
      ci.push_back(c - 1);
      vi.push_back(v);
      if (symmetric && r != c) {
        ri.push_back(c - 1);
        ci.push_back(r - 1);
        vi.push_back(v);
      }
    }
  } else if (format == "array") {
    if (!size || rows <= 0 || cols <= 0 || symmetric)
      throw std::runtime_error(path + ": bad size line '" + line + "'");
    for (long c = 0; c < cols; ++c)
      for (long r = 0; r < rows; ++r) {
        double v = 0.0;
        if (!(in >> v)) throw std::runtime_error(path + ": missing array entry");
        if (v != 0.0) {
          ri.push_back(r);
          ci.push_back(c);
          vi.push_back(v);
        }
      }
  } else {
    throw std::runtime_error(path + ": format must be coordinate or array");
  }
  // Counting sort by column, then by row within each column; duplicates are summed.
  Csc m;
  m.rows = rows;
  m.cols = cols;
  m.ptr.assign(static_cast<std::size_t>(cols + 1), 0);
  for (long c : ci) ++m.ptr[static_cast<std::size_t>(c + 1)];
  for (long c = 0; c < cols; ++c) m.ptr[c + 1] += m.ptr[c];
  std::vector<long> next(m.ptr.begin(), m.ptr.end() - 1);
  std::vector<long> idx(ri.size());
  std::vector<double> val(ri.size());
  for (std::size_t e = 0; e < ri.size(); ++e) {
    const long at = next[static_cast<std::size_t>(ci[e])]++;
    idx[static_cast<std::size_t>(at)] = ri[e];
    val[static_cast<std::size_t>(at)] = vi[e];
  }
  std::vector<std::pair<long, double>> col;
  m.ptr.assign(static_cast<std::size_t>(cols + 1), 0);
  for (long c = 0; c < cols; ++c) {
    col.clear();
    const long begin = c == 0 ? 0 : next[static_cast<std::size_t>(c - 1)];
    for (long k = begin; k < next[static_cast<std::size_t>(c)]; ++k)
      col.emplace_back(idx[static_cast<std::size_t>(k)], val[static_cast<std::size_t>(k)]);
    std::sort(col.begin(), col.end());
    for (std::size_t k = 0; k < col.size(); ++k) {
      if (k > 0 && col[k].first == col[k - 1].first) {
        m.val.back() += col[k].second;
      } else {
        m.idx.push_back(col[k].first);
        m.val.push_back(col[k].second);
      }
    }
    m.ptr[static_cast<std::size_t>(c + 1)] = static_cast<long>(m.idx.size());
  }
  return m;
}

inline Csc transpose(const Csc& a) {
  Csc t;
  t.rows = a.cols;
  t.cols = a.rows;
  t.ptr.assign(static_cast<std::size_t>(t.cols + 1), 0);
  for (long i : a.idx) ++t.ptr[static_cast<std::size_t>(i + 1)];
  for (long c = 0; c < t.cols; ++c) t.ptr[c + 1] += t.ptr[c];
  t.idx.resize(a.idx.size());
  t.val.resize(a.val.size());
  std::vector<long> next(t.ptr.begin(), t.ptr.end() - 1);
  for (long c = 0; c < a.cols; ++c)  // columns in order: rows of the transpose come out sorted
    for (long k = a.ptr[c]; k < a.ptr[c + 1]; ++k) {
      const long at = next[static_cast<std::size_t>(a.idx[k])]++;
      t.idx[static_cast<std::size_t>(at)] = c;
      t.val[static_cast<std::size_t>(at)] = a.val[static_cast<std::size_t>(k)];
    }
  return t;
}

/// out += scale * a * x
inline void gaxpy(const Csc& a, const double* x, double scale, double* out) {
  for (long c = 0; c < a.cols; ++c) {
    const double xc = scale * x[c];
    if (xc == 0.0) continue;
    for (long k = a.ptr[c]; k < a.ptr[c + 1]; ++k) out[a.idx[k]] += a.val[k] * xc;
  }
}

/// The first 2n rows of both drivers' residual F(t, y, y') for M u'' + K u = s(t) f over
/// y = [u; v] (n = M.rows): r₁ = u' − v, r₂ = M v' + K u − s f, s the step load, on from t = 0.
inline void second_order_residual(const Csc& M, const Csc& K, const std::vector<double>& f,
                                  double t, const double* y, const double* d, double* r) {
  const long n = M.rows;
  const double s = t >= 0.0 ? 1.0 : 0.0;
  for (long i = 0; i < n; ++i) r[i] = d[i] - y[n + i];
  double* r2 = r + n;
  for (long i = 0; i < n; ++i) r2[i] = -s * f[static_cast<std::size_t>(i)];
  gaxpy(M, d + n, 1.0, r2);
  gaxpy(K, y, 1.0, r2);
}

inline void check(int flag, const char* what) {
  if (flag < 0)
    throw std::runtime_error(std::string(what) + " failed with flag " + std::to_string(flag));
}

/// CPU seconds (user + system) of this process so far: on a shared machine the figure that wall
/// time inflates and this does not.
inline double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// What bench/lattice.py and bench/mesh_lattice.py write into a folder: M, K, A and the load
/// pattern f (dense), their sizes checked against each other.
struct MatrixFiles {
  Csc M, K, A;
  std::vector<double> f;
};

inline MatrixFiles read_matrix_files(const std::string& dir) {
  MatrixFiles out{read_mtx(dir + "/M.mtx"), read_mtx(dir + "/K.mtx"), read_mtx(dir + "/A.mtx"), {}};
  const Csc f = read_mtx(dir + "/f.mtx");
  const long n = out.M.rows;
  if (out.M.cols != n || out.K.rows != n || out.K.cols != n || out.A.cols != n || f.rows != n ||
      f.cols != 1)
    throw std::runtime_error("sizes of M, K, A, f do not agree");
  out.f.assign(static_cast<std::size_t>(n), 0.0);
  for (long k = 0; k < f.ptr[1]; ++k) out.f[static_cast<std::size_t>(f.idx[k])] = f.val[k];
  return out;
}

/// A driver's flag `--name NUMBER`: where its value goes, and whether 0 is allowed (else it must
/// be positive); finite either way.
struct NumberFlag {
  double* value;
  bool zero_allowed = false;
};

/// Reads argv[first...] as flags of `flags`; on an unknown flag, a missing value or a number out
/// of range prints the problem and returns false.
inline bool parse_number_flags(int argc, char** argv, int first,
                               const std::map<std::string, NumberFlag>& flags) {
  for (int i = first; i < argc; ++i) {
    const std::string flag = argv[i];
    const auto known = flags.find(flag);
    if (known == flags.end()) {
      std::cerr << "error: unknown flag " << flag << "\n";
      return false;
    }
    if (i + 1 >= argc) {
      std::cerr << "error: " << flag << " needs a value\n";
      return false;
    }
    char* end = nullptr;
    const double v = std::strtod(argv[++i], &end);
    const bool zero = known->second.zero_allowed;
    if (*end != '\0' || !(v > 0.0 || (zero && v == 0.0)) || !std::isfinite(v)) {
      std::cerr << "error: " << flag << ": expected a " << (zero ? "non-negative" : "positive")
                << " number, got '" << argv[i] << "'\n";
      return false;
    }
    *known->second.value = v;
  }
  return true;
}

}  // namespace bare
