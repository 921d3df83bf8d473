// The consistency digest (node/consistency_digest.h): it changes with what
// nodes must agree on (a type's field, an id, a type more, the MAC cycle)
// and not with what is the node's own (data_dir, modem id, queues, driver,
// link name and cost, range guard, comments, file names, declaration
// order).

#include "node/consistency_digest.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/config_loader.h"
#include "node/codec_setup.h"
#include "temp_dir.h"

namespace acomms::node {
namespace {

// A DCCL file of two types; each test changes one thing in it.
struct Proto {
  std::string status_id = "20";
  std::string src_max = "31";
  std::string comment = "// Where it is.";
  bool fields_swapped = false;  // y declared before x (numbers unchanged)
  bool extra_type = false;
  std::string mode_last = "HOLDING = 2;";

  std::string text() const {
    std::string x = "  required int32 x = 3 [(dccl.field) = { min: -1000 max: 1000 }];\n";
    std::string y = "  required int32 y = 4 [(dccl.field) = { min: -1000 max: 1000 }];\n";
    return "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage fleet;\n" + comment +
           "\nmessage Status {\n  option (dccl.msg) = { codec_version: 4 id: " + status_id +
           " max_bytes: 32 };\n  required int32 src = 1 [(dccl.field) = { min: 0 max: " + src_max + " }];\n" +
           "  required int32 dest = 2 [(dccl.field) = { min: 0 max: 31 }];\n" + (fields_swapped ? y + x : x + y) +
           "  enum Mode { IDLE = 0; SURVEY = 1; " + mode_last + " }\n  optional Mode mode = 5;\n}\n" +
           "message Command {\n  option (dccl.msg) = { codec_version: 4 id: 21 max_bytes: 32 };\n" +
           "  required int32 dest = 1 [(dccl.field) = { min: 0 max: 31 }];\n}\n" +
           (extra_type ? "message Extra {\n  option (dccl.msg) = { codec_version: 4 id: 22 max_bytes: 8 };\n"
                         "  required int32 a = 1 [(dccl.field) = { min: 0 max: 3 }];\n}\n"
                       : "");
  }
};

const char* kFixedMac = "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 3 } slot { src: 2 rate: 5 seconds: 3 } }";

class ConsistencyDigest : public ::testing::Test {
 protected:
  // The digest of a node whose config is `rest` plus a dccl block for
  // `proto`, written under `file`.
  uint32_t digest(const Proto& proto, const std::string& rest = kFixedMac, const std::string& file = "fleet.proto") {
    const auto path = dir_ / file;
    std::ofstream(path) << proto.text();
    v1::Config config =
        core::parse_config("dccl { proto_files: \"" + path.string() + "\" }\n" + rest, "test.conf");
    auto codec = make_codec(config.dccl());
    auto digests = config_digests(config, *codec);
    EXPECT_EQ(digests.size(), 1u);
    return digests.empty() ? 0 : digests.front().second;
  }

  testing::TempDir dir_;
};

TEST_F(ConsistencyDigest, IsTheSameForTheSameDefinitionsAndCycle) {
  EXPECT_EQ(digest(Proto{}), digest(Proto{}, kFixedMac, "again.proto"));
}

TEST_F(ConsistencyDigest, ChangesWhenAFieldOfATypeChanges) {
  Proto changed;
  changed.src_max = "63";
  EXPECT_NE(digest(Proto{}), digest(changed, kFixedMac, "changed.proto"));
}

TEST_F(ConsistencyDigest, ChangesWhenAnEnumOfATypeChanges) {
  Proto changed;
  changed.mode_last = "HOLDING = 2; FAULT = 3;";
  EXPECT_NE(digest(Proto{}), digest(changed, kFixedMac, "changed.proto"));
}

TEST_F(ConsistencyDigest, ChangesWhenAnIdChanges) {
  Proto changed;
  changed.status_id = "23";
  EXPECT_NE(digest(Proto{}), digest(changed, kFixedMac, "changed.proto"));
}

TEST_F(ConsistencyDigest, ChangesWhenATypeIsAdded) {
  Proto changed;
  changed.extra_type = true;
  EXPECT_NE(digest(Proto{}), digest(changed, kFixedMac, "changed.proto"));
}

TEST_F(ConsistencyDigest, ChangesWhenTheMacCycleChanges) {
  const uint32_t base = digest(Proto{});
  EXPECT_NE(base, digest(Proto{}, "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 4 } slot { src: 2 rate: 5 "
                                  "seconds: 3 } }"));
  EXPECT_NE(base, digest(Proto{}, "mac { name: \"fixed\" slot { src: 1 rate: 1 seconds: 3 } slot { src: 2 rate: 5 "
                                  "seconds: 3 } }"));
  EXPECT_NE(base, digest(Proto{}, "mac { name: \"fixed\" slot { src: 2 rate: 5 seconds: 3 } slot { src: 1 rate: 5 "
                                  "seconds: 3 } }"));
  EXPECT_NE(base, digest(Proto{}, std::string(kFixedMac).insert(std::string(kFixedMac).size() - 1, " epoch: 100 ")));
  EXPECT_NE(base, digest(Proto{}, "mac { name: \"auto_discovery\" slot_seconds: 3 rate: 5 coolness: 2 "
                                  "expire_cycles: 3 }"));
}

TEST_F(ConsistencyDigest, ChangesWhenAnAutoDiscoverySettingChanges) {
  const std::string mac = "mac { name: \"auto_discovery\" slot_seconds: 3 rate: 5 coolness: 2 expire_cycles: 3 ";
  const uint32_t base = digest(Proto{}, mac + "}");
  EXPECT_EQ(base, digest(Proto{}, mac + "blank_rule: \"anywhere\" }"));  // the default, spelled out
  EXPECT_NE(base, digest(Proto{}, mac + "blank_rule: \"figure\" }"));
  EXPECT_NE(base, digest(Proto{}, "mac { name: \"auto_discovery\" slot_seconds: 3 rate: 5 coolness: 3 "
                                  "expire_cycles: 3 }"));
}

TEST_F(ConsistencyDigest, DoesNotChangeWithNodeLocalSettings) {
  const uint32_t base = digest(Proto{});
  const std::string local = std::string("data_dir: \"/elsewhere\" log_level: DEBUG\n") +
                            "driver { name: \"sim\" modem_id: 7 sim { position { x: 300 } } }\n" +
                            "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: 3 } slot { src: 2 rate: 5 "
                            "seconds: 3 } max_range_m: 400 }\n" +
                            "queue { type { type: \"fleet.Status\" policy { ttl_s: 60 value_base: 3 } } }\n" +
                            "consistency { announce_interval_s: 30 }\n";
  EXPECT_EQ(base, digest(Proto{}, local));
  // A link block (named, with a cost) instead of the top-level driver/mac.
  EXPECT_EQ(base, digest(Proto{}, "link { name: \"acoustic\" cost: 0.5 driver { name: \"sim\" } mac { name: "
                                  "\"fixed\" slot { src: 1 rate: 5 seconds: 3 } slot { src: 2 rate: 5 seconds: 3 "
                                  "} } }"));
}

TEST_F(ConsistencyDigest, DoesNotChangeWithCommentsFileNamesOrDeclarationOrder) {
  const uint32_t base = digest(Proto{});
  Proto commented;
  commented.comment = "// Where it is, and a longer comment about it.";
  EXPECT_EQ(base, digest(commented, kFixedMac, "commented.proto"));
  Proto swapped;
  swapped.fields_swapped = true;
  EXPECT_EQ(base, digest(swapped, kFixedMac, "swapped.proto"));
}

// A polled cycle is the master's alone: the nodes it polls (MAC "none")
// agree with it.
TEST_F(ConsistencyDigest, APolledMasterAndTheNodesItPollsAgree) {
  EXPECT_EQ(digest(Proto{}, "mac { name: \"polled\" slot { src: 1 rate: 1 seconds: 3 } slot { src: 2 dest: 1 "
                            "rate: 1 seconds: 3 } }"),
            digest(Proto{}, "mac { name: \"none\" }"));
}

TEST_F(ConsistencyDigest, ACycleSetAtRunTimeIsWhatCounts) {
  v1::MacConfig config;
  config.set_name("fixed");
  mac::Cycle cycle{{.src = 1, .rate = 5, .seconds = 3}, {.src = 2, .rate = 5, .seconds = 3}};
  const std::string before = canonical_mac(config, cycle);
  cycle[1].seconds = 5;
  EXPECT_NE(consistency_digest("", before), consistency_digest("", canonical_mac(config, cycle)));
}

// The framing is part of the wire contract between releases: checked
// against sha256sum of the documented head ("acomms consistency v1\n
// definitions N\nmac M\n", then both texts).
TEST(ConsistencyDigestFormat, IsTheFirst32BitsOfTheSha256OfTheDocumentedFraming) {
  EXPECT_EQ(digest_hex(consistency_digest("", "")), "ba557320");
  EXPECT_EQ(digest_hex(consistency_digest("", "master-driven\n")), "d51742c8");
}

TEST(ConsistencyDigestFormat, HexRoundTripsAndRefusesWhatIsNotEightHexDigits) {
  EXPECT_EQ(digest_hex(0x0012abcd), "0012abcd");
  EXPECT_EQ(parse_digest("0012ABcd"), std::optional<uint32_t>(0x0012abcd));
  EXPECT_EQ(parse_digest("12abcd"), std::nullopt);
  EXPECT_EQ(parse_digest("0012abcdx"), std::nullopt);
  EXPECT_EQ(parse_digest("0012abcg"), std::nullopt);
  EXPECT_EQ(parse_digest(""), std::nullopt);
}

}  // namespace
}  // namespace acomms::node
