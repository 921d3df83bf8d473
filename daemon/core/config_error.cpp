#include "core/config_error.h"

#include <sstream>

namespace acomms::core {
namespace {

std::string describe(const std::string& file, int line, int column, const std::string& field,
                     const std::string& problem) {
  std::ostringstream text;
  text << file;
  if (line > 0) {
    text << ':' << line;
    if (column > 0) text << ':' << column;
  }
  text << ": ";
  if (!field.empty()) text << "field '" << field << "': ";
  text << problem;
  return text.str();
}

}  // namespace

ConfigError::ConfigError(std::string file, int line, int column, std::string field,
                         std::string problem)
    : std::runtime_error(describe(file, line, column, field, problem)),
      file_(std::move(file)),
      line_(line),
      column_(column),
      field_(std::move(field)),
      problem_(std::move(problem)) {}

}  // namespace acomms::core
