#include "output.h"

#include <google/protobuf/util/json_util.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>

namespace acomms::cli {

std::string json_with_defaults(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json;
}

void print_json(const google::protobuf::Message& message) { std::cout << json_with_defaults(message) << "\n"; }

std::string json_quote(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string number_text(double value) {
  if (!std::isfinite(value)) return "null";  // JSON has no NaN or infinity
  char buffer[64];
  auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return error == std::errc() ? std::string(buffer, end) : "null";
}

std::string route_text(int32_t src, int32_t dest) {
  std::string from = src < 0 ? "-" : std::to_string(src);
  std::string to = dest < 0 ? "-" : dest == 0 ? "all" : std::to_string(dest);
  return from + ">" + to;
}

std::string utc_text(double seconds) {
  if (seconds <= 0) return "-";
  auto whole = static_cast<std::time_t>(std::floor(seconds));
  int millis = static_cast<int>((seconds - static_cast<double>(whole)) * 1000);
  std::tm parts{};
  gmtime_r(&whole, &parts);
  char buffer[96];
  std::snprintf(buffer, sizeof(buffer), "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", parts.tm_year + 1900,
                parts.tm_mon + 1, parts.tm_mday, parts.tm_hour, parts.tm_min, parts.tm_sec, millis);
  return buffer;
}

}  // namespace acomms::cli
