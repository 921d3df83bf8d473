#include "link/backoff.h"

#include <gtest/gtest.h>

#include "link/address.h"

namespace acomms::link {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(BackoffTest, DoublesUpToMaxAndResets) {
  Backoff backoff(1, 5);
  EXPECT_EQ(backoff.next(), seconds(1));
  EXPECT_EQ(backoff.next(), seconds(2));
  EXPECT_EQ(backoff.next(), seconds(4));
  EXPECT_EQ(backoff.next(), seconds(5));
  EXPECT_EQ(backoff.next(), seconds(5));
  backoff.reset();
  EXPECT_EQ(backoff.next(), seconds(1));
}

TEST(BackoffTest, NonsenseBoundsFallBackToSaneOnes) {
  Backoff zero(0, 0);  // the config's "unset"
  EXPECT_EQ(zero.next(), seconds(1));
  EXPECT_EQ(zero.next(), seconds(1));
  Backoff fractional(0.25, 0.3);
  EXPECT_EQ(fractional.next(), milliseconds(250));
  EXPECT_EQ(fractional.next(), milliseconds(300));
}

TEST(AddressTest, ParsesHostPortAndNamesTheFieldWhenBad) {
  auto hp = parse_host_port("127.0.0.1:50100", "udp.listen");
  EXPECT_EQ(hp.host, "127.0.0.1");
  EXPECT_EQ(hp.port, "50100");
  auto v6 = parse_host_port("[::1]:7", "x");
  EXPECT_EQ(v6.host, "::1");
  EXPECT_EQ(parse_host_port("h:0", "x", /*allow_port_zero=*/true).port, "0");
  for (const char* bad : {"127.0.0.1", ":5", "h:", "h:70000", "h:0", "::1:5", "h:5x"}) {
    try {
      parse_host_port(bad, "driver.udp.peers");
      FAIL() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("driver.udp.peers"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace acomms::link
