// The fake Micro-Modem itself: two fakes in one process on simulated time
// play spec §8's sequences, with travel time from their positions.

#include <gtest/gtest.h>

#include <chrono>

#include "fake_modem_host.h"
#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"

namespace acomms::fake_micromodem {
namespace {

using namespace std::chrono_literals;
using micromodem::Sentence;
using micromodem::Talker;

FakeModemConfig config(int address, Generation generation, Position position) {
  FakeModemConfig config;
  config.address = address;
  config.generation = generation;
  config.position = position;
  return config;
}

class FakeMicroModemTest : public ::testing::Test {
 protected:
  FakeMicroModemTest(Generation generation = Generation::kMM2)
      : a_(water_, config(1, generation, {0, 0, 0})),
        b_(water_, config(2, generation, {1500, 0, 0})),
        host_a_(a_, scheduler_.clock()),
        host_b_(b_, scheduler_.clock()) {
    a_.power_on();
    b_.power_on();
    run(2s);
    host_a_.clear();
    host_b_.clear();
  }

  void run(Duration d) { scheduler_.run_for(d); }
  core::Clock::time_point now() const { return scheduler_.clock().now(); }

  // Answers every $CADRQ of `modem` with the next of `frames` (then empty).
  void answer_data_requests(FakeModemHost& host, std::vector<std::string> frames, bool ack) {
    size_t answered = 0;
    for (int step = 0; step < 400; ++step) {
      size_t requests = host.count("CADRQ");
      while (answered < requests) {
        const HeardLine* request = nullptr;
        size_t seen = 0;
        for (const HeardLine& line : host.lines()) {
          if (line.sentence.is("CADRQ") && seen++ == answered) request = &line;
        }
        auto drq = micromodem::parse_data_request(request->sentence).value();
        std::string data = answered < frames.size() ? frames[answered] : "";
        host.send(to_sentence(micromodem::TransmitData{drq.source, drq.destination, ack, data}));
        ++answered;
      }
      run(50ms);
    }
  }

  core::SimulatedScheduler scheduler_{core::Clock::time_point{} + std::chrono::hours(24 * 365 * 56)};
  Water water_{scheduler_, {}};
  FakeMicroModem a_;
  FakeMicroModem b_;
  FakeModemHost host_a_;
  FakeModemHost host_b_;
};

TEST_F(FakeMicroModemTest, PowerOnPrintsInitThenTheAuvAndCoprocRevisions) {
  a_.reboot();
  run(2s);
  ASSERT_EQ(host_a_.addresses(), (std::vector<std::string>{"CAREV", "CAREV", "CAREV"}));
  auto init = micromodem::parse_revision(host_a_.lines()[0].sentence).value();
  auto auv = micromodem::parse_revision(host_a_.lines()[1].sentence).value();
  EXPECT_TRUE(init.is_boot());
  EXPECT_EQ(auv.identifier, "AUV");
  EXPECT_EQ(micromodem::modem_generation(auv.revision).value(), micromodem::ModemGeneration::kMM2);
  EXPECT_EQ(host_a_.lines()[2].sentence.field(2), "COPROC");
}

TEST_F(FakeMicroModemTest, ConfigWritesAreEchoedAfterTheNvramDelayAndUnknownNamesRefused) {
  auto sent = now();
  host_a_.send(to_sentence(micromodem::ConfigParameter{"xst", "1"}, Talker::kHost));
  run(1s);
  ASSERT_EQ(host_a_.addresses(), std::vector<std::string>{"CACFG"});
  EXPECT_EQ(host_a_.lines()[0].sentence.fields, (std::vector<std::string>{"XST", "1"}));
  EXPECT_EQ(host_a_.lines()[0].at - sent, 100ms);
  EXPECT_TRUE(a_.nvram().flag("XST"));
  host_a_.clear();
  host_a_.send(to_sentence(micromodem::ConfigParameter{"QQQ", "1"}, Talker::kHost));
  host_a_.send(to_sentence(micromodem::ConfigQuery{"SRC"}));
  run(1s);
  EXPECT_EQ(host_a_.addresses(), (std::vector<std::string>{"CAERR", "CACFG"}));
  EXPECT_EQ(host_a_.lines()[1].sentence.fields, (std::vector<std::string>{"SRC", "1"}));
}

TEST_F(FakeMicroModemTest, ACommandWithABadChecksumIsRefusedWithCaerrBadChecksum) {
  host_a_.send_raw("$CCCFG,XST,1*00\r\n");
  host_a_.send_raw("$CCCFG,XST,1\r\n");  // no checksum at all: accepted (§2.3)
  run(1s);
  ASSERT_EQ(host_a_.addresses(), (std::vector<std::string>{"CAERR", "CACFG"}));
  auto error = micromodem::parse_modem_error(host_a_.lines()[0].sentence).value();
  EXPECT_EQ(error.module, "NMEA");
  EXPECT_EQ(error.message, "Bad checksum");
}

TEST_F(FakeMicroModemTest, ACycleFromADeliversCarxdToBAfterRangeOverSoundSpeedAndIsAcknowledged) {
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, true, 1}, Talker::kHost));
  answer_data_requests(host_a_, {"Hello"}, true);
  run(20s);
  const HeardLine* txp = host_a_.first("CATXP");
  const HeardLine* rxp = host_b_.first("CARXP");
  ASSERT_TRUE(txp && rxp);
  EXPECT_EQ(rxp->at - txp->at, 1s) << "1500 m at 1500 m/s";
  EXPECT_EQ(rxp->sentence.field(1), "1") << "PSK";
  const HeardLine* rxd = host_b_.first("CARXD");
  ASSERT_TRUE(rxd);
  auto frame = micromodem::parse_received_data(rxd->sentence).value();
  EXPECT_EQ(frame, (micromodem::ReceivedData{1, 2, true, 1, "Hello"}));
  // B: the PSK header's $CACYC, the frame, its statistics, then B's modem
  // sends the acknowledgement by itself.
  EXPECT_EQ(host_b_.addresses(), (std::vector<std::string>{"CARXP", "CACYC", "CARXD", "CACST",
                                                            "CATXP", "CATXF"}));
  const HeardLine* ack = host_a_.first("CAACK");
  ASSERT_TRUE(ack);
  EXPECT_EQ(micromodem::parse_acknowledgement(ack->sentence).value(),
            (micromodem::Acknowledgement{2, 1, 1}));
  const HeardLine* ack_txp = &host_b_.lines()[4];
  EXPECT_EQ(ack->at - ack_txp->at, 1s + 700ms + 100ms) << "travel + mini air time + decode";
}

TEST_F(FakeMicroModemTest, Rate0SenderSeesTheSpecsSequence) {
  host_a_.send(to_sentence(micromodem::ConfigParameter{"XST", "1"}, Talker::kHost));
  run(1s);
  host_a_.clear();
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 0, true, 1}, Talker::kHost));
  answer_data_requests(host_a_, {"Hello"}, true);
  run(20s);
  // §8.1 rows 2, 3, 5, 6, 8, 10, 11, 13, 16, 18.
  EXPECT_EQ(host_a_.addresses(),
            (std::vector<std::string>{"CACYC", "CATXP", "CATXF", "CAXST", "CADRQ", "CATXD", "CATXP",
                                      "CATXF", "CAXST", "CARXP", "CAACK", "CACST"}));
  auto mini = micromodem::parse_transmit_statistics(host_a_.lines()[3].sentence).value();
  EXPECT_EQ(mini.packet_type, micromodem::kPacketFskMini);
  auto data = micromodem::parse_transmit_statistics(host_a_.lines()[8].sentence).value();
  EXPECT_EQ(data.packet_type, micromodem::kPacketFsk);
  EXPECT_EQ(data.bytes, 5);
  EXPECT_EQ(data.version, 7);
  // The destination prints two $CACST: the cycle-init's and the data's.
  EXPECT_EQ(host_b_.count("CACST"), 2u);
  EXPECT_EQ(host_b_.count("CACYC"), 1u) << "rate 0 data carries no cycle header";
}

TEST_F(FakeMicroModemTest, AThirdPartyPollMakesBSendToA) {
  host_a_.send(to_sentence(micromodem::Cycle{0, 2, 1, 1, true, 2}, Talker::kHost));
  answer_data_requests(host_b_, {"\x01\x02"}, true);
  run(20s);
  EXPECT_EQ(host_b_.count("CADRQ"), 2u);
  EXPECT_EQ(host_b_.count("CATXD"), 2u);
  auto heard = host_a_.addresses();
  // The poller: echo, its mini-packet, then the PSK packet with its header.
  ASSERT_GE(heard.size(), 9u);
  EXPECT_EQ(std::vector<std::string>(heard.begin(), heard.begin() + 9),
            (std::vector<std::string>{"CACYC", "CATXP", "CATXF", "CARXP", "CACYC", "CARXD",
                                      "CARXD", "CACST", "CATXP"}));
  auto first = micromodem::parse_received_data(*&host_a_.lines()[5].sentence).value();
  EXPECT_EQ(first.data, "\x01\x02");
  // The blank second frame asked for an ACK too and is acknowledged like
  // the spec's (§5.3, §8.2 step 9): drivers ignore it (§10 quirk 9).
  EXPECT_EQ(host_b_.count("CAACK"), 2u);
}

TEST_F(FakeMicroModemTest, AnUnansweredDataRequestTimesOutWithNothingSent) {
  host_a_.send(to_sentence(micromodem::ConfigParameter{"XST", "1"}, Talker::kHost));
  run(1s);  // one command at a time, as a driver must (§2.4)
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, true, 1}, Talker::kHost));
  run(10s);
  EXPECT_EQ(host_a_.addresses(), (std::vector<std::string>{"CACFG", "CACYC", "CADRQ", "CAERR", "CAXST"}));
  auto error = micromodem::parse_modem_error(host_a_.lines()[3].sentence).value();
  EXPECT_EQ(error.module, "DATA_TIMEOUT");
  EXPECT_EQ(error.number, "1");
  EXPECT_EQ(micromodem::parse_transmit_statistics(host_a_.lines()[4].sentence)->mode, 4);
  EXPECT_EQ(host_a_.lines()[3].at - host_a_.lines()[2].at, 2s) << "DTO";
  EXPECT_TRUE(host_b_.lines().empty());
}

TEST_F(FakeMicroModemTest, ALateFrameIsSentWithTheNextCycle) {
  host_a_.send(to_sentence(micromodem::TransmitData{1, 2, false, "stale"}));
  run(1s);
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, false, 1}, Talker::kHost));
  run(20s);
  EXPECT_EQ(host_a_.count("CADRQ"), 0u);
  EXPECT_EQ(micromodem::parse_received_data(host_b_.first("CARXD")->sentence)->data, "stale");
}

TEST_F(FakeMicroModemTest, ARebootIsReportedAndAbandonsTheCycle) {
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, true, 1}, Talker::kHost));
  run(500ms);
  ASSERT_EQ(host_a_.count("CADRQ"), 1u);
  a_.reboot();
  host_a_.send(to_sentence(micromodem::TransmitData{1, 2, true, "late"}));
  run(20s);
  EXPECT_EQ(host_a_.count("CATXP"), 0u) << "the abandoned cycle never transmits";
  const HeardLine* rev = host_a_.first("CAREV");
  ASSERT_TRUE(rev);
  EXPECT_EQ(rev->sentence.field(2), "INIT");
  EXPECT_TRUE(host_b_.lines().empty());
}

TEST_F(FakeMicroModemTest, BroadcastsAreHeardButNeverAcknowledged) {
  host_b_.send(to_sentence(micromodem::Cycle{0, 2, 0, 1, false, 1}, Talker::kHost));
  answer_data_requests(host_b_, {"\xCA\xFE"}, true);
  run(20s);
  EXPECT_EQ(micromodem::parse_received_data(host_a_.first("CARXD")->sentence).value(),
            (micromodem::ReceivedData{2, 0, true, 1, "\xCA\xFE"}));
  EXPECT_EQ(host_a_.count("CATXP"), 0u);
  EXPECT_EQ(host_b_.count("CAACK"), 0u);
}

TEST_F(FakeMicroModemTest, APollThatIsNeverAnsweredEndsInPacketTimeout) {
  b_.faults().set_silent(true);
  host_a_.send(to_sentence(micromodem::Cycle{0, 2, 1, 1, true, 1}, Talker::kHost));
  run(15s);
  const HeardLine* timeout = host_a_.first("CAMSG");
  ASSERT_TRUE(timeout);
  EXPECT_TRUE(micromodem::parse_transaction_message(timeout->sentence)->is_packet_timeout());
  EXPECT_EQ(micromodem::parse_receive_statistics(host_a_.first("CACST")->sentence)->mode, 2);
}

TEST_F(FakeMicroModemTest, OverlappingArrivalsAreDamagedAndHalfDuplexLosesThem) {
  FakeMicroModem c(water_, config(3, Generation::kMM2, {0, 1500, 0}));
  FakeModemHost host_c(c, scheduler_.clock());
  c.power_on();
  run(2s);
  // A and C both send to B at once: B hears a damaged packet.
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, true, 1}, Talker::kHost));
  host_c.send(to_sentence(micromodem::Cycle{0, 3, 2, 1, true, 1}, Talker::kHost));
  run(500ms);
  for (FakeModemHost* host : {&host_a_, &host_c}) {
    ASSERT_EQ(host->count("CADRQ"), 1u);
    auto drq = micromodem::parse_data_request(host->first("CADRQ")->sentence).value();
    host->send(to_sentence(micromodem::TransmitData{drq.source, 2, true, "x"}));
  }
  run(20s);
  ASSERT_EQ(host_a_.count("CATXP"), 1u);
  ASSERT_EQ(host_c.count("CATXP"), 1u);
  EXPECT_EQ(host_a_.first("CATXP")->at, host_c.first("CATXP")->at) << "both sounds reach B together";
  EXPECT_EQ(host_b_.count("CARXD"), 0u);
  EXPECT_EQ(host_b_.count("CAMSG"), 1u);
  EXPECT_EQ(micromodem::parse_receive_statistics(host_b_.first("CACST")->sentence)->bad_frames, 1);
  EXPECT_EQ(b_.counters().collisions, 1u);
  EXPECT_EQ(host_a_.count("CAACK") + host_c.count("CAACK"), 0u);
}

TEST_F(FakeMicroModemTest, OutputFaultsReachTheHostAsTheDriverWouldSeeThem) {
  a_.faults().corrupt_checksums(1);
  host_a_.send(to_sentence(micromodem::ConfigQuery{"SRC"}));
  run(1s);
  a_.faults().truncate_lines(1);
  host_a_.send(to_sentence(micromodem::ConfigQuery{"XST"}));
  run(1s);
  a_.write_raw(a_.faults().noise_burst(64));
  a_.write_raw(FaultInjector::overlong_line(9000));
  a_.write_raw(FaultInjector::unknown_sentence());
  a_.report_error("NMEA", "9", "injected");
  run(1s);
  ASSERT_GE(host_a_.refused().size(), 1u);
  EXPECT_EQ(host_a_.refused()[0].kind, micromodem::ErrorKind::kBadChecksum);
  // The truncated line lost its checksum; the unknown sentence and the
  // injected error are well formed.
  bool truncated = false;
  for (const auto& error : host_a_.refused()) truncated |= error.kind == micromodem::ErrorKind::kMissingChecksum;
  EXPECT_TRUE(truncated);
  EXPECT_TRUE(host_a_.first("CAZZZ"));
  EXPECT_TRUE(host_a_.first("CAERR"));
}

TEST_F(FakeMicroModemTest, Mm2StatisticsUseTheVersion8And7Layouts) {
  host_a_.send(to_sentence(micromodem::ConfigParameter{"XST", "1"}, Talker::kHost));
  run(1s);
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, false, 1}, Talker::kHost));
  answer_data_requests(host_a_, {"y"}, false);
  run(20s);
  auto cst = micromodem::parse_receive_statistics(host_b_.first("CACST")->sentence).value();
  EXPECT_EQ(cst.version, 8);
  EXPECT_EQ(cst.field_count, 34u);
  EXPECT_EQ(cst.source, 1);
  EXPECT_GT(cst.snr_in, 0);
  EXPECT_EQ(micromodem::parse_transmit_statistics(host_a_.first("CAXST")->sentence)->field_count, 17u);
}

TEST_F(FakeMicroModemTest, RevisionIsPrintedPeriodicallyOnlyWhileRevIsOn) {
  run(60s);
  EXPECT_EQ(host_a_.count("CAREV"), 2u) << "AUV and COPROC, once a minute";
  host_a_.send(to_sentence(micromodem::ConfigParameter{"REV", "0"}, Talker::kHost));
  run(1s);
  host_a_.clear();
  run(120s);
  EXPECT_EQ(host_a_.count("CAREV"), 0u);
}

TEST_F(FakeMicroModemTest, BadFramesArePrintedAsBadCrcInFrameOrder) {
  FakeModemConfig noisy = config(3, Generation::kMM2, {0, 1500, 0});
  noisy.frame_error_probability = 1;
  FakeMicroModem c(water_, noisy);
  FakeModemHost host_c(c, scheduler_.clock());
  c.power_on();
  run(2s);
  host_c.clear();
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 3, 2, true, 2}, Talker::kHost));
  answer_data_requests(host_a_, {"one", "two"}, true);
  run(20s);
  EXPECT_EQ(host_c.addresses(), (std::vector<std::string>{"CARXP", "CACYC", "CAMSG", "CAMSG", "CACST"}));
  auto cst = micromodem::parse_receive_statistics(host_c.first("CACST")->sentence).value();
  EXPECT_EQ(cst.mode, 1);
  EXPECT_EQ(cst.bad_frames, 2);
  EXPECT_EQ(cst.psk_error, 3);
  EXPECT_EQ(host_a_.count("CAACK"), 0u) << "nothing good, nothing acknowledged";
  EXPECT_EQ(host_b_.count("CARXD"), 2u) << "B overhears the packet meant for C";
}

class FakeMm1Test : public FakeMicroModemTest {
 protected:
  FakeMm1Test() : FakeMicroModemTest(Generation::kMM1) {}
};

TEST_F(FakeMm1Test, Mm1PrintsVersion6StatisticsAndOneRevisionLine) {
  a_.reboot();
  run(2s);
  EXPECT_EQ(host_a_.addresses(), (std::vector<std::string>{"CAREV", "CAREV"}));
  EXPECT_EQ(micromodem::modem_generation(host_a_.lines()[1].sentence.field(3)).value(),
            micromodem::ModemGeneration::kMM1);
  host_a_.clear();
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, false, 1}, Talker::kHost));
  answer_data_requests(host_a_, {"y"}, false);
  run(20s);
  auto cst = micromodem::parse_receive_statistics(host_b_.first("CACST")->sentence).value();
  EXPECT_EQ(cst.version, 6);
  EXPECT_EQ(cst.field_count, 30u);
  host_a_.send(Sentence{"CC", "TMQ", {"0"}});
  run(1s);
  EXPECT_TRUE(host_a_.first("CAERR")) << "MM1 does not know $CCTMQ";
}

TEST_F(FakeMm1Test, TheThirdPartyAckBugReportsOtherModemsAcksAsOurs) {
  FakeModemConfig buggy = config(3, Generation::kMM1, {0, 1500, 0});
  buggy.third_party_ack_bug = true;
  FakeMicroModem c(water_, buggy);
  FakeModemHost host_c(c, scheduler_.clock());
  c.power_on();
  run(2s);
  host_a_.send(to_sentence(micromodem::Cycle{0, 1, 2, 1, true, 1}, Talker::kHost));
  answer_data_requests(host_a_, {"z"}, true);
  run(20s);
  ASSERT_EQ(host_a_.count("CAACK"), 1u);
  ASSERT_EQ(host_c.count("CAACK"), 1u);
  EXPECT_EQ(micromodem::parse_acknowledgement(host_c.first("CAACK")->sentence).value(),
            (micromodem::Acknowledgement{2, 3, 1})) << "B's ACK to A, reported with DEST = C";
}

TEST(WaterDatagramTest, RoundTripsAndRefusesGarbage) {
  WaterDatagram d{{1.5, -2, 3}, 3.4, {PacketKind::kData, 2, 1, 2, true, 3, {{true, "ab"}, {false, ""}}, {}}};
  std::string error;
  auto back = decode_datagram(encode(d), &error);
  ASSERT_TRUE(back) << error;
  EXPECT_EQ(back->from.x, 1.5);
  EXPECT_EQ(back->air_seconds, 3.4);
  EXPECT_EQ(back->packet.frames.size(), 2u);
  EXPECT_EQ(back->packet.frames[0].bytes, "ab");
  EXPECT_FALSE(back->packet.frames[1].ack);
  WaterDatagram ack{{}, 0.7, {PacketKind::kAck, 1, 2, 1, false, 0, {}, {1, 3}}};
  EXPECT_EQ(decode_datagram(encode(ack), &error)->packet.acked_frames, (std::vector<int>{1, 3}));
  EXPECT_FALSE(decode_datagram("FAKEMM1 1 2", &error));
  EXPECT_FALSE(decode_datagram("hello", &error));
  EXPECT_FALSE(decode_datagram("FAKEMM1 0 0 0 100 1 9 1 2 0 1 -", &error)) << "rate 9";
  EXPECT_FALSE(decode_datagram("FAKEMM1 0 0 0 100 1 1 1 2 0 1 - 1:ABC", &error)) << "odd hex";
}

}  // namespace
}  // namespace acomms::fake_micromodem
