// "Core thread only" is checked, not only written: while an EventLoop runs,
// a core-thread function called from any other thread aborts naming itself;
// on the core thread, or while no core runs (start-up, shutdown, tests on
// the simulated scheduler), it passes.

#include "core/core_thread.h"

#include <gtest/gtest.h>

#include <thread>

#include "core/event_loop.h"
#include "core/logging.h"

namespace acomms::core {
namespace {

// Stands for any function documented "core thread only".
int core_only_function() {
  ACOMMS_ASSERT_CORE_THREAD();
  return 42;
}

TEST(CoreThread, AnyThreadMayCallWhileNoCoreRuns) {
  EXPECT_EQ(core_only_function(), 42);
  int from_other = 0;
  std::thread([&] { from_other = core_only_function(); }).join();
  EXPECT_EQ(from_other, 42);
}

TEST(CoreThread, TheCoreThreadMayCall) {
  EventLoop loop;
  loop.start();
  EXPECT_EQ(loop.call([] { return core_only_function(); }), 42);
}

TEST(CoreThreadDeathTest, AnotherThreadFailsTheAssertionWhileTheCoreRuns) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        configure_logging(v1::INFO);  // the daemon's logger: stderr
        EventLoop loop;
        loop.start();
        core_only_function();
      },
      "core_only_function.* must run on the core thread");
}

TEST(CoreThread, TheRuleLiftsOnceTheCoreStops) {
  {
    EventLoop loop;
    loop.start();
    loop.stop();
  }
  EXPECT_EQ(core_only_function(), 42);
}

}  // namespace
}  // namespace acomms::core
