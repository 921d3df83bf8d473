#pragma once
// A time on acommsctl's command line and in the map's URLs: seconds since
// the Unix epoch, "now", or relative to now. One parser, so `events
// --since`, `track --since` and `/api/history?from=` read times alike.
//
// Thread-safety: pure function.

#include <string>

namespace acomms::cli {

// "1712345678.5" (seconds since the Unix epoch), "now", or relative to
// `now_s`: "-30s", "-10m", "-2h", "-1d". Throws UsageError.
double parse_time(const std::string& text, double now_s);

}  // namespace acomms::cli
