#include "json_text.h"

#include <cmath>
#include <cstdio>

#include "output.h"

namespace acomms::cli::geov {

std::string json_number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[40];
  std::snprintf(text, sizeof text, "%.10g", value == 0 ? 0.0 : value);  // never "-0"
  return text;
}

std::string json_string(std::string_view text) {
  // acommsctl's one JSON quoting (output.h), then <, > and & as \u escapes
  // too, so that a string is also safe inside the page's <script>. Neither
  // appears inside an escape json_quote writes, so the pass is exact.
  std::string out;
  for (char c : json_quote(std::string(text))) {
    switch (c) {
      case '<': out += "\\u003c"; break;
      case '>': out += "\\u003e"; break;
      case '&': out += "\\u0026"; break;
      default: out.push_back(c);
    }
  }
  return out;
}

std::string xml_text(std::string_view text) {
  std::string out;
  for (unsigned char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        if (c >= 0x20 || c == '\n' || c == '\t') out.push_back(static_cast<char>(c));  // XML 1.0 forbids the rest
    }
  }
  return out;
}

}  // namespace acomms::cli::geov
