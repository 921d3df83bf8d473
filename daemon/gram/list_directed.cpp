// Fortran list-directed records: shared/spec/gram.md §7.1.
#include "gram/list_directed.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace acomms::gram {
namespace {

bool separator(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; }

}  // namespace

ListDirectedReader::ListDirectedReader(std::string_view text, std::string file_name)
    : file_name_(std::move(file_name)) {
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) {
      if (start < text.size()) lines_.emplace_back(text.substr(start));
      break;
    }
    lines_.emplace_back(text.substr(start, end - start));
    start = end + 1;
  }
}

bool ListDirectedReader::at_end() const {
  for (std::size_t i = next_line_; i < lines_.size(); ++i)
    for (char c : lines_[i]) {
      if (c == '!') break;
      if (!separator(c)) return false;
    }
  return true;
}

void ListDirectedReader::fail(std::size_t line, const std::string& message) const {
  throw ImportError(file_name_ + ":" + std::to_string(line) + ": " + message);
}

ListDirectedReader::Record ListDirectedReader::next_record(std::size_t min, std::size_t max,
                                                           const std::string& what) {
  Record record;
  record.line = next_line_ + 1;
  while (record.values.size() < max) {
    if (next_line_ >= lines_.size())
      fail(lines_.size(), "the file ends before " + what + " (" + std::to_string(min) +
                              " value(s) expected, " + std::to_string(record.values.size()) +
                              " found)");
    const std::string& line = lines_[next_line_++];
    std::size_t i = 0;
    while (i < line.size() && record.values.size() < max) {
      const char c = line[i];
      if (separator(c)) { ++i; continue; }
      if (c == '!') break;
      if (c == '/') { record.slash = true; break; }
      ListValue value;
      if (c == '\'' || c == '"') {
        const std::size_t close = line.find(c, i + 1);
        if (close == std::string::npos) fail(next_line_, "unterminated string in " + what);
        value.text = line.substr(i + 1, close - i - 1);
        value.quoted = true;
        i = close + 1;
      } else {
        const std::size_t start = i;
        while (i < line.size() && !separator(line[i]) && line[i] != '/' && line[i] != '!') ++i;
        value.text = line.substr(start, i - start);
        if (value.text.find('*') != std::string::npos)
          fail(next_line_, "repeat counts ('" + value.text + "') are not supported in " + what);
      }
      record.values.push_back(std::move(value));
    }
    if (record.slash) break;
  }
  // Stricter than Fortran: '/' may leave optional values at their defaults,
  // never the ones a record needs.
  if (record.values.size() < min)
    fail(record.line, what + ": " + std::to_string(min) + " value(s) expected, " +
                          std::to_string(record.values.size()) + " given");
  return record;
}

double ListDirectedReader::number(const ListValue& v, const std::string& what,
                                  std::size_t line) const {
  if (v.quoted) fail(line, what + ": a number was expected, found the string '" + v.text + "'");
  std::string text = v.text;
  for (char& c : text)  // Fortran double-precision exponents: 1.5D3
    if (c == 'd' || c == 'D') c = 'e';
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
    fail(line, what + ": '" + v.text + "' is not a number");
  return value;
}

}  // namespace acomms::gram
