#include "models/systems/multibody_system.hpp"

#include <algorithm>
#include <cmath>

#include "models/systems/multibody_forces.hpp"
#include "models/systems/multibody_geometry.hpp"
#include "models/systems/multibody_outputs.hpp"
#include "models/systems/multibody_rows.hpp"
#include "models/systems/quadratic_rows.hpp"

namespace condyn {

namespace {

/// M = diag(m, m, I, I) per body in 2D; blockdiag(m I₃, J ⊗ I₃) in 3D, J = ½ tr(I) 1 − I the
/// body's second moment ∫ s sᵀ dm (kinetic energy ½ m |r'|² + ½ Σ_jk J_jk R_j'·R_k').
Eigen::SparseMatrix<double> mass_matrix(const Mechanism& m, const MultibodyGeometry& g) {
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const auto& body = m.bodies[b];
    const int o = g.offset(static_cast<int>(b));
    for (int r = 0; r < m.dimension; ++r) trip.emplace_back(o + r, o + r, body.mass);
    if (m.dimension == 2) {
      trip.emplace_back(o + 2, o + 2, body.inertia(2, 2));
      trip.emplace_back(o + 3, o + 3, body.inertia(2, 2));
      continue;
    }
    const Eigen::Matrix3d J =
        0.5 * body.inertia.trace() * Eigen::Matrix3d::Identity() - body.inertia;
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) {
        for (int i = 0; i < 3; ++i)
          trip.emplace_back(o + 3 + 3 * j + i, o + 3 + 3 * k + i, J(j, k));
      }
    }
  }
  Eigen::SparseMatrix<double> M(g.coordinates(), g.coordinates());
  M.setFromTriplets(trip.begin(), trip.end());
  M.makeCompressed();
  return M;
}

/// The constant data every evaluator of one mechanism shares.
struct MultibodyData {
  std::shared_ptr<const QuadraticRows> rows;
  std::shared_ptr<const MultibodyForces> forces;
  Eigen::SparseMatrix<double> M;
  std::vector<bool> position;
  bool conservative = false;
  double coordinate_scale = 0.0, row_length_scale = 0.0;
};

class MultibodySystem final : public MechanicalSystem {
 public:
  explicit MultibodySystem(std::shared_ptr<const MultibodyData> data)
      : data_(std::move(data)), n_(static_cast<int>(data_->M.rows())), m_(data_->rows->rows()) {}

  [[nodiscard]] std::unique_ptr<MechanicalSystem> clone() const override {
    return std::make_unique<MultibodySystem>(*this);
  }
  [[nodiscard]] int dofs() const override { return n_; }
  [[nodiscard]] int constraints() const override { return m_; }
  [[nodiscard]] const std::vector<bool>& position_rows() const override { return data_->position; }
  [[nodiscard]] const Sparse& mass(double /*t*/, ConstRef /*u*/) override { return data_->M; }
  void force(double t, ConstRef u, ConstRef v, Ref f) override {
    f.setZero();
    data_->forces->add_force(t, steps_at(t), u, v, f);
  }
  [[nodiscard]] const Sparse& stiffness(double t, ConstRef u, ConstRef v) override {
    data_->forces->stiffness(t, steps_at(t), u, v, trip_);
    return assemble(K_);
  }
  [[nodiscard]] const Sparse& damping(double /*t*/, ConstRef u, ConstRef v) override {
    data_->forces->damping(u, v, trip_);
    return assemble(C_);
  }
  [[nodiscard]] const Sparse& constraint_jacobian(double t, ConstRef u) override {
    data_->rows->jacobian(t, steps_at(t), u, A_);
    return A_;
  }
  void position_residual(double t, ConstRef u, Ref phi) override {
    data_->rows->residual(t, steps_at(t), u, phi);
  }
  void velocity_residual(double t, ConstRef u, ConstRef v, Ref psi) override {
    data_->rows->velocity_residual(t, steps_at(t), u, v, psi);
  }
  void acceleration_bias(double t, ConstRef u, ConstRef v, Ref gamma) override {
    data_->rows->acceleration_bias(t, steps_at(t), u, v, gamma);
  }
  [[nodiscard]] bool has_curvature() const override { return data_->rows->has_curvature(); }
  [[nodiscard]] const Sparse& constraint_force_jacobian(double t, ConstRef /*u*/,
                                                        ConstRef w) override {
    data_->rows->force_jacobian(t, steps_at(t), w, force_jac_);
    return force_jac_;
  }
  [[nodiscard]] const Sparse& constraint_product_jacobian(double t, ConstRef /*u*/,
                                                          ConstRef a) override {
    data_->rows->product_jacobian(t, steps_at(t), a, product_jac_);
    return product_jac_;
  }
  [[nodiscard]] const Sparse& velocity_residual_jacobian(double t, ConstRef u,
                                                         ConstRef v) override {
    data_->rows->velocity_residual_jacobian(t, steps_at(t), u, v, psi_jac_);
    return psi_jac_;
  }
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_u(double t, ConstRef u,
                                                           ConstRef v) override {
    data_->rows->acceleration_bias_jacobian_u(t, steps_at(t), u, v, gamma_u_);
    return gamma_u_;
  }
  [[nodiscard]] const Sparse& acceleration_bias_jacobian_v(double t, ConstRef u,
                                                           ConstRef v) override {
    data_->rows->acceleration_bias_jacobian_v(t, steps_at(t), u, v, gamma_v_);
    return gamma_v_;
  }
  [[nodiscard]] std::optional<double> energy(double t, ConstRef u, ConstRef v) override {
    if (!data_->conservative) return std::nullopt;
    return 0.5 * v.dot(data_->M * v) + data_->forces->energy_parts(t, steps_at(t), u, v).potential;
  }
  [[nodiscard]] std::optional<EnergyParts> energy_parts(double t, ConstRef u, ConstRef v) override {
    return data_->forces->energy_parts(t, steps_at(t), u, v);
  }
  [[nodiscard]] double coordinate_scale() const override { return data_->coordinate_scale; }
  [[nodiscard]] double row_length_scale() const override { return data_->row_length_scale; }

 private:
  /// The triplets, always at the same positions, as an n x n matrix (explicit zeros kept).
  const Sparse& assemble(Sparse& S) {
    S.resize(n_, n_);
    S.setFromTriplets(trip_.begin(), trip_.end());
    S.makeCompressed();
    trip_.clear();
    return S;
  }

  std::shared_ptr<const MultibodyData> data_;
  int n_, m_;
  Sparse K_, C_, A_, force_jac_, product_jac_, psi_jac_, gamma_u_, gamma_v_;
  std::vector<Eigen::Triplet<double>> trip_;
};

/// The largest distance of a marker or centre of mass from the origin at t = 0, and of a marker
/// from its body's centre (at least 1, the size of the unit vectors among the coordinates).
double model_size(const Mechanism& m) {
  double size = 1.0;
  const auto grow = [&](const Mechanism::Vec3& x) {
    size = std::max(size, Eigen::Vector3d(x[0], x[1], x[2]).norm());
  };
  for (const auto& p : m.ground_points) grow(p.at);
  for (const auto& b : m.bodies) {
    grow(b.position);
    for (const auto& p : b.points) {
      grow(p.at);
      const Eigen::Vector3d r(b.position[0], b.position[1], b.position[2]);
      size = std::max(size, (r + Eigen::Vector3d(p.at[0], p.at[1], p.at[2])).norm());
    }
  }
  return size;
}

std::vector<std::string> coordinate_names(const Mechanism& m) {
  std::vector<std::string> names;
  for (const auto& b : m.bodies) {
    if (m.dimension == 2) {
      for (const char* s : {"rx", "ry", "ux", "uy"}) names.push_back(b.name + "." + s);
      continue;
    }
    for (const char* s : {"rx", "ry", "rz"}) names.push_back(b.name + "." + s);
    for (int j = 1; j <= 3; ++j)
      for (int i = 1; i <= 3; ++i)
        names.push_back(b.name + ".R" + std::to_string(i) + std::to_string(j));
  }
  return names;
}

/// The model's row: its name, what it says, and for a linear row with constant coefficients
/// (points coinciding, a marker on a ground line) its coefficients and right-hand side.
Constraint constraint_of(const MultibodyRow& row) {
  Constraint c;
  c.name = row.name;
  c.nonlinear_kind = row.kind;
  c.where = row.where;
  const bool linear = row.terms.size() == 1 && row.terms.front().factor == TimeFactor::one &&
                      row.terms.front().form.is_linear();
  if (linear) {
    for (const auto& [col, value] : row.terms.front().form.g) {
      if (value != 0.0) c.coefficients.emplace_back(col, value);
    }
    c.value = TimeFunction::constant(-row.terms.front().form.c);
    c.position_value = c.value;
  }
  return c;
}

}  // namespace

MultibodyParts build_multibody(const Mechanism& mechanism) {
  const MultibodyGeometry geometry(mechanism);
  MultibodyRowSet set = multibody_rows(mechanism, geometry);
  std::vector<std::vector<QuadraticTerm>> terms;
  MultibodyParts parts;
  for (const auto& row : set.rows) {
    terms.push_back(row.terms);
    parts.rows.push_back(constraint_of(row));
    parts.row_joint.push_back(row.joint);
  }
  auto rows =
      std::make_shared<const QuadraticRows>(geometry.coordinates(), terms, std::move(set.drives));
  for (int i = 0; i < rows->rows(); ++i) parts.row_rheonomic.push_back(rows->rheonomic(i));
  auto data = std::make_shared<MultibodyData>();
  data->rows = rows;
  data->forces = std::make_shared<const MultibodyForces>(mechanism, geometry);
  data->M = mass_matrix(mechanism, geometry);
  data->position.assign(static_cast<std::size_t>(rows->rows()), true);
  data->conservative = data->forces->conservative() &&
                       std::none_of(parts.row_rheonomic.begin(), parts.row_rheonomic.end(),
                                    [](bool r) { return r; });
  data->coordinate_scale = model_size(mechanism);
  data->row_length_scale = data->coordinate_scale;
  parts.system = std::make_shared<const MultibodySystem>(data);
  parts.outputs = std::make_shared<const MultibodyOutputs>(mechanism, rows, parts.row_joint);
  parts.coordinate_names = coordinate_names(mechanism);
  parts.q0 = geometry.initial_coordinates(mechanism);
  parts.v0 = geometry.initial_velocities(mechanism);
  return parts;
}

}  // namespace condyn
