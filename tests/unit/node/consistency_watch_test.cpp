// Consistency checked at sea (node/consistency_watch.h): when this node's
// announce goes, what a heard digest is judged against, what is kept per
// node, what is logged (once per node and digest) and counted.

#include "node/consistency_watch.h"

#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/config_loader.h"
#include "node/codec_setup.h"
#include "node/consistency_announce.h"
#include "node/consistency_digest.h"
#include "temp_dir.h"

namespace acomms::node {
namespace {

// A MAC that only holds a cycle (the watch reads nothing else).
class CycleOnlyMac final : public mac::Mac {
 public:
  void start(Transmit) override {}
  void stop() override {}
  void set_cycle(const mac::Cycle& cycle) override { cycle_ = cycle; }
  const mac::Cycle& cycle() const override { return cycle_; }
  void on_receive(const v1::ModemTransmission&) override {}

 private:
  mac::Cycle cycle_{{.src = 1, .rate = 5, .seconds = 3}, {.src = 2, .rate = 5, .seconds = 3}};
};

// Captures what spdlog logs while it lives.
class LogCapture {
 public:
  LogCapture() : previous_(spdlog::default_logger()) {
    spdlog::set_default_logger(
        std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log_)));
  }
  ~LogCapture() { spdlog::set_default_logger(previous_); }
  std::string text() const { return log_.str(); }
  size_t count(const std::string& needle) const {
    size_t n = 0;
    const std::string all = text();
    for (size_t at = all.find(needle); at != std::string::npos; at = all.find(needle, at + 1)) ++n;
    return n;
  }

 private:
  std::ostringstream log_;
  std::shared_ptr<spdlog::logger> previous_;
};

class ConsistencyWatchTest : public ::testing::Test {
 protected:
  ConsistencyWatchTest()
      : codec_(make_codec(core::parse_config("dccl { proto_files: \"" ACOMMS_SOURCE_DIR "/examples/messages.proto\" }",
                                             "test.conf")
                              .dccl())) {
    mac_config_.set_name("fixed");
  }

  std::unique_ptr<ConsistencyWatch> watch(const std::string& consistency) {
    v1::ConsistencyConfig config =
        core::parse_config("consistency { enabled: true " + consistency + " }", "test.conf").consistency();
    return std::make_unique<ConsistencyWatch>(config, *codec_,
                                              std::vector<ConsistencyWatch::Link>{{"acoustic", &mac_config_, &mac_}});
  }

  std::unique_ptr<dccl::Codec> codec_;
  v1::MacConfig mac_config_;
  CycleOnlyMac mac_;
};

TEST_F(ConsistencyWatchTest, AnnouncesAtTheFirstChanceThenOncePerInterval) {
  auto w = watch("announce_interval_s: 600");
  const std::string first = w->take(0, 32, 1000);
  EXPECT_EQ(first, encode_announce(w->own_digest(0), kDefaultAnnounceId));
  EXPECT_EQ(w->take(0, 32, 1001), "");
  EXPECT_EQ(w->take(0, 32, 1599), "");
  EXPECT_EQ(w->take(0, 32, 1600), first);
}

TEST_F(ConsistencyWatchTest, WaitsForRoomAndIsNeverSentDisabled) {
  auto w = watch("");
  EXPECT_EQ(w->take(0, kAnnounceBytes - 1, 1000), "");  // no room: still due
  EXPECT_EQ(w->take(0, kAnnounceBytes, 1001).size(), kAnnounceBytes);
  auto off = std::make_unique<ConsistencyWatch>(v1::ConsistencyConfig(), *codec_,
                                                std::vector<ConsistencyWatch::Link>{{"acoustic", &mac_config_, &mac_}});
  EXPECT_EQ(off->take(0, 32, 1000), "");
}

TEST_F(ConsistencyWatchTest, ANeighbourWithTheSameDigestAgrees) {
  auto w = watch("");
  EXPECT_EQ(w->on_received(encode_announce(w->own_digest(0), kDefaultAnnounceId), 2, 0, 1000), kAnnounceBytes);
  const HeardDigest& heard = w->heard().at({0, 2});
  EXPECT_TRUE(heard.agrees);
  EXPECT_EQ(heard.disagrees_since, 0);
  EXPECT_EQ(heard.last_heard, 1000);
  EXPECT_EQ(w->unexpected(), 0u);
}

TEST_F(ConsistencyWatchTest, ADifferentDigestIsLoggedOncePerNodeAndDigestAndCountedEachTime) {
  LogCapture log;
  auto w = watch("");
  const uint32_t other = w->own_digest(0) ^ 1;
  for (double t : {1000.0, 1600.0, 2200.0}) w->on_received(encode_announce(other, kDefaultAnnounceId), 2, 0, t);
  const HeardDigest& heard = w->heard().at({0, 2});
  EXPECT_FALSE(heard.agrees);
  EXPECT_EQ(heard.disagrees_since, 1000);  // since the first, not the last
  EXPECT_EQ(heard.last_heard, 2200);
  EXPECT_EQ(heard.announces, 3u);
  EXPECT_EQ(w->unexpected(), 3u);
  EXPECT_EQ(log.count("node 2 on link acoustic announces digest " + digest_hex(other)), 1u) << log.text();
  // Another digest from it, and the same from another node: logged too.
  w->on_received(encode_announce(other ^ 2, kDefaultAnnounceId), 2, 0, 2800);
  w->on_received(encode_announce(other, kDefaultAnnounceId), 3, 0, 2800);
  EXPECT_EQ(log.count("announces digest"), 3u) << log.text();
}

TEST_F(ConsistencyWatchTest, AgreeingAgainEndsTheDisagreement) {
  auto w = watch("");
  w->on_received(encode_announce(w->own_digest(0) ^ 1, kDefaultAnnounceId), 2, 0, 1000);
  w->on_received(encode_announce(w->own_digest(0), kDefaultAnnounceId), 2, 0, 1600);
  EXPECT_TRUE(w->heard().at({0, 2}).agrees);
  EXPECT_EQ(w->heard().at({0, 2}).disagrees_since, 0);
}

TEST_F(ConsistencyWatchTest, TheFleetsExpectedDigestIsWhatAgrees) {
  auto w = watch("expected_digest: \"0badcafe\"");
  w->on_received(encode_announce(0x0badcafe, kDefaultAnnounceId), 2, 0, 1000);
  w->on_received(encode_announce(w->own_digest(0), kDefaultAnnounceId), 3, 0, 1000);
  EXPECT_TRUE(w->heard().at({0, 2}).agrees);
  EXPECT_FALSE(w->heard().at({0, 3}).agrees);
}

TEST_F(ConsistencyWatchTest, ACycleSetAtRunTimeChangesTheOwnDigest) {
  auto w = watch("");
  const uint32_t before = w->own_digest(0);
  mac_.set_cycle({{.src = 1, .rate = 5, .seconds = 4}});
  EXPECT_NE(w->own_digest(0), before);
}

TEST_F(ConsistencyWatchTest, AMalformedAnnounceIsCountedAndUsesNoBytes) {
  LogCapture log;
  auto w = watch("");
  EXPECT_EQ(w->on_received(encode_announce(1, kDefaultAnnounceId).substr(0, 4), 2, 0, 1000), 0u);
  EXPECT_EQ(w->malformed(), 1u);
  EXPECT_TRUE(w->heard().empty());
  EXPECT_NE(log.text().find("bad announce from node 2: announce truncated"), std::string::npos) << log.text();
}

TEST_F(ConsistencyWatchTest, DisabledReadsPastAnAnnounceWithoutRecordingIt) {
  auto w = std::make_unique<ConsistencyWatch>(v1::ConsistencyConfig(), *codec_,
                                              std::vector<ConsistencyWatch::Link>{{"acoustic", &mac_config_, &mac_}});
  EXPECT_EQ(w->on_received(encode_announce(1, kDefaultAnnounceId), 2, 0, 1000), kAnnounceBytes);
  EXPECT_TRUE(w->heard().empty());
}

TEST_F(ConsistencyWatchTest, StatusShowsTheOwnDigestAndEachNodeHeard) {
  auto w = watch("");
  w->on_received(encode_announce(0x0badcafe, kDefaultAnnounceId), 2, 0, 1000);
  v1::Status status;
  w->fill(&status);
  EXPECT_EQ(status.consistency_digest(), digest_hex(w->own_digest(0)));
  ASSERT_EQ(status.consistency_size(), 1);
  EXPECT_EQ(status.consistency(0).node(), 2);
  EXPECT_EQ(status.consistency(0).link(), "acoustic");
  EXPECT_EQ(status.consistency(0).digest(), "0badcafe");
  EXPECT_FALSE(status.consistency(0).agrees());
  EXPECT_EQ(status.consistency(0).disagrees_since(), 1000);
  EXPECT_EQ(status.unexpected_digests(), 1u);
  v1::LinkStatusResponse link;
  w->fill_link(0, &link);
  EXPECT_EQ(link.consistency_digest(), status.consistency_digest());
  ASSERT_EQ(link.consistency_size(), 1);
  EXPECT_EQ(link.consistency(0).digest(), "0badcafe");
}

// As the routing envelope's id is: with consistency enabled, a loaded type
// with the announce's id would be read as an announce, so the start stops
// and says which type; disabled, nothing is taken.
TEST_F(ConsistencyWatchTest, RefusesAnAnnounceIdALoadedTypeUses) {
  testing::TempDir dir;
  std::ofstream(dir / "taken.proto")
      << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage taken;\n"
         "message Big {\n  option (dccl.msg) = { codec_version: 4 id: 32766 max_bytes: 8 };\n"
         "  required int32 a = 1 [(dccl.field) = { min: 0 max: 3 }];\n}\n";
  codec_ = make_codec(
      core::parse_config("dccl { proto_files: \"" + (dir / "taken.proto").string() + "\" }", "test.conf").dccl());
  try {
    watch("");
    ADD_FAILURE() << "the default announce_id 32766 accepted though taken.Big has it";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("consistency.announce_id 32766 is the DCCL id of taken.Big"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(watch("announce_id: 32765"));
  // Disabled, the id is an ordinary DCCL id: the config loads as before.
  EXPECT_NO_THROW(ConsistencyWatch(v1::ConsistencyConfig(), *codec_,
                                   std::vector<ConsistencyWatch::Link>{{"acoustic", &mac_config_, &mac_}}));
}

TEST_F(ConsistencyWatchTest, RefusesBadSettings) {
  EXPECT_THROW(watch("announce_id: 100"), std::invalid_argument);
  EXPECT_THROW(watch("announce_id: 32768"), std::invalid_argument);
  EXPECT_THROW(watch("announce_interval_s: 0.5"), std::invalid_argument);
  EXPECT_THROW(watch("expected_digest: \"xyz\""), std::invalid_argument);
}

}  // namespace
}  // namespace acomms::node
