#include "link/rate_table.h"

#include <gtest/gtest.h>

#include "link/transmission_rules.h"

namespace acomms::link {
namespace {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;

TEST(RateTableTest, MicroModemFramesAndBytes) {
  const uint32_t frames[] = {1, 3, 3, 2, 2, 8};
  const uint32_t bytes[] = {32, 64, 64, 256, 256, 256};
  for (int rate = 0; rate <= 5; ++rate) {
    const ModemRate* row = find_rate(rate);
    ASSERT_NE(row, nullptr);
    EXPECT_EQ(row->max_num_frames, frames[rate]);
    EXPECT_EQ(row->max_frame_bytes, bytes[rate]);
  }
  EXPECT_EQ(find_rate(-1), nullptr);
  EXPECT_EQ(find_rate(6), nullptr);
}

TEST(RateTableTest, AirTimeIsHeaderPlusBitsOverRate) {
  EXPECT_EQ(packet_air_time(*find_rate(0), 1), milliseconds(3500));       // 0.3 + 256/80
  EXPECT_EQ(packet_air_time(*find_rate(1), 3), milliseconds(300 + 6144));  // 1536/250
  EXPECT_EQ(packet_air_time(*find_rate(2), 1), milliseconds(300 + 1024));  // 512/500
  EXPECT_EQ(packet_air_time(*find_rate(3), 2), nanoseconds(300'000'000 + 3'413'333'333));
  EXPECT_EQ(packet_air_time(*find_rate(5), 8), nanoseconds(300'000'000 + 3'091'320'754));
}

TEST(TransmissionRulesTest, PrepareCheckAckPoll) {
  v1::ModemTransmission tx;
  tx.set_rate(2);
  EXPECT_EQ(prepare_data(&tx, 3), "");
  EXPECT_EQ(tx.src(), 3);
  EXPECT_EQ(tx.max_num_frames(), 3u);
  EXPECT_EQ(tx.max_frame_bytes(), 64u);
  tx.add_frame(std::string(64, 'a'));
  EXPECT_EQ(check_frames(tx), "");
  tx.add_frame(std::string(65, 'b'));
  EXPECT_NE(check_frames(tx).find("frame 1 has 65 bytes"), std::string::npos);

  v1::ModemTransmission bad_rate;
  bad_rate.set_rate(9);
  EXPECT_EQ(prepare_data(&bad_rate, 1), "rate 9 is not in 0..5");
  v1::ModemTransmission overridden;
  EXPECT_EQ(prepare_data(&overridden, 1, 100, 2), "");
  EXPECT_EQ(overridden.max_frame_bytes(), 100u);
  EXPECT_EQ(overridden.max_num_frames(), 2u);

  v1::ModemTransmission data;
  data.set_src(2);
  data.set_dest(3);
  data.add_frame(std::string("x"));
  data.add_frame(std::string("y"));
  EXPECT_TRUE(wants_ack(data, 3));
  EXPECT_FALSE(wants_ack(data, 4));
  auto ack = make_ack(data, 3);
  EXPECT_EQ(ack.type(), v1::ModemTransmission::ACK);
  EXPECT_EQ(ack.src(), 3);
  EXPECT_EQ(ack.dest(), 2);
  ASSERT_EQ(ack.acked_frame_size(), 2);
  EXPECT_TRUE(should_report(ack, 2));
  EXPECT_FALSE(should_report(ack, 5));

  v1::ModemTransmission request;
  request.set_src(7);
  request.set_dest(1);
  EXPECT_TRUE(is_poll_request(request, 1));
  EXPECT_FALSE(is_poll_request(request, 7));
  EXPECT_TRUE(is_poll_for(request, 7));
  EXPECT_FALSE(is_poll_for(data, 2));  // has frames: our own DATA echoed, not a poll
  auto answer = make_poll_response(request, 7);
  EXPECT_EQ(answer.src(), 7);
  EXPECT_EQ(answer.dest(), 1);
  EXPECT_FALSE(answer.has_time());
  // A poll heard, ending at `time`: the answer is dated from the start of
  // its reception, a mini-packet (0.7 s) earlier, for the slot budget.
  request.set_time(1000.0);
  request.set_slot_seconds(12);
  answer = make_poll_response(request, 7);
  EXPECT_DOUBLE_EQ(answer.time(), 999.3);
  EXPECT_EQ(answer.slot_seconds(), 12);
}

}  // namespace
}  // namespace acomms::link
