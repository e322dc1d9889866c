#include "dae/elimination.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "dae/ida_integrator.hpp"
#include "dae/observed_run.hpp"
#include "dae/reduced_ode.hpp"

namespace condyn {

namespace {

// A named slave block whose condition number exceeds this is refused: the slave displacements
// would carry cond * eps relative error from roundoff alone.
constexpr double kMaxSlaveCondition = 1e12;
// Column-pivoting rank threshold on the row-normalised A (same meaning as in build_model).
constexpr double kRankTolerance = 1e-10;

Eigen::SparseMatrix<double> sparse_from_dense(const Eigen::MatrixXd& d) {
  return d.sparseView(0.0, 0.0);  // keeps every entry that is not exactly zero
}

}  // namespace

MasterSlave master_slave_transform(const Eigen::SparseMatrix<double>& A,
                                   const std::vector<int>& preferred_slaves) {
  const int m = static_cast<int>(A.rows()), n = static_cast<int>(A.cols());
  Eigen::MatrixXd a(A);
  MasterSlave out;
  if (m == 0) {
    out.T.resize(n, n);
    out.T.setIdentity();
    out.G.resize(n, 0);
    for (int i = 0; i < n; ++i) out.masters.push_back(i);
    return out;
  }
  if (preferred_slaves.empty()) {
    // Pivot on the row-normalised matrix so that a constraint's scale does not bias the choice.
    Eigen::MatrixXd scaled = a;
    for (int i = 0; i < m; ++i) scaled.row(i) /= scaled.row(i).stableNorm();  // no underflow
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled.rows(), scaled.cols());
    qr.setThreshold(kRankTolerance);
    qr.compute(scaled);
    if (qr.rank() < m) {
      throw std::invalid_argument("constraint matrix is rank deficient (rank " +
                                  std::to_string(qr.rank()) + " < " + std::to_string(m) + ")");
    }
    for (int k = 0; k < m; ++k) out.slaves.push_back(qr.colsPermutation().indices()[k]);
  } else {
    out.slaves = preferred_slaves;
  }
  std::sort(out.slaves.begin(), out.slaves.end());
  if (static_cast<int>(out.slaves.size()) != m ||
      std::adjacent_find(out.slaves.begin(), out.slaves.end()) != out.slaves.end()) {
    throw std::invalid_argument("need " + std::to_string(m) +
                                " distinct slave DOFs, one per constraint");
  }
  std::vector<bool> is_slave(static_cast<std::size_t>(n), false);
  for (int s : out.slaves) is_slave[static_cast<std::size_t>(s)] = true;
  for (int i = 0; i < n; ++i) {
    if (!is_slave[static_cast<std::size_t>(i)]) out.masters.push_back(i);
  }
  const int nm = n - m;
  Eigen::MatrixXd a_s(m, m), a_r(m, nm);
  for (int k = 0; k < m; ++k) a_s.col(k) = a.col(out.slaves[static_cast<std::size_t>(k)]);
  for (int k = 0; k < nm; ++k) a_r.col(k) = a.col(out.masters[static_cast<std::size_t>(k)]);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a_s);
  const double smax = svd.singularValues()(0), smin = svd.singularValues()(m - 1);
  if (!(smin > smax / kMaxSlaveCondition)) {
    std::ostringstream s;
    s << "the slave DOFs do not determine the constraints (slave block condition number "
      << (smin > 0 ? smax / smin : INFINITY) << "): choose other slaves";
    throw std::invalid_argument(s.str());
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(a_s);
  const Eigen::MatrixXd s_r = lu.solve(a_r);                              // A_S⁻¹ A_R
  const Eigen::MatrixXd s_g = lu.solve(Eigen::MatrixXd::Identity(m, m));  // A_S⁻¹
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(n, nm), g = Eigen::MatrixXd::Zero(n, m);
  for (int k = 0; k < nm; ++k) t(out.masters[static_cast<std::size_t>(k)], k) = 1.0;
  for (int k = 0; k < m; ++k) {
    t.row(out.slaves[static_cast<std::size_t>(k)]) = -s_r.row(k);
    g.row(out.slaves[static_cast<std::size_t>(k)]) = s_g.row(k);
  }
  out.T = sparse_from_dense(t);
  out.G = sparse_from_dense(g);
  return out;
}

ReducedSystem reduce(const Model& model, const std::vector<std::string>& preferred_slaves) {
  std::vector<int> preferred;
  preferred.reserve(preferred_slaves.size());
  for (const auto& name : preferred_slaves) preferred.push_back(model.dof_index.at(name));
  ReducedSystem r;
  r.transform = master_slave_transform(model.A, preferred);
  const auto& T = r.transform.T;
  const auto& G = r.transform.G;
  const Eigen::SparseMatrix<double> Tt = T.transpose();
  r.M = Tt * model.M * T;
  r.K = Tt * model.K * T;
  const int nm = static_cast<int>(T.cols());
  if (model.has_damping()) {
    r.C = Tt * model.C * T;
  } else {
    r.C.resize(nm, nm);
  }
  r.FK = -Eigen::MatrixXd(Tt * model.K * G);
  r.FM = -Eigen::MatrixXd(Tt * model.M * G);
  r.FC = model.has_damping() ? Eigen::MatrixXd(-(Tt * model.C * G))
                             : Eigen::MatrixXd::Zero(nm, model.constraint_count());
  r.loads.resize(nm, static_cast<Eigen::Index>(model.loads.size()));
  for (std::size_t k = 0; k < model.loads.size(); ++k) {
    const Load& load = model.loads[k];
    if (load.dof >= 0) {
      r.loads.col(static_cast<Eigen::Index>(k)) = Tt.col(load.dof);
    } else {
      r.loads.col(static_cast<Eigen::Index>(k)) = Tt * Eigen::VectorXd(load.pattern);
    }
  }
  for (const auto& c : model.constraints) r.rheonomic = r.rheonomic || !c.position_value.is_zero();
  return r;
}

Eigen::VectorXd ReducedSystem::forces(const Model& model, double t, double step_reference) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(M.rows());
  for (std::size_t k = 0; k < model.loads.size(); ++k) {
    f += loads.col(static_cast<Eigen::Index>(k)) *
         model.loads[k].value.derivative(0, t, step_reference);
  }
  // Homogeneous scleronomic constraints have no transfer forces: skip the time functions.
  if (rheonomic) {
    f += FK * model.position_rhs(0, t) + FM * model.position_rhs(2, t);
    if (model.has_damping()) f += FC * model.position_rhs(1, t);
  }
  return f;
}

void solve_elimination(const Model& model, const std::vector<std::string>& preferred_slaves,
                       const IntegratorOptions& options, SolveResult& result) {
  const ReducedSystem reduced = reduce(model, preferred_slaves);
  ReducedOde ode(model, reduced);
  const auto& masters = reduced.transform.masters;
  const int nm = static_cast<int>(masters.size());
  Eigen::VectorXd y0(2 * nm);
  for (int k = 0; k < nm; ++k) {
    y0[k] = model.u0[masters[static_cast<std::size_t>(k)]];
    y0[nm + k] = model.v0[masters[static_cast<std::size_t>(k)]];
  }
  result.summary.scheme = "elimination";
  const auto& T = reduced.transform.T;
  const auto& G = reduced.transform.G;
  const Observation::FullState full_state = [&](double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd u = T * y.head(nm), v = T * y.tail(nm);
    if (reduced.rheonomic) {
      u += G * model.position_rhs(0, t);
      v += G * model.position_rhs(1, t);
    }
    return std::make_pair(u, v);
  };
  const MultiplierRecovery recover(model);
  Observation observe;
  observe.full_state = full_state;
  observe.multipliers = [&](double t, const Eigen::VectorXd& y, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& v) {
    Eigen::VectorXd a = T * ode.acceleration(t, y.head(nm), y.tail(nm));
    if (reduced.rheonomic) a += G * model.position_rhs(2, t);
    return recover(t, u, v, a);
  };
  observe.drift_at_every_step = false;
  run_observed(
      model, options,
      [&](const IntegratorOptions& o) { return integrate(ode, y0, o, result.summary); }, observe,
      result);
}

}  // namespace condyn
