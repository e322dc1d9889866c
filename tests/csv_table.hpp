#pragma once
// A condyn CSV result read back for the tests: its header and its columns by name.

#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace condyn::test {

struct CsvTable {
  std::vector<std::string> header;
  std::map<std::string, std::vector<double>> columns;

  /// The header as written: the names joined by commas.
  [[nodiscard]] std::string header_line() const {
    std::string line;
    for (const auto& name : header) line += (line.empty() ? "" : ",") + name;
    return line;
  }
};

/// Every cell after the header read as a number (std::stod: condyn writes shortest round-trip
/// digits, so each value is the one computed).
inline CsvTable read_csv_table(const std::string& text) {
  CsvTable out;
  std::istringstream lines(text);
  std::string line, cell;
  std::getline(lines, line);
  for (std::istringstream cells(line); std::getline(cells, cell, ',');) out.header.push_back(cell);
  while (std::getline(lines, line)) {
    std::istringstream cells(line);
    for (const auto& name : out.header) {
      std::getline(cells, cell, ',');
      out.columns[name].push_back(std::stod(cell));
    }
  }
  return out;
}

}  // namespace condyn::test
