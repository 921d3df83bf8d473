// A numeric CSV table from shared/conformance/gram, read at run time (the
// reference values are never copied into tests). Columns are looked up by
// header name so a reordered file cannot silently shift values.
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace acomms::gram::test {

inline std::string conformance_path(const std::string& name) {
  return std::string(ACOMMS_SHARED_DIR) + "/conformance/gram/" + name;
}

class CsvTable {
 public:
  explicit CsvTable(const std::string& name) {
    std::ifstream in(conformance_path(name));
    if (!in) throw std::runtime_error("cannot open " + conformance_path(name));
    std::string line;
    std::getline(in, line);
    std::stringstream header(line);
    for (std::string cell; std::getline(header, cell, ',');) names_.push_back(cell);
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      std::stringstream row(line);
      std::vector<double> values;
      std::vector<std::string> texts;
      for (std::string cell; std::getline(row, cell, ',');) {
        values.push_back(std::stod(cell));
        texts.push_back(cell);
      }
      rows_.push_back(std::move(values));
      texts_.push_back(std::move(texts));
    }
  }
  std::size_t size() const { return rows_.size(); }
  double at(std::size_t row, const std::string& column) const {
    return rows_.at(row).at(index(column));
  }
  // The cell as printed (to tell how many digits an input was rounded to).
  const std::string& text(std::size_t row, const std::string& column) const {
    return texts_.at(row).at(index(column));
  }
  // Half a unit of the last printed decimal of a cell.
  double half_unit(std::size_t row, const std::string& column) const {
    const std::string& t = text(row, column);
    const auto dot = t.find('.');
    const int decimals = dot == std::string::npos ? 0 : static_cast<int>(t.size() - dot - 1);
    double unit = 0.5;
    for (int i = 0; i < decimals; ++i) unit /= 10.0;
    return unit;
  }

 private:
  std::size_t index(const std::string& column) const {
    for (std::size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == column) return i;
    throw std::runtime_error("no column " + column);
  }
  std::vector<std::string> names_;
  std::vector<std::vector<std::string>> texts_;
  std::vector<std::vector<double>> rows_;
};

}  // namespace acomms::gram::test
