#include "dae/run/failure_advice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "models/core/solve_spec.hpp"

namespace condyn {

namespace {

/// "about 140", "about 4e+304": two significant digits, an order of magnitude for the advice.
std::string about(double x) {
  std::ostringstream s;
  if (x >= 1.0 && x < 1e6) {
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    s << "about " << static_cast<long>(std::round(x / unit) * unit);
  } else {
    s.precision(2);
    s << "about " << x;
  }
  return s.str();
}

/// What the Newmark family and rattle add: the step to shrink when it was fixed; the damped
/// members or the stabilized form when an undamped one ran at index 3 (on the slider-crank,
/// newmark without a step needed 100,000 steps before t = 1.7 where the stabilized form ran all
/// 5 s in 2,416).
std::string fixed_step_family_advice(const AdviceContext& context) {
  std::string s = context.fixed_step
                      ? "; this scheme runs with the fixed [solve] step: try a smaller step"
                      : "; the steps were controlled by the method's error estimate at rtol";
  if (context.undamped_index3) {
    s += "; these parameters damp no high frequency (spectral radius 1 at infinity), and at "
         "index 3 the multipliers' oscillation then grows: set [solve] newmark_constraints = "
         "\"stabilized\", or use hht or generalized_alpha (numerical damping)";
  }
  return s;
}

/// What the scheme itself adds to the advice after a solver failure (penalty on a nonlinear
/// model is the augmented Lagrangian, whose weight comes from the model).
std::string scheme_advice(Scheme scheme, const AdviceContext& context) {
  switch (scheme) {
    case Scheme::baumgarte:
      return "; large Baumgarte gains make the system stiff: try smaller [solve] baumgarte gains "
             "or ggl";
    case Scheme::penalty:
      if (context.nonlinear_model) {
        return "; penalty on a nonlinear model is the augmented Lagrangian under CVODE's "
               "non-stiff Adams method (its weight is set from the model, [solve] penalty does "
               "not apply): a stiff model defeats it, try ggl";
      }
      return "; a large penalty weight makes the system stiff: try a smaller [solve] penalty "
             "weight or ggl";
    case Scheme::index1:
    case Scheme::index2:
      return "; this scheme lets the drift grow: ggl or projection hold the constraints";
    case Scheme::index3:
      return "; index3 is the least robust formulation: try ggl";
    case Scheme::ggl:
      // The pendulum at rtol 1e-13 collapsed at t = 5e-5 and ran with atol_mu = 1e-10; the
      // message blamed a singular configuration alone.
      return "; at rtol 1e-10 and tighter, GGL's derived μ and λ tolerances (`condyn info`) can "
             "ask for roundoff: set [solve] atol_mu and atol_multiplier larger (models/scenes/"
             "pendulum.toml at rtol 1e-13 runs with atol_mu = 1e-10)";
    case Scheme::newmark:
    case Scheme::hht:
    case Scheme::generalized_alpha:
    case Scheme::rattle:
      return fixed_step_family_advice(context);
    default:
      return "";
  }
}

/// Whether a tolerance below roundoff can explain a failure of this kind: those of the step size.
bool step_size_failure(FailureKind kind) {
  switch (kind) {
    case FailureKind::step_size_collapsed:
    case FailureKind::steps_per_output:
    case FailureKind::error_test:
    case FailureKind::convergence:
    case FailureKind::first_step:
      return true;
    default:
      return false;
  }
}

}  // namespace

std::string roundoff_advice(const RunFailure& e, double atol, double max_displacement,
                            double coordinates) {
  if (!step_size_failure(e.kind)) return "";
  constexpr double kUlps = 100.0;
  // The constraint rows compute with the coordinates even where the displacements are small;
  // where the model does not say how large they are, of order 1 (a model in metres).
  const double scale = std::max({1.0, max_displacement, coordinates});
  const double roundoff = std::numeric_limits<double>::epsilon() * scale;
  if (!(atol < kUlps * roundoff)) return "";
  std::ostringstream s;
  s.precision(2);
  s << "; atol " << atol << " is within " << static_cast<int>(kUlps) << " ulps of " << scale
    << " (the largest of 1, the model's coordinates, " << coordinates
    << ", and the largest displacement reached, " << max_displacement
    << "), which doubles hold to about " << roundoff
    << ": the error test may ask for what the arithmetic cannot give; raise atol (and "
       "atol_velocity, atol_multiplier, atol_mu if set) to the size of the smallest "
       "displacement that matters";
  return s.str();
}

std::string failure_suggestion(Scheme scheme, const RunFailure& e, const AdviceContext& context) {
  // What is left of the run, in steps of the last size and in wall time at the pace so far.
  const double left = e.t_end - e.t_reached;
  const bool progressed = e.in_loop && e.t_reached > e.t0;
  const double steps_left = e.last_step != 0.0 ? left / std::abs(e.last_step) : 0.0;
  const double seconds_left = progressed ? e.elapsed_seconds * left / (e.t_reached - e.t0) : 0.0;
  switch (e.kind) {
    case FailureKind::non_finite:
    case FailureKind::residual_non_finite:
      return "the solution blew up: check loads and time functions for runaway growth, and masses "
             "and stiffnesses for absurd magnitudes";
    case FailureKind::step_budget: {
      std::string s = "the run used up its step budget ([solve] max_steps or --max-steps)";
      // IDA's first steps grow from a tiny start: extrapolated, the 5th step of a run of 326
      // promised 3.1e8 more. Below kSettledSteps the estimate says nothing and is left out.
      constexpr long kSettledSteps = 100;
      if (steps_left > 0.0 && e.steps >= kSettledSteps) {
        s += "; at the last step size the rest of the run needs " + about(steps_left) +
             " more steps";
      } else if (steps_left > 0.0) {
        s += "; after " + std::to_string(e.steps) +
             " steps the step size is still growing from its start, so how many more the run "
             "needs is not known yet";
      }
      return s + ": shorten t_end, raise the budget, or loosen rtol (larger steps)";
    }
    case FailureKind::wall_time_budget: {
      std::string s =
          "the run used up its wall-time budget ([solve] max_wall_time or "
          "--max-wall-time)";
      if (seconds_left > 0.0) {
        s += "; at the pace so far the rest of the run needs " + about(seconds_left) + " s";
      }
      return s + ": shorten t_end, raise the budget, or loosen rtol (larger steps)";
    }
    case FailureKind::steps_per_output:
      return "the step size stayed tiny for many steps: the model is very stiff or oscillates far "
             "faster than the output step; a smaller output_step or a larger [solve] "
             "max_steps_per_output (default " +
             std::to_string(kDefaultStepsPerOutput) +
             ", or max_steps when larger) lets the run go on, a looser rtol takes larger steps" +
             scheme_advice(scheme, context);
    case FailureKind::step_size_collapsed:
      return "the step size collapsed to roundoff of the time reached: the motion reaches a "
             "singular configuration (constraints that become dependent, a mechanism at a dead "
             "point, a prescribed motion it cannot follow) or a jump; check the scene at the time "
             "reached" +
             scheme_advice(scheme, context);
    case FailureKind::tolerance_too_tight:
      return "the tolerances ask for more than double precision holds at these magnitudes: "
             "loosen rtol, or raise atol to the size of the smallest quantity that matters";
    case FailureKind::linear_solver:
      return "the iteration matrix could not be factored (singular): a DOF that nothing holds "
             "(no mass, stiffness or constraint), or constraints that became dependent near the "
             "time reached; `condyn info` shows the classification, another scheme may pass" +
             scheme_advice(scheme, context);
    case FailureKind::first_step:
      return "the integrator failed before its first step, so no motion was computed: check the "
             "initial state (displacements and velocities consistent with the constraints; "
             "[initial] project = true), the tolerances (atol on the scale of the smallest "
             "unknown that matters, rtol not tighter than needed), and the time scale (t_end and "
             "output_step against the model's periods); another scheme may start";
    case FailureKind::bad_input:
      if (e.t_reached == e.t0 && e.message.find("is behind current t") != std::string::npos) {
        // IDA's first step is 0.5 over the weighted norm of y'0, 0 when that norm overflows.
        return "the integrator's first step came out as 0: the initial rates of change are "
               "beyond double precision against the tolerances (|y'| / atol above about 1e308: "
               "loads, masses or stiffnesses in a unit far too small or too large); rescale the "
               "model or loosen atol";
      }
      return "the integrator refused an input (a time, tolerance or size it cannot use): check "
             "t_end, output_step, the load step times and the tolerances";
    case FailureKind::interrupted:
      return "";  // the user stopped it: nothing to try instead
    case FailureKind::convergence:
    case FailureKind::error_test:
    case FailureKind::unknown:
      break;
  }
  std::string s = progressed ? "repeated convergence or error-test failures near the time "
                               "reached: the motion may pass a singular configuration or jump "
                               "there; a looser rtol or another scheme may pass"
                             : "repeated convergence or error-test failures right after the "
                               "start or a load step: check the state there and the tolerances; "
                               "a looser rtol or another scheme may pass";
  return s + scheme_advice(scheme, context);
}

std::string mu_roundoff_advice(const RunFailure& e, double atol_mu, double mu_floor) {
  if (!step_size_failure(e.kind) || !(atol_mu < mu_floor)) return "";
  std::ostringstream s;
  s.precision(2);
  s << "; atol_mu " << atol_mu << " lies below " << mu_floor
    << ", the smallest GGL's μ can be held to: the μ a step needs to correct the constraint "
       "rows' roundoff (its derivation is in `condyn info`); remove [solve] atol_mu (the derived "
       "value respects that floor) or set it to "
    << mu_floor << " or more";
  return s.str();
}

std::string failure_suggestion(Scheme scheme, const RunFailure& e, const std::string& causes,
                               const AdviceContext& context) {
  if (causes.empty()) return failure_suggestion(scheme, e, context);
  switch (e.kind) {
    case FailureKind::step_size_collapsed:
      return "the step size collapsed to roundoff of the time reached because a tolerance asks for "
             "more than double precision holds" +
             causes;
    case FailureKind::convergence:
    case FailureKind::error_test:
      return "repeated convergence or error-test failures because a tolerance asks for more than "
             "double precision holds" +
             causes;
    default:
      return failure_suggestion(scheme, e, context) + causes;
  }
}

}  // namespace condyn
