// Packets sent and not received, as a Micro-Modem reports them (spec §8.6),
// told by the driver through on_reception_failed so that the event log
// counts them and `acommsctl link calibrate` sees failures (issue 32):
// which failures are told, from whom, with which figures, and only once.
// The driver against fake Micro-Modems on simulated time.

#include <gtest/gtest.h>

#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"
#include "micromodem_driver_fixture.h"

namespace acomms::fake_micromodem {
namespace {

class MicroModemLostPacketsTest : public MicroModemDriverTest {
 protected:
  // Nodes 1 and 2, 1500 m apart; node 2's modem loses every frame it
  // receives (BAD_CRC) or every PSK header, as asked.
  void nodes(double b_frame_errors, double a_header_errors = 0, double b_header_errors = 0) {
    a_ = std::make_unique<Node>(water_, scheduler_, 1, Generation::kMM2, Position{0, 0, 0}, std::vector<std::string>{},
                                0, 0, a_header_errors);
    b_ = std::make_unique<Node>(water_, scheduler_, 2, Generation::kMM2, Position{1500, 0, 0},
                                std::vector<std::string>{}, 0, b_frame_errors, b_header_errors);
    nodes_ = {a_.get(), b_.get()};
    for (Node* node : nodes_) {
      node->start();
      node->modem.power_on();
    }
    run(8s);
    ASSERT_TRUE(a_->driver->ready());
    ASSERT_TRUE(b_->driver->ready());
  }
};

// Rate 0 (FSK) carries no cycle header (§5.1): the destination hears the
// cycle-init ($CACYC and its own $CACST), then the data packet, whose every
// frame failed: $CARXP, $CAMSG,BAD_CRC, $CACST mode 1 and no $CACYC. The
// cycle-init named the sender, so the packet is told lost from it, with
// the $CACST's figures, once.
TEST_F(MicroModemLostPacketsTest, ARateZeroPacketWhoseFramesFailedIsToldLostFromItsCycleInit) {
  nodes(/*b_frame_errors=*/1.0);
  a_->frames_to_send = {std::string(20, 'a')};
  a_->driver->initiate_transmission(data_to(1, 2, 0));
  run(30s);
  EXPECT_TRUE(b_->received_of(ModemTransmission::DATA).empty());
  ASSERT_EQ(b_->failed.size(), 1u) << "the damaged rate-0 packet";
  const ModemTransmission& lost = b_->failed[0];
  EXPECT_EQ(lost.src(), 1);
  EXPECT_EQ(lost.dest(), 2);
  EXPECT_EQ(lost.rate(), 0);
  ASSERT_TRUE(lost.has_figures());
  EXPECT_EQ(lost.figures().bad_frames(), 1u);
  EXPECT_EQ(lost.figures().packet_type(), 1) << "FSK data, not the cycle-init mini-packet";
  EXPECT_NEAR(lost.figures().snr_in_db(), 36.5, 0.1) << "the fake's 100 - 20 log10(1500)";
  EXPECT_EQ(b_->driver->reception_counters().lost_told, 1u);
  EXPECT_EQ(b_->driver->reception_counters().unattributed, 0u);

  // The next packet decodes (the fake's frames fail no more): no loss told
  // for it, and the earlier cycle-init is not taken to announce it twice.
  b_->modem.set_frame_error_probability(0);
  a_->driver->initiate_transmission(data_to(1, 2, 0));
  run(30s);
  EXPECT_EQ(b_->received_of(ModemTransmission::DATA).size(), 1u);
  EXPECT_EQ(b_->failed.size(), 1u);
}

// A PSK packet whose header did not decode (§8.6: $CARXP,1 and a $CACST
// with mode 1, PSK error 1, no $CACYC, no frame): an answer to our poll is
// told lost from the polled node, with the figures; the modem's later
// PACKET_TIMEOUT for the same poll tells nothing more.
TEST_F(MicroModemLostPacketsTest, AnAnswerToOurPollWhoseHeaderDidNotDecodeIsToldLostOnce) {
  nodes(0, /*a_header_errors=*/1.0);
  b_->frames_to_send = {std::string("\x01\x02", 2)};
  a_->driver->initiate_transmission(data_to(2, 1, 1));
  run(40s);
  EXPECT_TRUE(a_->received_of(ModemTransmission::DATA).empty());
  ASSERT_EQ(a_->failed.size(), 1u);
  const ModemTransmission& lost = a_->failed[0];
  EXPECT_EQ(lost.src(), 2);
  EXPECT_EQ(lost.dest(), 1);
  EXPECT_EQ(lost.rate(), 1);
  ASSERT_TRUE(lost.has_figures()) << "detected: the $CACST's figures are real";
  EXPECT_EQ(lost.figures().psk_error(), 1u);
  EXPECT_NEAR(lost.figures().snr_in_db(), 36.5, 0.1);
}

// A damaged packet that nothing names: a PSK broadcast whose header did
// not decode at a node that polled no one and heard no cycle-init. The
// $CACST's source is not trusted for a packet the modem could not decode:
// counted, not told (no guess in the calibration's data).
TEST_F(MicroModemLostPacketsTest, ADamagedPacketNothingNamesIsCountedNotTold) {
  nodes(0, 0, /*b_header_errors=*/1.0);
  a_->frames_to_send = {std::string(20, 'a')};
  a_->driver->initiate_transmission(data_to(1, 0, 1));
  run(30s);
  EXPECT_TRUE(b_->received_of(ModemTransmission::DATA).empty());
  EXPECT_TRUE(b_->failed.empty());
  EXPECT_EQ(b_->driver->reception_counters().unattributed, 1u);
  EXPECT_EQ(b_->driver->reception_counters().lost_told, 0u);
  const auto bad_input = b_->driver->counters().bad_input;
  ASSERT_EQ(bad_input.count("damaged packet, sender unknown"), 1u) << "shown by acommsctl link status";
  EXPECT_EQ(bad_input.at("damaged packet, sender unknown"), 1u);
}

// A cycle-init we could not read (a damaged mini-packet) is the next packet
// after an earlier one: node 3's cycle-init to node 2 was heard, 3's data
// never came (and no PACKET_TIMEOUT was printed), then node 4's cycle-init
// came damaged and 4's rate-0 data damaged too. That data is nobody's the
// driver can name (counted, not told), never node 3's.
TEST_F(MicroModemLostPacketsTest, ADamagedCycleInitForgetsTheSenderAnnouncedBeforeIt) {
  nodes(0);
  using namespace acomms::micromodem;
  auto line = [](const Sentence& sentence) { return serialize(sentence) + "\r\n"; };
  auto statistics = [](int mode, int source, int packet_type, int bad_frames) {
    ReceiveStatistics s;
    s.version = 8;
    s.mode = mode;
    s.time_of_arrival = "20231114221320.0000";
    s.rate = 0;
    s.source = source;
    s.destination = 2;
    s.packet_type = packet_type;
    s.frames = 1;
    s.bad_frames = bad_frames;
    s.snr_in = 30;
    return s;
  };
  // 3's cycle-init, heard.
  b_->modem.write_raw(line(to_sentence(ReceiveStarted{0})));
  b_->modem.write_raw(line(to_sentence(Cycle{0, 3, 2, 0, true, 1}, Talker::kModem)));
  b_->modem.write_raw(line(to_sentence(statistics(0, 3, kPacketFskMini, 0))));
  run(3s);
  // 4's cycle-init, damaged (BAD_CRC value 2: a mini-packet).
  b_->modem.write_raw(line(to_sentence(ReceiveStarted{0})));
  b_->modem.write_raw(line(to_sentence(TransactionMessage{"BAD_CRC", "2"})));
  b_->modem.write_raw(line(to_sentence(statistics(1, 4, kPacketFskMini, 1))));
  run(3s);
  // 4's rate-0 data, every frame bad.
  b_->modem.write_raw(line(to_sentence(ReceiveStarted{0})));
  b_->modem.write_raw(line(to_sentence(TransactionMessage{"BAD_CRC", "1"})));
  b_->modem.write_raw(line(to_sentence(statistics(1, 4, kPacketFsk, 1))));
  run(3s);
  EXPECT_TRUE(b_->failed.empty()) << "not credited to node 3";
  EXPECT_EQ(b_->driver->reception_counters().lost_told, 0u);
  EXPECT_EQ(b_->driver->reception_counters().unattributed, 1u);
}

}  // namespace
}  // namespace acomms::fake_micromodem
