// `condyn check`'s report and JUnit XML (src/check_report.hpp).

#include "src/check_report.hpp"

#include <sstream>

namespace condyn {

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
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
  if (!r.failure.empty()) {
    out << "  ERROR the run failed: " << r.failure << "\n";
    return;
  }
  for (std::size_t k = 0; k < r.outcomes.size(); ++k) {
    const CheckOutcome& o = r.outcomes[k];
    out << "  " << (o.passed ? "PASS " : "FAIL ") << case_name(o, k) << ": " << o.text << "\n";
  }
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
  }
  out << "checks: " << passed << " passed, " << failed << " failed";
  if (runs_failed > 0) out << ", " << runs_failed << " run(s) failed";
  if (bad > 0) out << ", " << bad << " scene(s) not checked";
  out << " (" << scenes.size() << " scene" << (scenes.size() == 1 ? "" : "s") << ")\n";
}

std::string junit_xml(const std::vector<CheckedScene>& scenes) {
  std::ostringstream x;
  long tests = 0, failures = 0, errors = 0;
  std::ostringstream suites;
  for (const auto& s : scenes) {
    long t = 0, f = 0, e = 0;
    std::ostringstream cases;
    if (!s.result) {
      t = e = 1;
      cases << "    <testcase classname=\"" << xml_escape(s.scene) << "\" name=\"scene\" time=\""
            << seconds(s.seconds) << "\">\n      <error message=\"" << xml_escape(s.error)
            << "\"/>\n    </testcase>\n";
    } else if (!s.result->failure.empty()) {
      t = e = 1;
      cases << "    <testcase classname=\"" << xml_escape(s.scene) << "\" name=\"run\" time=\""
            << seconds(s.seconds)
            << "\">\n      <error message=\"the run failed: " << xml_escape(s.result->failure)
            << "\"/>\n    </testcase>\n";
    } else {
      const auto& outcomes = s.result->outcomes;
      for (std::size_t k = 0; k < outcomes.size(); ++k) {
        const CheckOutcome& o = outcomes[k];
        ++t;
        cases << "    <testcase classname=\"" << xml_escape(s.scene) << "\" name=\""
              << xml_escape(case_name(o, k)) << "\" time=\"0\">\n";
        if (!o.passed) {
          ++f;
          cases << "      <failure message=\"" << xml_escape(o.text) << "\"/>\n";
        } else {
          cases << "      <system-out>" << xml_escape(o.text) << "</system-out>\n";
        }
        cases << "    </testcase>\n";
      }
    }
    tests += t;
    failures += f;
    errors += e;
    suites << "  <testsuite name=\"" << xml_escape(s.scene) << "\" tests=\"" << t
           << "\" failures=\"" << f << "\" errors=\"" << e << "\" time=\"" << seconds(s.seconds)
           << "\">\n"
           << cases.str() << "  </testsuite>\n";
  }
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"condyn check\" tests=\""
    << tests << "\" failures=\"" << failures << "\" errors=\"" << errors << "\">\n"
    << suites.str() << "</testsuites>\n";
  return x.str();
}

}  // namespace condyn
