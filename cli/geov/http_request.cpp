#include "http_request.h"

#include <algorithm>
#include <cctype>

namespace acomms::cli::geov {
namespace {

HttpParseResult refuse(int status, std::string reason) { return {std::nullopt, {status, std::move(reason)}}; }

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool printable(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](unsigned char c) { return c > 0x20 && c < 0x7f; });
}

// Splits "a=1&b=2" into `query`; false (with `reason`) on a bad part.
bool parse_query(std::string_view text, std::map<std::string, std::string>& query, std::string& reason) {
  std::size_t count = 0;
  while (!text.empty()) {
    const std::size_t amp = text.find('&');
    std::string_view part = text.substr(0, amp);
    text = amp == std::string_view::npos ? std::string_view() : text.substr(amp + 1);
    if (part.empty()) continue;
    if (++count > kMaxQueryParams) {
      reason = "more than " + std::to_string(kMaxQueryParams) + " query parameters";
      return false;
    }
    const std::size_t eq = part.find('=');
    auto name = percent_decode(part.substr(0, eq));
    auto value = percent_decode(eq == std::string_view::npos ? std::string_view() : part.substr(eq + 1));
    if (!name || !value) {
      reason = "bad percent-escape in the query";
      return false;
    }
    query[*name] = *value;
  }
  return true;
}

}  // namespace

std::optional<std::string> percent_decode(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '+') {
      c = ' ';
    } else if (c == '%') {
      if (i + 2 >= text.size()) return std::nullopt;
      const int high = hex_value(text[i + 1]);
      const int low = hex_value(text[i + 2]);
      if (high < 0 || low < 0) return std::nullopt;
      c = static_cast<char>(high * 16 + low);
      i += 2;
    }
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return std::nullopt;
    out.push_back(c);
  }
  return out;
}

HttpParseResult parse_http_request(std::string_view head) {
  if (head.size() > kMaxHeadBytes) {
    return refuse(431, "request head longer than " + std::to_string(kMaxHeadBytes) + " bytes");
  }
  const std::size_t line_end = head.find("\r\n");
  const std::string_view line = head.substr(0, line_end);
  const std::size_t sp1 = line.find(' ');
  const std::size_t sp2 = sp1 == std::string_view::npos ? sp1 : line.find(' ', sp1 + 1);
  if (sp2 == std::string_view::npos || line.find(' ', sp2 + 1) != std::string_view::npos) {
    return refuse(400, "malformed request line (want: METHOD /path HTTP/1.1)");
  }
  HttpRequest request;
  request.method = std::string(line.substr(0, sp1));
  const std::string_view target = line.substr(sp1 + 1, sp2 - sp1 - 1);
  const std::string_view version = line.substr(sp2 + 1);
  if (version != "HTTP/1.1" && version != "HTTP/1.0") return refuse(505, "only HTTP/1.0 and HTTP/1.1");
  if (request.method != "GET" && request.method != "HEAD") {
    return refuse(405, "method " + std::string(request.method.substr(0, 16)) + " not allowed: only GET and HEAD");
  }
  if (target.empty() || target.front() != '/' || !printable(target)) {
    return refuse(400, "the target must be a path starting with '/', printable ASCII");
  }
  const std::size_t question = target.find('?');
  request.path = std::string(target.substr(0, question));
  if (question != std::string_view::npos) {
    std::string reason;
    if (!parse_query(target.substr(question + 1), request.query, reason)) return refuse(400, reason);
  }
  std::string_view rest = line_end == std::string_view::npos ? std::string_view() : head.substr(line_end + 2);
  while (!rest.empty()) {
    const std::size_t end = rest.find("\r\n");
    const std::string_view header = rest.substr(0, end);
    rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 2);
    const std::size_t colon = header.find(':');
    if (colon == std::string_view::npos || colon == 0) return refuse(400, "malformed header line");
    const std::string_view name = header.substr(0, colon);
    if (!printable(name)) return refuse(400, "malformed header name");
    request.headers[lower(name)] = std::string(trim(header.substr(colon + 1)));
  }
  // No request here carries a body; one announced is refused rather than
  // left unread in front of the next request.
  auto length = request.headers.find("content-length");
  if ((length != request.headers.end() && length->second != "0") || request.headers.count("transfer-encoding")) {
    return refuse(413, "a request body is not accepted");
  }
  return {std::move(request), {}};
}

}  // namespace acomms::cli::geov
