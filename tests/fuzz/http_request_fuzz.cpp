// libFuzzer target: the map server's request-head parser (cli/geov/
// http_request.h), which reads whatever reaches `acommsctl geov serve`'s
// port. Any bytes must give either a request or a refusal with a 4xx/5xx
// status and a reason, never a crash; an accepted request keeps the bounds
// the parser promises.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "geov/http_request.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace acomms::cli::geov;
  const std::string_view head(reinterpret_cast<const char*>(data), size);
  HttpParseResult result = parse_http_request(head);
  if (result.request) {
    const HttpRequest& r = *result.request;
    if (r.method != "GET" && r.method != "HEAD") std::abort();
    if (r.path.empty() || r.path.front() != '/') std::abort();
    if (r.query.size() > kMaxQueryParams) std::abort();
    if (size > kMaxHeadBytes) std::abort();
  } else if (result.refusal.status < 400 || result.refusal.status > 599 || result.refusal.reason.empty()) {
    std::abort();
  }
  (void)percent_decode(head);
  return 0;
}
