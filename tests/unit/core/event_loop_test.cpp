// The core thread: work posted from other threads runs on it, in order;
// call() returns results and exceptions; stop() runs what was posted first.

#include "core/event_loop.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/clock.h"

namespace acomms::core {
namespace {

TEST(EventLoop, CallRunsOnTheCoreThreadAndReturns) {
  EventLoop loop;
  loop.start();
  EXPECT_FALSE(loop.on_core_thread());
  EXPECT_TRUE(loop.call([&] { return loop.on_core_thread(); }));
  EXPECT_EQ(loop.call([] { return 41 + 1; }), 42);
}

TEST(EventLoop, CallWithNoCoreThreadRunsOnTheCallersThreadInsteadOfWaitingForever) {
  EventLoop loop;
  const std::thread::id caller = std::this_thread::get_id();
  EXPECT_EQ(loop.call([] { return std::this_thread::get_id(); }), caller) << "before start()";
  loop.start();
  EXPECT_NE(loop.call([] { return std::this_thread::get_id(); }), caller);
  loop.stop();
  EXPECT_EQ(loop.call([] { return std::this_thread::get_id(); }), caller) << "after stop()";
}

TEST(EventLoop, CallPropagatesExceptions) {
  EventLoop loop;
  loop.start();
  EXPECT_THROW(loop.call([]() -> int { throw std::invalid_argument("bad"); }),
               std::invalid_argument);
  // The loop survives it.
  EXPECT_EQ(loop.call([] { return 7; }), 7);
}

TEST(EventLoop, StopRunsWorkPostedBeforeIt) {
  std::vector<int> order;
  {
    EventLoop loop;
    loop.start();
    for (int i = 0; i < 100; ++i) loop.post([&order, i] { order.push_back(i); });
    loop.stop();
    loop.stop();  // idempotent
  }
  ASSERT_EQ(order.size(), 100u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(order[i], i);
}

TEST(EventLoop, PostedExceptionIsLoggedNotFatal) {
  EventLoop loop;
  loop.start();
  loop.post([] { throw std::runtime_error("handler bug"); });
  EXPECT_EQ(loop.call([] { return 1; }), 1);
}

TEST(SimulatedClock, MovesOnlyWhenTold) {
  SimulatedClock clock(Clock::time_point(std::chrono::seconds(1'700'000'000)));
  EXPECT_DOUBLE_EQ(clock.now_seconds(), 1'700'000'000.0);
  clock.advance(std::chrono::milliseconds(1500));
  EXPECT_DOUBLE_EQ(clock.now_seconds(), 1'700'000'001.5);
  clock.set(Clock::time_point(std::chrono::seconds(5)));
  EXPECT_DOUBLE_EQ(clock.now_seconds(), 5.0);
}

}  // namespace
}  // namespace acomms::core
