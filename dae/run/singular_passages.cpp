#include "dae/run/singular_passages.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace condyn {

void SingularPassageMonitor::step(double t, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  const double sigma = conditioning_(t, u);
  best_ = std::max(best_, sigma);
  const bool near = sigma < SingularPassage::kNearSingular * best_;
  if (near && !inside_) {
    inside_ = true;
    before_t_ = outside_t_;
    before_v_ = outside_v_;
    if (before_v_[1].size() != v.size()) {  // a run that starts inside: its first velocity
      before_t_ = {t, t};
      before_v_ = {v, v};
    }
    SingularPassage p;
    p.t_enter = p.t_leave = p.t_closest = t;
    p.closest = sigma;
    p.left_open = true;
    passages_.push_back(p);
  } else if (near) {
    SingularPassage& p = passages_.back();
    p.t_leave = t;
    if (sigma < p.closest) {
      p.closest = sigma;
      p.t_closest = t;
    }
  } else if (inside_) {
    inside_ = false;
    SingularPassage& p = passages_.back();
    p.t_leave = t;
    p.left_open = false;
    p.branch_change = conditioning_.forbidden_share(velocity_before(t));
  }
  if (!near) {
    outside_t_ = {outside_t_[1], t};
    outside_v_[0] = std::move(outside_v_[1]);
    outside_v_[1] = v;
  }
}

Eigen::VectorXd SingularPassageMonitor::velocity_before(double t) const {
  const double dt = before_t_[1] - before_t_[0];
  if (before_v_[0].size() != before_v_[1].size() || !(dt > 0.0)) return before_v_[1];
  return before_v_[1] + (before_v_[1] - before_v_[0]) * ((t - before_t_[1]) / dt);
}

std::vector<SingularPassage> SingularPassageMonitor::passages() const { return passages_; }

bool SingularPassageMonitor::covers(double t) const {
  // near_singular_rows' test; the latest passages first, where a row in the last step lies.
  return std::any_of(passages_.rbegin(), passages_.rend(),
                     [t](const SingularPassage& p) { return t >= p.t_enter && t <= p.t_leave; });
}

std::vector<bool> near_singular_rows(const std::vector<SingularPassage>& passages,
                                     const std::vector<double>& row_times) {
  std::vector<bool> near(row_times.size(), false);
  for (const SingularPassage& p : passages) {
    for (std::size_t k = 0; k < row_times.size(); ++k) {
      if (row_times[k] >= p.t_enter && row_times[k] <= p.t_leave) near[k] = true;
    }
  }
  return near;
}

namespace {

/// "rows t = 0.9 to 1.1" or "rows t = 1", or "no output row" for a passage between two rows.
std::string rows_inside(const SingularPassage& p, const std::vector<double>& row_times) {
  std::vector<double> inside;
  for (double t : row_times) {
    if (t >= p.t_enter && t <= p.t_leave) inside.push_back(t);
  }
  std::ostringstream s;
  s.precision(6);
  if (inside.empty()) return "between output rows";
  s << (inside.size() == 1 ? "row t = " : "rows t = ") << inside.front();
  if (inside.size() > 1) s << " to " << inside.back();
  return s.str();
}

}  // namespace

std::string singular_passage_note(const std::vector<SingularPassage>& passages,
                                  const std::vector<double>& row_times) {
  if (passages.empty()) return "";
  std::ostringstream s;
  s.precision(3);
  s << "passed " << passages.size() << " near-singular configuration"
    << (passages.size() == 1 ? "" : "s") << " (rows' conditioning below "
    << SingularPassage::kNearSingular << " of the run's best; reactions there unreliable):";
  // The first few in full; a run around a rotating mechanism passes one every half turn.
  constexpr std::size_t kListed = 5;
  for (std::size_t k = 0; k < std::min(passages.size(), kListed); ++k) {
    const SingularPassage& p = passages[k];
    s << (k == 0 ? " " : ", ") << "t = " << p.t_closest << " (closest " << p.closest << ", "
      << rows_inside(p, row_times);
    if (p.left_branch()) s << ", left its branch";
    s << ")";
  }
  if (passages.size() > kListed) {
    const auto left = std::count_if(passages.begin() + kListed, passages.end(),
                                    [](const SingularPassage& p) { return p.left_branch(); });
    s << " and " << passages.size() - kListed << " more";
    if (left > 0) s << " (" << left << " of them leaving the branch)";
  }
  return s.str();
}

std::string singular_failure_advice(const std::vector<SingularPassage>& passages) {
  if (passages.empty() || !passages.back().left_open) return "";
  const SingularPassage& p = passages.back();
  std::ostringstream s;
  s.precision(6);
  s << "; it failed inside a near-singular configuration entered at t = " << p.t_enter
    << " (rows' conditioning " << std::setprecision(3) << p.closest
    << " at t = " << std::setprecision(6) << p.t_closest << ")";
  return s.str();
}

std::vector<std::string> singular_passage_warnings(const std::vector<SingularPassage>& passages) {
  std::vector<std::string> out;
  const auto left = std::count_if(passages.begin(), passages.end(),
                                  [](const SingularPassage& p) { return p.left_branch(); });
  if (left > 0) {
    // One warning for the run, naming the first change: each later one starts from a result
    // already on another branch.
    const SingularPassage& p = *std::find_if(
        passages.begin(), passages.end(), [](const SingularPassage& q) { return q.left_branch(); });
    std::ostringstream s;
    s.precision(3);
    s << "the run left its branch at the singular configuration near t = " << p.t_closest
      << " (conditioning " << p.closest << "): " << std::lround(100.0 * p.branch_change)
      << " % of the motion's kinetic energy before it is not a free motion after it";
    if (left > 1) s << " (and at " << left - 1 << " later passage" << (left > 2 ? "s" : "") << ")";
    s << ": the result follows another branch of the mechanism from there (energy balance "
         "intact); compare it with projection or ggl, which held the branch where index1, "
         "baumgarte and "
         "index2 left it on the reproducers of docs/schemes.md";
    out.push_back(s.str());
  }
  if (!passages.empty() && passages.back().left_open) {
    const SingularPassage& p = passages.back();
    std::ostringstream s;
    s.precision(3);
    s << "the run ended inside a near-singular configuration entered at t = " << p.t_enter
      << " (conditioning " << p.closest << " at t = " << p.t_closest
      << "): its last rows' reactions are unreliable";
    out.push_back(s.str());
  }
  return out;
}

}  // namespace condyn
