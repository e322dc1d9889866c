// `condyn check`'s report and JUnit XML (src/reports/check_report.hpp).

#include "src/reports/check_report.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

namespace condyn {

namespace {

/// The length of the well-formed UTF-8 sequence at s[i] that is an XML character (Unicode's
/// Table 3-7; U+FFFE and U+FFFF are no XML characters), 0 when there is none.
std::size_t utf8_sequence(const std::string& s, std::size_t i) {
  const auto at = [&](std::size_t k) {
    return i + k < s.size() ? static_cast<unsigned char>(s[i + k]) : 0u;
  };
  const unsigned b0 = at(0);
  const auto cont = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) {
    return at(k) >= lo && at(k) <= hi;
  };
  if (b0 >= 0xC2 && b0 <= 0xDF) return cont(1) ? 2 : 0;
  if (b0 >= 0xE0 && b0 <= 0xEF) {
    const bool ok = cont(1, b0 == 0xE0 ? 0xA0 : 0x80, b0 == 0xED ? 0x9F : 0xBF) && cont(2);
    const bool non_character = b0 == 0xEF && at(1) == 0xBF && (at(2) == 0xBE || at(2) == 0xBF);
    return ok && !non_character ? 3 : 0;
  }
  if (b0 >= 0xF0 && b0 <= 0xF4) {
    return cont(1, b0 == 0xF0 ? 0x90 : 0x80, b0 == 0xF4 ? 0x8F : 0xBF) && cont(2) && cont(3) ? 4
                                                                                             : 0;
  }
  return 0;
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (static_cast<unsigned char>(c) >= 0x80) {
      // Bytes a message copied from a file (a Latin-1 degree sign, a path): XML is UTF-8 here,
      // so what is not well-formed UTF-8 becomes U+FFFD, the replacement character.
      if (const std::size_t len = utf8_sequence(s, i); len > 0) {
        out.append(s, i, len);
        i += len - 1;
      } else {
        out += "\xEF\xBF\xBD";
      }
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // XML 1.0 allows no control characters but tab, line feed and carriage return.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') {
          out += '?';
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string seconds(double s) {
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << s;
  return o.str();
}

/// The check's name in reports: its form and quantity ("ux3 at t = 1" is in the text).
std::string case_name(const CheckOutcome& o, std::size_t k) {
  const char* form = o.form == CheckSpec::Form::at_value  ? "value"
                     : o.form == CheckSpec::Form::max_abs ? "max_abs"
                                                          : "reference";
  return "check[" + std::to_string(k + 1) + "] " + o.quantity + " (" + form + ")";
}

}  // namespace

int exit_code_of(const SceneCheckResult& result) { return result.passed() ? 0 : 1; }

void print_checked_scene(std::ostream& out, const CheckedScene& scene) {
  if (!scene.result) {
    out << "ERROR " << scene.error << "\n";
    return;
  }
  const SceneCheckResult& r = *scene.result;
  out << scene.scene << " (" << r.scheme << ", " << r.steps << " steps, " << seconds(scene.seconds)
      << " s)\n";
  for (const auto& w : r.warnings) out << "  warning: " << w << "\n";
  if (!r.failure.empty()) {
    out << "  ERROR the run failed: " << r.failure << "\n";
    return;
  }
  for (std::size_t k = 0; k < r.outcomes.size(); ++k) {
    const CheckOutcome& o = r.outcomes[k];
    out << "  " << (o.passed ? "PASS " : "FAIL ") << case_name(o, k) << ": " << o.text << "\n";
  }
  if (!r.drift.empty()) out << "  FAIL drift: " << r.drift << "\n";
}

void print_check_summary(std::ostream& out, const std::vector<CheckedScene>& scenes) {
  long passed = 0, failed = 0, runs_failed = 0, bad = 0;
  for (const auto& s : scenes) {
    if (!s.result) {
      ++bad;
      continue;
    }
    if (!s.result->failure.empty()) ++runs_failed;
    for (const auto& o : s.result->outcomes) (o.passed ? passed : failed) += 1;
    if (!s.result->drift.empty()) ++failed;
  }
  out << "checks: " << passed << " passed, " << failed << " failed";
  if (runs_failed > 0) out << ", " << runs_failed << " run(s) failed";
  if (bad > 0) out << ", " << bad << " scene(s) not checked";
  out << " (" << scenes.size() << " scene" << (scenes.size() == 1 ? "" : "s") << ")\n";
}

namespace {

/// A testcase's class: "condyn." and the scene's stem, its dots as '_'. Jenkins splits a class
/// name at its last dot (package.class): the scene's path made every class 'toml'.
std::string class_name(const std::string& scene) {
  std::string stem = std::filesystem::path(scene).stem().string();
  std::replace(stem.begin(), stem.end(), '.', '_');
  return "condyn." + (stem.empty() ? std::string("scene") : stem);
}

}  // namespace

std::string junit_xml(const std::vector<CheckedScene>& scenes) {
  std::ostringstream x;
  long tests = 0, failures = 0, errors = 0;
  std::ostringstream suites;
  for (const auto& s : scenes) {
    long t = 0, f = 0, e = 0;
    std::ostringstream cases;
    if (!s.result) {
      t = e = 1;
      cases << "    <testcase classname=\"" << xml_escape(class_name(s.scene))
            << "\" name=\"scene\" time=\"" << seconds(s.seconds) << "\">\n      <error message=\""
            << xml_escape(s.error) << "\"/>\n    </testcase>\n";
    } else if (!s.result->failure.empty()) {
      t = e = 1;
      cases << "    <testcase classname=\"" << xml_escape(class_name(s.scene))
            << "\" name=\"run\" time=\"" << seconds(s.seconds)
            << "\">\n      <error message=\"the run failed: " << xml_escape(s.result->failure)
            << "\"/>\n    </testcase>\n";
    } else {
      const auto& outcomes = s.result->outcomes;
      for (std::size_t k = 0; k < outcomes.size(); ++k) {
        const CheckOutcome& o = outcomes[k];
        ++t;
        cases << "    <testcase classname=\"" << xml_escape(class_name(s.scene)) << "\" name=\""
              << xml_escape(case_name(o, k)) << "\" time=\"0\">\n";
        if (!o.passed) {
          ++f;
          cases << "      <failure message=\"" << xml_escape(o.text) << "\"/>\n";
        } else {
          cases << "      <system-out>" << xml_escape(o.text) << "</system-out>\n";
        }
        cases << "    </testcase>\n";
      }
      if (!s.result->drift.empty()) {
        ++t;
        ++f;
        cases << "    <testcase classname=\"" << xml_escape(class_name(s.scene))
              << "\" name=\"drift\" time=\"0\">\n      <failure message=\""
              << xml_escape(s.result->drift) << "\"/>\n    </testcase>\n";
      }
    }
    tests += t;
    failures += f;
    errors += e;
    // The scene's warnings (a loose rtol, a unit mistake) beside its verdicts, as the terminal
    // shows them.
    std::string warned;
    if (s.result) {
      for (const auto& w : s.result->warnings) warned += "warning: " + w + "\n";
    }
    suites << "  <testsuite name=\"" << xml_escape(s.scene) << "\" tests=\"" << t
           << "\" failures=\"" << f << "\" errors=\"" << e << "\" time=\"" << seconds(s.seconds)
           << "\">\n"
           << cases.str()
           << (warned.empty() ? "" : "    <system-err>" + xml_escape(warned) + "</system-err>\n")
           << "  </testsuite>\n";
  }
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"condyn check\" tests=\""
    << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n"
    << suites.str() << "</testsuites>\n";
  return x.str();
}

}  // namespace condyn
