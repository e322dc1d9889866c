#include "models/systems/quadratic_rows.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace condyn {

QuadraticForm& QuadraticForm::operator+=(const QuadraticForm& other) {
  for (const auto& [at, value] : other.H) H[at] += value;
  for (const auto& [at, value] : other.g) g[at] += value;
  c += other.c;
  return *this;
}

QuadraticForm QuadraticForm::scaled(double s) const {
  QuadraticForm out = *this;
  for (auto& entry : out.H) entry.second *= s;
  for (auto& entry : out.g) entry.second *= s;
  out.c *= s;
  return out;
}

double QuadraticForm::value(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  double sum = c;
  for (const auto& [at, value] : H) sum += 0.5 * value * q[at.first] * q[at.second];
  for (const auto& [at, value] : g) sum += value * q[at];
  return sum;
}

AffineVector AffineVector::operator+(const AffineVector& other) const {
  AffineVector out = *this;
  for (int r = 0; r < dim(); ++r) {
    for (const auto& [col, value] : other.coefficients[static_cast<std::size_t>(r)])
      out.coefficients[static_cast<std::size_t>(r)][col] += value;
  }
  out.constant += other.constant;
  return out;
}

AffineVector AffineVector::operator-(const AffineVector& other) const {
  return *this + other.scaled(-1.0);
}

AffineVector AffineVector::scaled(double s) const {
  AffineVector out = *this;
  for (auto& row : out.coefficients)
    for (auto& entry : row) entry.second *= s;
  out.constant *= s;
  return out;
}

AffineVector AffineVector::perp() const {
  if (dim() != 2) throw std::logic_error("AffineVector::perp: a 2D vector only");
  AffineVector out(2);
  out.coefficients[0] = scaled(-1.0).coefficients[1];
  out.coefficients[1] = coefficients[0];
  out.constant << -constant[1], constant[0];
  return out;
}

Eigen::VectorXd AffineVector::value(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  Eigen::VectorXd x = constant;
  for (int r = 0; r < dim(); ++r) {
    for (const auto& [col, value] : coefficients[static_cast<std::size_t>(r)])
      x[r] += value * q[col];
  }
  return x;
}

QuadraticForm AffineVector::entry(int r) const {
  QuadraticForm form;
  form.g = coefficients[static_cast<std::size_t>(r)];
  form.c = constant[r];
  return form;
}

void AffineVector::add_transposed(const Eigen::VectorXd& F, Eigen::Ref<Eigen::VectorXd> f) const {
  for (int r = 0; r < dim(); ++r) {
    for (const auto& [col, value] : coefficients[static_cast<std::size_t>(r)])
      f[col] += value * F[r];
  }
}

QuadraticForm dot(const AffineVector& x, const AffineVector& y) {
  // Σ_r (b_r·q + x0_r)(c_r·q + y0_r): H = Σ b_r c_rᵀ + c_r b_rᵀ, g = Σ y0_r b_r + x0_r c_r.
  QuadraticForm form;
  for (int r = 0; r < x.dim(); ++r) {
    const auto& b = x.coefficients[static_cast<std::size_t>(r)];
    const auto& c = y.coefficients[static_cast<std::size_t>(r)];
    for (const auto& [i, bi] : b) {
      for (const auto& [j, cj] : c) {
        form.H[{i, j}] += bi * cj;
        form.H[{j, i}] += bi * cj;
      }
      form.g[i] += bi * y.constant[r];
    }
    for (const auto& [j, cj] : c) form.g[j] += cj * x.constant[r];
    form.c += x.constant[r] * y.constant[r];
  }
  return form;
}

namespace {

/// The index into S's values of entry (i, j), which the pattern holds.
int slot_of(const Eigen::SparseMatrix<double>& S, int i, int j) {
  const auto* begin = S.innerIndexPtr() + S.outerIndexPtr()[j];
  const auto* end = S.innerIndexPtr() + S.outerIndexPtr()[j + 1];
  const auto* at = std::lower_bound(begin, end, i);
  return static_cast<int>(at - S.innerIndexPtr());
}

Eigen::SparseMatrix<double> pattern_of(int rows, int cols,
                                       std::vector<Eigen::Triplet<double>>& trip) {
  Eigen::SparseMatrix<double> S(rows, cols);
  S.setFromTriplets(trip.begin(), trip.end());
  S.makeCompressed();
  std::fill(S.valuePtr(), S.valuePtr() + S.nonZeros(), 0.0);
  return S;
}

}  // namespace

QuadraticRows::QuadraticRows(int n, const std::vector<std::vector<QuadraticTerm>>& rows,
                             std::vector<TimeFunction> drives)
    : n_(n), drives_(std::move(drives)) {
  const int m = static_cast<int>(rows.size());
  std::vector<Eigen::Triplet<double>> trip_m, trip_n;
  std::vector<int> h_row_of;  // the row each H entry belongs to, for its m x n slot
  std::vector<int> g_row_of;
  row_start_.assign(1, 0);
  for (int i = 0; i < m; ++i) {
    for (const auto& t : rows[static_cast<std::size_t>(i)]) {
      if (t.factor != TimeFactor::one &&
          (t.drive < 0 || t.drive >= static_cast<int>(drives_.size()))) {
        throw std::logic_error("QuadraticRows: a term names no drive");
      }
      Term term{t.factor, t.drive, h_.size(), 0, g_.size(), 0, t.form.c};
      for (const auto& [at, value] : t.form.H) {
        h_.push_back({at.first, at.second, value, 0, 0});
        h_row_of.push_back(i);
        trip_m.emplace_back(i, at.first, 1.0);
        trip_n.emplace_back(at.first, at.second, 1.0);
      }
      for (const auto& [col, value] : t.form.g) {
        g_.push_back({col, value, 0});
        g_row_of.push_back(i);
        trip_m.emplace_back(i, col, 1.0);
      }
      term.h_end = h_.size();
      term.g_end = g_.size();
      terms_.push_back(term);
    }
    row_start_.push_back(terms_.size());
  }
  pattern_m_ = pattern_of(m, n, trip_m);
  pattern_n_ = pattern_of(n, n, trip_n);
  n_pattern_nonzeros_ = pattern_n_.nonZeros();
  for (std::size_t k = 0; k < h_.size(); ++k) {
    h_[k].slot_m = slot_of(pattern_m_, h_row_of[k], h_[k].row);
    h_[k].slot_n = slot_of(pattern_n_, h_[k].row, h_[k].col);
  }
  for (std::size_t k = 0; k < g_.size(); ++k)
    g_[k].slot_m = slot_of(pattern_m_, g_row_of[k], g_[k].col);
}

bool QuadraticRows::rheonomic(int i) const {
  for (auto k = row_start_[static_cast<std::size_t>(i)];
       k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
    if (terms_[k].factor != TimeFactor::one) return true;
  }
  return false;
}

std::vector<Eigen::Vector3d> QuadraticRows::drive_values(double t, double steps) const {
  std::vector<Eigen::Vector3d> d;
  d.reserve(drives_.size());
  for (const auto& f : drives_)
    d.emplace_back(f.derivative(0, t, steps), f.derivative(1, t, steps), f.derivative(2, t, steps));
  return d;
}

QuadraticRows::Factors QuadraticRows::factors(const Term& term,
                                              const std::vector<Eigen::Vector3d>& d) const {
  if (term.factor == TimeFactor::one) return {1.0, 0.0, 0.0};
  const Eigen::Vector3d& x = d[static_cast<std::size_t>(term.drive)];
  const double c = std::cos(x[0]), s = std::sin(x[0]);
  switch (term.factor) {
    case TimeFactor::cos_drive:  // (cos d)' = −sin d d', (cos d)'' = −cos d d'² − sin d d''
      return {c, -s * x[1], -c * x[1] * x[1] - s * x[2]};
    case TimeFactor::sin_drive:
      return {s, c * x[1], -s * x[1] * x[1] + c * x[2]};
    default:
      return {x[0], x[1], x[2]};
  }
}

double QuadraticRows::form_value(const Term& term, const ConstRef& q) const {
  double sum = term.c;
  for (auto k = term.h_begin; k < term.h_end; ++k)
    sum += 0.5 * h_[k].value * q[h_[k].row] * q[h_[k].col];
  for (auto k = term.g_begin; k < term.g_end; ++k) sum += g_[k].value * q[g_[k].col];
  return sum;
}

double QuadraticRows::gradient_dot(const Term& term, const ConstRef& q, const ConstRef& x) const {
  double sum = 0.0;
  for (auto k = term.h_begin; k < term.h_end; ++k) sum += h_[k].value * q[h_[k].col] * x[h_[k].row];
  for (auto k = term.g_begin; k < term.g_end; ++k) sum += g_[k].value * x[g_[k].col];
  return sum;
}

double QuadraticRows::bilinear(const Term& term, const ConstRef& x, const ConstRef& y) const {
  double sum = 0.0;
  for (auto k = term.h_begin; k < term.h_end; ++k) sum += h_[k].value * x[h_[k].row] * y[h_[k].col];
  return sum;
}

void QuadraticRows::add_row_block(const Term& term, double a, const ConstRef& x, double b,
                                  const ConstRef& q, double* values) const {
  // Row i, column h.row: a (H x)_row + b (H q + g)_row.
  for (auto k = term.h_begin; k < term.h_end; ++k)
    values[h_[k].slot_m] += h_[k].value * (a * x[h_[k].col] + b * q[h_[k].col]);
  if (b == 0.0) return;
  for (auto k = term.g_begin; k < term.g_end; ++k) values[g_[k].slot_m] += b * g_[k].value;
}

double* QuadraticRows::start_m(Sparse& S) const {
  if (S.rows() != pattern_m_.rows() || S.cols() != pattern_m_.cols() ||
      S.nonZeros() != pattern_m_.nonZeros() || !S.isCompressed()) {
    S = pattern_m_;
  }
  std::fill(S.valuePtr(), S.valuePtr() + S.nonZeros(), 0.0);
  return S.valuePtr();
}

void QuadraticRows::residual(double t, double steps, const ConstRef& q, Ref phi) const {
  const auto d = drive_values(t, steps);
  for (int i = 0; i < rows(); ++i) {
    double sum = 0.0;
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      sum += factors(terms_[k], d).s0 * form_value(terms_[k], q);
    }
    phi[i] = sum;
  }
}

void QuadraticRows::velocity_residual(double t, double steps, const ConstRef& q, const ConstRef& v,
                                      Ref psi) const {
  const auto d = drive_values(t, steps);
  for (int i = 0; i < rows(); ++i) {
    double sum = 0.0;
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      const Term& term = terms_[k];
      const Factors s = factors(term, d);
      sum += s.s0 * gradient_dot(term, q, v);
      if (s.s1 != 0.0) sum += s.s1 * form_value(term, q);
    }
    psi[i] = sum;
  }
}

void QuadraticRows::acceleration_bias(double t, double steps, const ConstRef& q, const ConstRef& v,
                                      Ref gamma) const {
  const auto d = drive_values(t, steps);
  for (int i = 0; i < rows(); ++i) {
    double sum = 0.0;
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      const Term& term = terms_[k];
      const Factors s = factors(term, d);
      sum -= s.s0 * bilinear(term, v, v);
      if (term.factor != TimeFactor::one)
        sum -= 2.0 * s.s1 * gradient_dot(term, q, v) + s.s2 * form_value(term, q);
    }
    gamma[i] = sum;
  }
}

void QuadraticRows::jacobian(double t, double steps, const ConstRef& q, Sparse& S) const {
  const auto d = drive_values(t, steps);
  double* values = start_m(S);
  for (int i = 0; i < rows(); ++i) {
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      add_row_block(terms_[k], 0.0, q, factors(terms_[k], d).s0, q, values);
    }
  }
}

void QuadraticRows::force_jacobian(double t, double steps, const ConstRef& w, Sparse& S) const {
  const auto d = drive_values(t, steps);
  if (S.rows() != n_ || S.cols() != n_ || S.nonZeros() != pattern_n_.nonZeros()) S = pattern_n_;
  std::fill(S.valuePtr(), S.valuePtr() + S.nonZeros(), 0.0);
  double* values = S.valuePtr();
  for (int i = 0; i < rows(); ++i) {
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      const Term& term = terms_[k];
      const double s = w[i] * factors(term, d).s0;
      for (auto e = term.h_begin; e < term.h_end; ++e) values[h_[e].slot_n] += s * h_[e].value;
    }
  }
}

void QuadraticRows::product_jacobian(double t, double steps, const ConstRef& a, Sparse& S) const {
  const auto d = drive_values(t, steps);
  double* values = start_m(S);
  for (int i = 0; i < rows(); ++i) {
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      add_row_block(terms_[k], factors(terms_[k], d).s0, a, 0.0, a, values);
    }
  }
}

void QuadraticRows::velocity_residual_jacobian(double t, double steps, const ConstRef& q,
                                               const ConstRef& v, Sparse& S) const {
  const auto d = drive_values(t, steps);
  double* values = start_m(S);
  for (int i = 0; i < rows(); ++i) {
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      const Factors s = factors(terms_[k], d);
      add_row_block(terms_[k], s.s0, v, s.s1, q, values);
    }
  }
}

void QuadraticRows::acceleration_bias_jacobian_u(double t, double steps, const ConstRef& q,
                                                 const ConstRef& v, Sparse& S) const {
  const auto d = drive_values(t, steps);
  double* values = start_m(S);
  for (int i = 0; i < rows(); ++i) {
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      const Factors s = factors(terms_[k], d);
      add_row_block(terms_[k], -2.0 * s.s1, v, -s.s2, q, values);
    }
  }
}

void QuadraticRows::acceleration_bias_jacobian_v(double t, double steps, const ConstRef& q,
                                                 const ConstRef& v, Sparse& S) const {
  const auto d = drive_values(t, steps);
  double* values = start_m(S);
  for (int i = 0; i < rows(); ++i) {
    for (auto k = row_start_[static_cast<std::size_t>(i)];
         k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
      const Factors s = factors(terms_[k], d);
      add_row_block(terms_[k], -2.0 * s.s0, v, -2.0 * s.s1, q, values);
    }
  }
}

void QuadraticRows::add_gradient(double t, double steps, const ConstRef& q, int i, double scale,
                                 Ref f) const {
  const auto d = drive_values(t, steps);
  for (auto k = row_start_[static_cast<std::size_t>(i)];
       k < row_start_[static_cast<std::size_t>(i) + 1]; ++k) {
    const Term& term = terms_[k];
    const double s = scale * factors(term, d).s0;
    for (auto e = term.h_begin; e < term.h_end; ++e) f[h_[e].row] += s * h_[e].value * q[h_[e].col];
    for (auto e = term.g_begin; e < term.g_end; ++e) f[g_[e].col] += s * g_[e].value;
  }
}

}  // namespace condyn
