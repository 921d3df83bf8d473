#include "sim/sim_envelope.h"

#include <gtest/gtest.h>

#include <random>

namespace acomms::drivers {
namespace {

SimEnvelope sample() {
  SimEnvelope e;
  e.sender = 7;
  e.position = {1.5, -2.25, -100};
  e.start = core::Clock::time_point(std::chrono::nanoseconds(1'700'000'000'123'456'789));
  e.duration = std::chrono::milliseconds(3500);
  e.transmission.set_src(7);
  e.transmission.set_dest(3);
  e.transmission.add_frame(std::string("\0\x01\xff", 3));
  return e;
}

TEST(SimEnvelopeTest, RoundTrips) {
  SimEnvelope e = sample();
  std::string error;
  auto back = decode_envelope(encode(e), &error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(back->sender, 7);
  EXPECT_EQ(back->position.y, -2.25);
  EXPECT_EQ(back->position.z, -100);
  EXPECT_EQ(back->start, e.start);
  EXPECT_EQ(back->duration, e.duration);
  EXPECT_EQ(back->transmission.SerializeAsString(), e.transmission.SerializeAsString());
}

TEST(SimEnvelopeTest, MalformedInputIsRejectedWithAReason) {
  std::string good = encode(sample());
  std::string error;
  EXPECT_FALSE(decode_envelope("", &error));
  EXPECT_NE(error.find("shorter than an envelope header"), std::string::npos);
  EXPECT_FALSE(decode_envelope("XSIM" + good.substr(4), &error));
  EXPECT_NE(error.find("bad magic"), std::string::npos);
  EXPECT_FALSE(decode_envelope(good.substr(0, good.size() - 1), &error));
  EXPECT_NE(error.find("does not match"), std::string::npos);
  EXPECT_FALSE(decode_envelope(good + "x", &error));
  std::string version = good;
  version[4] = 9;
  EXPECT_FALSE(decode_envelope(version, &error));
  std::string no_time = good;
  for (int i = 41; i < 49; ++i) no_time[i] = 0;  // zero duration
  EXPECT_FALSE(decode_envelope(no_time, &error));
  EXPECT_NE(error.find("duration"), std::string::npos);
  std::string nan = good;
  for (int i = 9; i < 17; ++i) nan[i] = '\xff';  // x = NaN
  EXPECT_FALSE(decode_envelope(nan, &error));
}

// The loopback port hears anything: an envelope that parses but is not
// physically possible must not reach the arrival arithmetic.
TEST(SimEnvelopeTest, ImpossiblePositionsAndStartsAreRejected) {
  std::string error;
  SimEnvelope far = sample();
  far.position.x = 1e300;
  EXPECT_FALSE(decode_envelope(encode(far), &error));
  EXPECT_NE(error.find("farther than 10,000 km"), std::string::npos) << error;
  far.position = {0, 0, -1e7};  // exactly the limit
  EXPECT_TRUE(decode_envelope(encode(far), &error)) << error;

  SimEnvelope late = sample();
  late.start = core::Clock::time_point(std::chrono::nanoseconds(INT64_MAX - 1));
  EXPECT_FALSE(decode_envelope(encode(late), &error));
  EXPECT_NE(error.find("not between 1970 and 2100"), std::string::npos) << error;
  late.start = core::Clock::time_point(std::chrono::nanoseconds(-1));
  EXPECT_FALSE(decode_envelope(encode(late), &error));
}

TEST(SimEnvelopeTest, HearingIsTheStartPlusTheTravelTime) {
  SimEnvelope e = sample();
  e.position = {0, 0, 0};
  auto heard = hearing(e, {3000, 0, -4000}, 1500);  // 5 km at 1500 m/s
  ASSERT_TRUE(heard);
  EXPECT_DOUBLE_EQ(heard->range_m, 5000);
  EXPECT_EQ(heard->start - e.start, std::chrono::nanoseconds(3'333'333'333));
  EXPECT_EQ(heard->end - heard->start, e.duration);
  // Farthest possible envelope, slowest sound that still arrives in a day.
  e.position = {1e7, 1e7, 1e7};
  EXPECT_TRUE(hearing(e, {-1e7, -1e7, -1e7}, 500));
  EXPECT_FALSE(hearing(e, {-1e7, -1e7, -1e7}, 1)) << "more than a day of travel";
}

TEST(SimEnvelopeTest, RandomBytesNeverCrash) {
  std::mt19937 rng(1);
  std::string good = encode(sample());
  for (int i = 0; i < 20000; ++i) {
    std::string bytes = good;
    // Flip a few bytes of a valid envelope, or cut it short.
    int flips = 1 + static_cast<int>(rng() % 4);
    for (int f = 0; f < flips; ++f) bytes[rng() % bytes.size()] = static_cast<char>(rng());
    if (rng() % 4 == 0) bytes.resize(rng() % bytes.size());
    std::string error;
    decode_envelope(bytes, &error);
  }
}

}  // namespace
}  // namespace acomms::drivers
