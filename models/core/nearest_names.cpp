#include "models/core/nearest_names.hpp"

#include <algorithm>
#include <cctype>
#include <utility>
#include <vector>

namespace condyn {

namespace {

std::string lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::size_t name_distance(const std::string& a_text, const std::string& b_text) {
  const std::string a = lowercase(a_text), b = lowercase(b_text);
  // Three rows of the dynamic programme: two back, for a swap of adjacent characters.
  std::vector<std::size_t> before(b.size() + 1), last(b.size() + 1), row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) last[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      row[j] = std::min({last[j] + 1, row[j - 1] + 1, last[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        row[j] = std::min(row[j], before[j - 2] + 1);
      }
    }
    std::swap(before, last);
    std::swap(last, row);
  }
  return last[b.size()];
}

std::vector<std::string> nearest_names(const std::string& name,
                                       const std::vector<std::string>& candidates,
                                       std::size_t most) {
  constexpr std::size_t kMinContained = 3;  // "x" is in every name that has an x: no hint
  const std::size_t within = std::max<std::size_t>(1, name.size() / 3);
  const std::string folded = lowercase(name);
  std::vector<std::pair<std::size_t, std::size_t>> near;  // (score, index)
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const std::string other = lowercase(candidates[k]);
    const std::size_t d = name_distance(folded, other);
    const bool contained =
        std::min(folded.size(), other.size()) >= kMinContained &&
        (other.find(folded) != std::string::npos || folded.find(other) != std::string::npos);
    // Within a typo or two, and not a rewrite of the whole name ('q' is not near 'a'); a name
    // that contains the other ranks as the farthest typo still taken.
    const bool typo = d <= within && d < std::max(folded.size(), other.size());
    if (typo) {
      near.emplace_back(d, k);
    } else if (contained) {
      near.emplace_back(within, k);
    }
  }
  std::stable_sort(near.begin(), near.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  // The nearest alone: ux7 for UX7, not ux1 and uy7 one edit further.
  std::vector<std::string> out;
  for (std::size_t k = 0; k < near.size() && k < most && near[k].first == near[0].first; ++k) {
    out.push_back(candidates[near[k].second]);
  }
  return out;
}

std::string joined_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace condyn
