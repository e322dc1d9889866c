#pragma once
/// Constraint rows that are quadratic forms in the coordinates q, with time entering through the
/// factors of a drive (models/systems/multibody_system.hpp builds every rigid and joint row so):
///
///   φ_i(t, q) = Σ_k s_k(t) (½ qᵀH_k q + g_kᵀq + c_k),   s_k ∈ {1, cos d(t), sin d(t), d(t)}
///
/// for drives d (time functions). From this alone every quantity the multiplier formulations need
/// is exact (s' and s'' from the drive's derivatives d', d''):
///
///   A_i  = Σ s_k (H_k q + g_k)ᵀ
///   ψ_i  = A_i v + Σ s_k' (½ qᵀH_k q + g_kᵀq + c_k)
///   γ_i  = −Σ s_k vᵀH_k v − 2 Σ s_k' (H_k q + g_k)ᵀv − Σ s_k'' (½ qᵀH_k q + g_kᵀq + c_k)
///   ∂(Aᵀw)/∂q = Σ_i w_i Σ_k s_k H_k          ∂(A a)/∂q row i = Σ s_k (H_k a)ᵀ
///   ∂ψ/∂q row i = Σ s_k (H_k v)ᵀ + s_k' (H_k q + g_k)ᵀ
///   ∂γ/∂q row i = −Σ 2 s_k' (H_k v)ᵀ + s_k'' (H_k q + g_k)ᵀ
///   ∂γ/∂v row i = −Σ 2 s_k (H_k v)ᵀ + 2 s_k' (H_k q + g_k)ᵀ
///
/// The m x n blocks share one pattern (row i: the columns its H_k and g_k touch) and the n x n
/// block the union of the H_k: fixed at construction, whatever the values (explicit zeros kept).

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <map>
#include <utility>
#include <vector>

#include "models/core/time_function.hpp"

namespace condyn {

/// A quadratic form ½ qᵀH q + gᵀq + c, H symmetric, stored as its entries.
struct QuadraticForm {
  std::map<std::pair<int, int>, double> H;  ///< both (i, j) and (j, i)
  std::map<int, double> g;
  double c = 0.0;

  QuadraticForm& operator+=(const QuadraticForm& other);
  [[nodiscard]] QuadraticForm scaled(double s) const;
  [[nodiscard]] bool is_linear() const { return H.empty(); }
  [[nodiscard]] double value(const Eigen::Ref<const Eigen::VectorXd>& q) const;
};

/// A vector of `dim` entries that is affine in q: entry r = Σ coefficients[r] q + constant[r]
/// (a marker's position r + R s, a body-fixed vector R e, a ground point).
struct AffineVector {
  std::vector<std::map<int, double>> coefficients;
  Eigen::VectorXd constant;

  explicit AffineVector(int dim = 0) : coefficients(static_cast<std::size_t>(dim)) {
    constant = Eigen::VectorXd::Zero(dim);
  }
  [[nodiscard]] int dim() const { return static_cast<int>(constant.size()); }
  [[nodiscard]] AffineVector operator-(const AffineVector& other) const;
  [[nodiscard]] AffineVector operator+(const AffineVector& other) const;
  [[nodiscard]] AffineVector scaled(double s) const;
  /// 2D: the vector rotated by +90°, (−y, x).
  [[nodiscard]] AffineVector perp() const;
  [[nodiscard]] Eigen::VectorXd value(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// Entry r as a linear form.
  [[nodiscard]] QuadraticForm entry(int r) const;
  /// The n-vector Bᵀ F of a force F applied where this vector points (generalized force).
  void add_transposed(const Eigen::VectorXd& F, Eigen::Ref<Eigen::VectorXd> f) const;
};

/// x·y as a quadratic form (2D cross products are dot(x, y.perp()) with a sign).
[[nodiscard]] QuadraticForm dot(const AffineVector& x, const AffineVector& y);

/// How a term's form is multiplied by time: 1, or cos d(t), sin d(t), d(t) of a drive d.
enum class TimeFactor { one, cos_drive, sin_drive, drive };

struct QuadraticTerm {
  TimeFactor factor = TimeFactor::one;
  int drive = -1;  ///< index into the drives, for every factor but `one`
  QuadraticForm form;
};

class QuadraticRows {
 public:
  using Vector = Eigen::VectorXd;
  using ConstRef = Eigen::Ref<const Eigen::VectorXd>;
  using Ref = Eigen::Ref<Eigen::VectorXd>;
  using Sparse = Eigen::SparseMatrix<double>;

  QuadraticRows() = default;
  /// n coordinates; rows[i] the terms of row i; drives the time functions the terms name.
  QuadraticRows(int n, const std::vector<std::vector<QuadraticTerm>>& rows,
                std::vector<TimeFunction> drives);

  [[nodiscard]] int rows() const { return static_cast<int>(row_start_.size()) - 1; }
  [[nodiscard]] bool has_curvature() const { return n_pattern_nonzeros_ > 0; }
  /// Whether row i depends on t (a term with a drive).
  [[nodiscard]] bool rheonomic(int i) const;

  // Each evaluation at (t, steps): steps is the step reference of TimeFunction::derivative.
  void residual(double t, double steps, const ConstRef& q, Ref phi) const;
  void velocity_residual(double t, double steps, const ConstRef& q, const ConstRef& v,
                         Ref psi) const;
  void acceleration_bias(double t, double steps, const ConstRef& q, const ConstRef& v,
                         Ref gamma) const;
  /// A, m x n, into S (pattern fixed).
  void jacobian(double t, double steps, const ConstRef& q, Sparse& S) const;
  /// ∂(Aᵀw)/∂q, n x n.
  void force_jacobian(double t, double steps, const ConstRef& w, Sparse& S) const;
  /// ∂(A a)/∂q, m x n.
  void product_jacobian(double t, double steps, const ConstRef& a, Sparse& S) const;
  /// ∂ψ/∂q, m x n.
  void velocity_residual_jacobian(double t, double steps, const ConstRef& q, const ConstRef& v,
                                  Sparse& S) const;
  /// ∂γ/∂q and ∂γ/∂v, m x n.
  void acceleration_bias_jacobian_u(double t, double steps, const ConstRef& q, const ConstRef& v,
                                    Sparse& S) const;
  void acceleration_bias_jacobian_v(double t, double steps, const ConstRef& q, const ConstRef& v,
                                    Sparse& S) const;
  /// f += scale · A_iᵀ: row i's gradient into an n-vector (the reactions of a joint's rows).
  void add_gradient(double t, double steps, const ConstRef& q, int i, double scale, Ref f) const;

 private:
  /// An entry of an H_k: H(row, col) = value; slot_m, slot_n its place in the m x n pattern (row
  /// i, column `row`) and in the n x n pattern (row, col).
  struct HEntry {
    int row, col;
    double value;
    int slot_m, slot_n;
  };
  struct GEntry {
    int col;
    double value;
    int slot_m;
  };
  struct Term {
    TimeFactor factor;
    int drive;
    std::size_t h_begin, h_end, g_begin, g_end;
    double c;
  };
  /// s, s', s'' of a term at t.
  struct Factors {
    double s0, s1, s2;
  };

  [[nodiscard]] Factors factors(const Term& term, const std::vector<Eigen::Vector3d>& d) const;
  /// d, d', d'' of every drive at t.
  [[nodiscard]] std::vector<Eigen::Vector3d> drive_values(double t, double steps) const;
  /// ½ qᵀH q + gᵀq + c of a term.
  [[nodiscard]] double form_value(const Term& term, const ConstRef& q) const;
  /// (H q + g)·x and xᵀH y.
  [[nodiscard]] double gradient_dot(const Term& term, const ConstRef& q, const ConstRef& x) const;
  [[nodiscard]] double bilinear(const Term& term, const ConstRef& x, const ConstRef& y) const;
  /// Adds a (H x)ᵀ + b (H q + g)ᵀ of a term into the m x n values (b multiplies g only when
  /// with_g).
  void add_row_block(const Term& term, double a, const ConstRef& x, double b, const ConstRef& q,
                     double* values) const;
  /// Prepares S with the m x n pattern, values zero; returns its value array.
  double* start_m(Sparse& S) const;

  int n_ = 0;
  std::vector<TimeFunction> drives_;
  std::vector<Term> terms_;
  std::vector<std::size_t> row_start_{0};  ///< row i's terms: [row_start_[i], row_start_[i+1])
  std::vector<HEntry> h_;
  std::vector<GEntry> g_;
  Sparse pattern_m_, pattern_n_;
  Eigen::Index n_pattern_nonzeros_ = 0;
};

}  // namespace condyn
