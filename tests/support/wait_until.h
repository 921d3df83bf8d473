#pragma once
// Waiting for another thread or process to get somewhere, with a bound.
//
// A test never sleeps a fixed time to let something happen: it waits for the
// event that shows it happened (a status, a count, a log line), polling
// until a deadline after which the test fails and says what it waited for.
// Tests had written this loop by hand in several shapes (while/sleep_for,
// do/while with an early break); this is the one.
//
// Thread-safe: a free function; the condition runs on the calling thread.

#include <chrono>
#include <functional>

namespace acomms::testing {

// Polls `condition` every `poll` until it holds (true) or `timeout` has
// passed (false). The condition is asked at least once, and again after
// every sleep, the last one included.
bool wait_until(const std::function<bool()>& condition, std::chrono::milliseconds timeout,
                std::chrono::milliseconds poll = std::chrono::milliseconds(20));

}  // namespace acomms::testing
