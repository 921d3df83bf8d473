// Consistency checked at sea (README "Consistency across a fleet"): two
// real acommsd processes on the loopback sim channel announce their
// consistency digests; started from different message definitions, each
// sees the other's disagreement in `status` (GetStatus) and `link status`
// within a few MAC cycles, logs it once and counts it; started from the
// same ones, they agree and no frame is counted malformed.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>

#include "daemon_harness.h"
#include "sim_network.h"

namespace acomms::testing {
namespace {

using namespace std::chrono_literals;

constexpr double kSlotSeconds = 3;
constexpr double kCycleSeconds = 2 * kSlotSeconds;
// Short, so that a test sees a second announce within a cycle or two (the
// default is 600 s).
const std::string kConsistency = "consistency { enabled: true announce_interval_s: 2 }\n";

class ConsistencyAtSea : public ::testing::Test {
 protected:
  void TearDown() override { net_.stop(); }

  // Node 2 loads examples/messages.proto as is (`same`), or a copy in which
  // example.Status's src field is wider (max 63 instead of 31): one bound of
  // one field differs.
  void start(bool same) {
    std::string rest2 = kConsistency;
    if (!same) {
      std::ifstream in(ACOMMS_SOURCE_DIR "/examples/messages.proto");
      std::stringstream text;
      text << in.rdbuf();
      const std::string original = text.str();
      const std::string changed = std::regex_replace(original, std::regex("src = 1 \\[\\(dccl.field\\) = \\{ min: 0 max: 31"),
                                                     "src = 1 [(dccl.field) = { min: 0 max: 63", std::regex_constants::format_first_only);
      ASSERT_NE(changed, original);
      std::ofstream(net_.dir() / "messages-v2.proto") << changed;
      rest2 += "dccl { proto_files: \"" + (net_.dir() / "messages-v2.proto").string() + "\" }\n";
    }
    net_.write_config(1, {.sim = "position { x: 300 }", .rest = kConsistency});
    net_.write_config(2, {.sim = "position { x: 0 }", .rest = rest2, .example_messages = same});
    started_ = std::chrono::steady_clock::now();
    net_.start(1);
    net_.start(2);
  }

  v1::Status status(int id) {
    grpc::ClientContext context;
    v1::Status response;
    EXPECT_TRUE(api(net_.socket(id))->GetStatus(&context, v1::GetStatusRequest(), &response).ok());
    return response;
  }

  v1::LinkStatusResponse link_status(int id) {
    grpc::ClientContext context;
    v1::LinkStatusResponse response;
    EXPECT_TRUE(api(net_.socket(id))->LinkStatus(&context, v1::LinkStatusRequest(), &response).ok());
    return response;
  }

  // What node `id` has heard node `other` announce (empty digest: nothing).
  v1::NodeConsistency heard(int id, int other) {
    const v1::Status now = status(id);  // kept: the loop reads into it
    for (const v1::NodeConsistency& node : now.consistency()) {
      if (node.node() == other) return node;
    }
    return {};
  }

  double seconds_since_start() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  }

  SimNetwork net_{"consistency", kSlotSeconds};
  std::chrono::steady_clock::time_point started_;
};

TEST_F(ConsistencyAtSea, NodesFromDifferentDefinitionsSeeEachOthersDisagreementWithinAFewCycles) {
  start(false);
  // Each node's first transmission carries its announce: one cycle, plus
  // the start of the second daemon. Three cycles is the bound.
  ASSERT_TRUE(wait_until([&] { return !heard(1, 2).digest().empty() && !heard(2, 1).digest().empty(); },
                         std::chrono::milliseconds(static_cast<int>(3 * kCycleSeconds * 1000)), 100ms))
      << "node 1 heard: " << heard(1, 2).DebugString() << "node 2 heard: " << heard(2, 1).DebugString()
      << net_.daemon(1).stderr_text();
  std::printf("both disagreements seen %.1f s after the first daemon's start\n", seconds_since_start());
  const v1::Status one = status(1);
  const v1::Status two = status(2);
  ASSERT_EQ(one.consistency_digest().size(), 8u);
  EXPECT_NE(one.consistency_digest(), two.consistency_digest());
  for (auto [id, other, other_status] : {std::tuple(1, 2, two), std::tuple(2, 1, one)}) {
    const v1::NodeConsistency node = heard(id, other);
    EXPECT_EQ(node.digest(), other_status.consistency_digest()) << id;
    EXPECT_FALSE(node.agrees()) << id;
    EXPECT_GT(node.disagrees_since(), 0) << id;
    EXPECT_EQ(node.link(), "default");
    EXPECT_GE(status(id).unexpected_digests(), 1u) << id;
    // link status: the same, on the link it was heard on.
    const v1::LinkStatusResponse link = link_status(id);
    EXPECT_EQ(link.consistency_digest(), status(id).consistency_digest());
    ASSERT_EQ(link.consistency_size(), 1) << id;
    EXPECT_EQ(link.consistency(0).node(), other);
    EXPECT_FALSE(link.consistency(0).agrees());
  }
  // A second announce from node 2 is counted, not logged again.
  ASSERT_TRUE(wait_until([&] { return heard(1, 2).announces() >= 2; },
                         std::chrono::milliseconds(static_cast<int>(3 * kCycleSeconds * 1000)), 100ms));
  EXPECT_GE(status(1).unexpected_digests(), 2u);
  const std::string log = net_.daemon(1).stderr_text();
  const std::string line = "node 2 on link default announces digest " + two.consistency_digest();
  const size_t first = log.find(line);
  EXPECT_NE(first, std::string::npos) << log;
  EXPECT_EQ(log.find(line, first + 1), std::string::npos) << log;
  std::printf("test wall time %.1f s\n", seconds_since_start());
}

TEST_F(ConsistencyAtSea, NodesFromTheSameDefinitionsAgree) {
  start(true);
  ASSERT_TRUE(wait_until([&] { return !heard(1, 2).digest().empty() && !heard(2, 1).digest().empty(); },
                         std::chrono::milliseconds(static_cast<int>(3 * kCycleSeconds * 1000)), 100ms));
  const v1::Status one = status(1);
  const v1::Status two = status(2);
  EXPECT_EQ(one.consistency_digest(), two.consistency_digest());
  EXPECT_TRUE(heard(1, 2).agrees());
  EXPECT_TRUE(heard(2, 1).agrees());
  EXPECT_EQ(heard(1, 2).disagrees_since(), 0);
  EXPECT_EQ(one.unexpected_digests(), 0u);
  EXPECT_EQ(two.unexpected_digests(), 0u);
  // The announce decoded where it was heard: no frame counted as malformed.
  EXPECT_EQ(link_status(1).counters().malformed_frames(), 0u);
  EXPECT_EQ(link_status(2).counters().malformed_frames(), 0u);
  // What `acommsd --print-digest` prints for a node's config (all of its
  // stdout, to paste into a fleet file) is what the running node reports.
  RunResult printed = run(ACOMMSD_BINARY, {"--config", (net_.dir() / "vehicle.conf").string(), "--print-digest"},
                          (net_.dir() / "print-digest").string());
  EXPECT_EQ(printed.exit_code, 0) << printed.err;
  EXPECT_EQ(printed.out, one.consistency_digest() + "\n") << printed.err;
  std::printf("test wall time %.1f s\n", seconds_since_start());
}

}  // namespace
}  // namespace acomms::testing
