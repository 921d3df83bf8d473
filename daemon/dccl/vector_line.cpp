#include "dccl/vector_line.h"

#include <stdexcept>

namespace acomms::dccl {
namespace {

std::string_view trim(std::string_view s) {
  size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// Position of the first " => " outside a '...' or "..." literal (text
// format escapes a quote inside one with a backslash), or npos.
size_t find_arrow(std::string_view text) {
  char quote = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (quote != 0) {
      if (c == '\\') {
        ++i;
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (text.compare(i, 4, " => ") == 0) {
      return i;
    }
  }
  return std::string_view::npos;
}

}  // namespace

VectorLine parse_vector_line(std::string_view line) {
  line = trim(line);
  if (line.empty() || line[0] != '|') throw std::invalid_argument("expected |type.Name| <text format>");
  size_t close = line.find('|', 1);
  if (close == std::string_view::npos) throw std::invalid_argument("missing closing '|' after the type name");
  VectorLine out;
  out.type = std::string(line.substr(1, close - 1));
  std::string_view rest = line.substr(close + 1);
  size_t arrow = find_arrow(rest);
  if (arrow == std::string_view::npos) {
    out.text = std::string(rest);
  } else {
    out.text = std::string(rest.substr(0, arrow));
    out.hex = std::string(trim(rest.substr(arrow + 4)));
  }
  return out;
}

}  // namespace acomms::dccl
