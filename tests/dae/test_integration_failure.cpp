// A failure inside the integration loop keeps what was computed: the time reached, the last step
// and the output rows before it, for the CLI to write as a partial result.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "dae/integrators/ida_integrator.hpp"
#include "dae/run/failure_advice.hpp"
#include "dae/run/solve.hpp"

using namespace condyn;

namespace test_integration_failure {

namespace {

/// Machine epsilon: roundoff bounds below are multiples of it times a stated scale.
constexpr double kEps = std::numeric_limits<double>::epsilon();

/// y' = 1 (y = t) until t = 0.45, then a residual that is NaN everywhere: IDA's recoverable
/// retries shrink the step until it gives up there.
class BreaksAtT : public DaeProblem {
 public:
  [[nodiscard]] int size() const override { return 1; }
  void begin_segment(double /*t0*/) override {}
  void residual(double t, ConstRef /*y*/, ConstRef yp, Ref r) const override {
    r[0] = t < kBreak ? yp[0] - 1.0 : std::numeric_limits<double>::quiet_NaN();
  }
  [[nodiscard]] const JacobianPattern& jacobian_pattern() const override { return pattern_; }
  void fill_jacobian(double /*t*/, ConstRef /*y*/, ConstRef /*yp*/, double cj,
                     JacobianMap J) const override {
    J.valuePtr()[0] = cj;
  }
  [[nodiscard]] Eigen::VectorXd differential_id() const override {
    return Eigen::VectorXd::Ones(1);
  }
  void make_consistent(double /*t*/, Eigen::VectorXd& /*y*/, Eigen::VectorXd& yp) const override {
    yp = Eigen::VectorXd::Ones(1);
  }
  static constexpr double kBreak = 0.45;

 private:
  JacobianPattern pattern_{1, {0, 1}, {0}};  // the one entry (0, 0)
};

}  // namespace

TEST_CASE("an integrator failure carries the time reached, the last step and the rows before it") {
  BreaksAtT problem;
  IntegratorOptions options;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  for (int k = 0; k <= 10; ++k) options.output_times.push_back(0.1 * k);
  SolveSummary summary;
  bool thrown = false;
  try {
    (void)integrate(problem, Eigen::VectorXd::Zero(1), options, summary);
  } catch (const IntegrationError& e) {
    thrown = true;
    CAPTURE(std::string(e.what()));
    CHECK(e.in_loop);
    CHECK(e.t_reached <= BreaksAtT::kBreak);
    CHECK(e.t_reached >= 0.4);  // the rows at 0 ... 0.4 came before the failure
    CHECK(e.last_step > 0.0);
    REQUIRE(e.raw_partial);
    REQUIRE(e.raw_partial->t.size() == 5);  // t = 0, 0.1, 0.2, 0.3, 0.4
    for (std::size_t k = 0; k < 5; ++k) {
      CHECK(e.raw_partial->t[k] == doctest::Approx(0.1 * static_cast<double>(k)).epsilon(8 * kEps));
      // y = t up to the integration error of a linear solution (exact for BDF: roundoff of the
      // steps' sums, 64 eps; observed exact).
      CHECK(e.raw_partial->y[k][0] == doctest::Approx(e.raw_partial->t[k]).epsilon(64 * kEps));
    }
  }
  CHECK(thrown);
}

TEST_CASE("failure suggestions name what to try") {
  IntegrationError collapsed(FailureKind::step_size_collapsed,
                             "IDASolve failed with IDA_CONV_FAIL at t = 1");
  collapsed.in_loop = true;
  collapsed.t_reached = 1.0;
  collapsed.t_end = 2.0;
  collapsed.last_step = 1e-200;
  CHECK(failure_suggestion(Scheme::ggl, failure_of(collapsed)).find("singular configuration") !=
        std::string::npos);
  IntegrationError slow(FailureKind::steps_per_output,
                        "took 100000 steps without reaching the output time 0.01 (at t = 1e-4)");
  slow.in_loop = true;
  slow.t_reached = 1e-4;
  slow.t_end = 20.0;
  slow.last_step = 1e-9;
  const std::string s = failure_suggestion(Scheme::baumgarte, failure_of(slow));
  CHECK(s.find("very stiff") != std::string::npos);
  CHECK(s.find("smaller [solve] baumgarte gains") != std::string::npos);
  const IntegrationError blown(FailureKind::non_finite,
                               "the solution became non-finite (NaN or inf) at t = 3");
  CHECK(failure_suggestion(Scheme::index1, failure_of(blown)).find("blew up") != std::string::npos);
}

}  // namespace test_integration_failure
