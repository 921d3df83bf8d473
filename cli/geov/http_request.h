#pragma once
// One HTTP/1.1 request head as the map server reads it: the request line
// and headers, parsed with bounds, before anything else looks at them.
//
// The map server is an interface to whoever can reach its port, so the
// parser decides early and in one place what it accepts: GET and HEAD only,
// no body, a head of at most kMaxHeadBytes, a path of printable ASCII, at
// most kMaxQueryParams query parameters, percent-decoding that refuses
// malformed escapes. Every refusal carries the HTTP status and a sentence a
// person can act on. The path is only ever compared with the built-in
// routes: it is never turned into a file name.
//
// Thread-safety: pure functions.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace acomms::cli::geov {

inline constexpr std::size_t kMaxHeadBytes = 8192;
inline constexpr std::size_t kMaxQueryParams = 16;

struct HttpRequest {
  std::string method;                          // "GET" or "HEAD"
  std::string path;                            // before '?', undecoded: "/api/track"
  std::map<std::string, std::string> query;   // decoded names and values
  std::map<std::string, std::string> headers;  // names lower-case
};

struct HttpRefusal {
  int status = 400;
  std::string reason;  // one line, for the response body and the log
};

// `head` is the text before the blank line that ends the head (without the
// final "\r\n\r\n"). Either the request or why it is refused.
struct HttpParseResult {
  std::optional<HttpRequest> request;
  HttpRefusal refusal;
};
HttpParseResult parse_http_request(std::string_view head);

// "a%20b+c" -> "a b c"; nullopt for a bad escape or a decoded control
// character.
std::optional<std::string> percent_decode(std::string_view text);

}  // namespace acomms::cli::geov
