// The fleet file's merge rules and provenance (daemon/core/fleet_merge.h,
// daemon/core/fleet.h): what a node gets from its levels, and the file and
// line each field came from.

#include <google/protobuf/descriptor.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "acomms/v1/config.pb.h"
#include "acomms/v1/fleet.pb.h"
#include "core/config_error.h"
#include "core/fleet.h"
#include "core/fleet_import.h"
#include "core/fleet_render.h"

namespace acomms::core {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

void collect_repeated(const pb::Descriptor* type, std::set<std::string>& seen, std::vector<const pb::FieldDescriptor*>& out) {
  if (!seen.insert(std::string(type->full_name())).second) return;
  for (int i = 0; i < type->field_count(); ++i) {
    const pb::FieldDescriptor* field = type->field(i);
    if (field->is_repeated()) out.push_back(field);
    if (field->message_type() != nullptr) collect_repeated(field->message_type(), seen, out);
  }
}

TEST(FleetMerge, EveryRepeatedFieldOfTheConfigHasARuleAndEveryKeyExists) {
  std::set<std::string> seen;
  std::vector<const pb::FieldDescriptor*> repeated;
  collect_repeated(v1::Config::descriptor(), seen, repeated);
  collect_repeated(v1::FleetKeys::descriptor(), seen, repeated);
  ASSERT_GT(repeated.size(), 20u);
  std::set<std::string> reachable;
  for (const pb::FieldDescriptor* field : repeated) {
    const std::string name(field->full_name());
    reachable.insert(name);
    auto rule = repeated_rules().find(name);
    EXPECT_NE(rule, repeated_rules().end()) << name << " has no merge rule in repeated_rules() (fleet_merge.cpp)";
    if (rule == repeated_rules().end() || rule->second.rule != RepeatedRule::kKeyed) continue;
    ASSERT_NE(field->message_type(), nullptr) << name << ": only a list of messages can be keyed";
    for (const std::string& key : rule->second.key_fields) {
      EXPECT_NE(field->message_type()->FindFieldByName(key), nullptr) << name << ": no key field " << key;
    }
  }
  for (const auto& [name, rule] : repeated_rules()) {
    EXPECT_TRUE(reachable.count(name)) << name << ": a rule for a field the config does not have";
  }
}

// Writes files into a fresh directory and loads one as a fleet.
class FleetFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-fleet-merge-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  fs::path dir_;
};

constexpr const char* kCruise =
    "node {\n"                                                     // 1
    "  name: \"cruise\"\n"                                         // 2
    "  abstract: true\n"                                           // 3
    "  config {\n"                                                 // 4
    "    mac { name: \"fixed\"\n"                                  // 5
    "      slot { src: 1 rate: 5 seconds: 3 }\n"                   // 6
    "      slot { src: 2 rate: 5 seconds: 3 }\n"                   // 7
    "      slot { src: 1 rate: 1 seconds: 10 } }\n"                // 8
    "    dccl { proto_files: \"a.proto\" }\n"                      // 9
    "    queue { type { type: \"x.A\" policy { ttl_s: 60 ack: true } } }\n"  // 10
    "    telemetry { receiver: 1 receiver: 2 }\n"                  // 11
    "    log_level: DEBUG\n"                                       // 12
    "  }\n"                                                        // 13
    "}\n";                                                         // 14

TEST_F(FleetFiles, ScalarsOverrideKeyedListsMergeByKeyAndEachFieldSaysWhereItCameFrom) {
  const std::string cruise = write("cruise.conf", kCruise);
  const std::string fleet = write("fleet.conf",
                                  "include: \"cruise.conf\"\n"                                      // 1
                                  "node {\n"                                                        // 2
                                  "  name: \"auv\"\n"                                               // 3
                                  "  parent: \"cruise\"\n"                                          // 4
                                  "  config {\n"                                                    // 5
                                  "    log_level: WARN\n"                                           // 6
                                  "    mac { slot { src: 1 seconds: 4 } slot { src: 1 seconds: 12 }\n"  // 7
                                  "          slot { src: 7 rate: 0 seconds: 2 } }\n"               // 8
                                  "    queue { type { type: \"x.A\" policy { ttl_s: 30 } }\n"       // 9
                                  "            type { type: \"x.B\" } }\n"                          // 10
                                  "    telemetry { receiver: 5 }\n"                                 // 11
                                  "  }\n"                                                           // 12
                                  "}\n");
  ResolvedNode node = Fleet::load(fleet).resolve("auv");
  const v1::Config& config = node.config;
  EXPECT_EQ(config.log_level(), v1::WARN);
  // The n-th slot of a src meets the n-th inherited slot of that src.
  ASSERT_EQ(config.mac().slot_size(), 4);
  EXPECT_EQ(config.mac().slot(0).seconds(), 4);
  EXPECT_EQ(config.mac().slot(0).rate(), 5);
  EXPECT_EQ(config.mac().slot(1).src(), 2);
  EXPECT_EQ(config.mac().slot(2).seconds(), 12);
  EXPECT_EQ(config.mac().slot(2).rate(), 1);
  EXPECT_EQ(config.mac().slot(3).src(), 7);
  // queue.type by type: x.A keeps ack, takes the new ttl; x.B is appended.
  ASSERT_EQ(config.queue().type_size(), 2);
  EXPECT_EQ(config.queue().type(0).policy().ttl_s(), 30);
  EXPECT_TRUE(config.queue().type(0).policy().ack());
  EXPECT_EQ(config.queue().type(1).type(), "x.B");
  // telemetry.receiver replaces.
  ASSERT_EQ(config.telemetry().receiver_size(), 1);
  EXPECT_EQ(config.telemetry().receiver(0), 5);
  // Relative paths are relative to the file that names them.
  EXPECT_EQ(config.dccl().proto_files(0), (dir_ / "a.proto").string());

  auto at = [&](const std::string& path) {
    auto it = node.config_where.find(path);
    return it == node.config_where.end() ? std::string("(none)") : to_string(it->second);
  };
  EXPECT_EQ(at("log_level"), fleet + ":6");
  EXPECT_EQ(at("mac.slot[0].seconds"), fleet + ":7");
  EXPECT_EQ(at("mac.slot[0].rate"), cruise + ":6");
  EXPECT_EQ(at("mac.slot[1].seconds"), cruise + ":7");
  EXPECT_EQ(at("mac.slot[2].rate"), cruise + ":8");
  EXPECT_EQ(at("mac.slot[3].src"), fleet + ":8");
  EXPECT_EQ(at("queue.type[0].policy.ack"), cruise + ":10");
  EXPECT_EQ(at("queue.type[0].policy.ttl_s"), fleet + ":9");
  EXPECT_EQ(at("queue.type[1].type"), fleet + ":10");
  EXPECT_EQ(at("telemetry.receiver[0]"), fleet + ":11");
  EXPECT_EQ(at("telemetry.receiver[1]"), "(none)");  // the replaced list leaves no trace
  EXPECT_EQ(at("dccl.proto_files[0]"), cruise + ":9");

  // --explain: the same places after each field.
  std::string explained = render_located(config, &node.config_where).text;
  EXPECT_NE(explained.find("log_level: WARN  # " + fleet + ":6\n"), std::string::npos) << explained;
  EXPECT_NE(explained.find("    rate: 5  # " + cruise + ":6\n"), std::string::npos) << explained;
}

TEST_F(FleetFiles, AnAncestorReachedTwiceIsMergedOnceAndAppendListsSkipRepeats) {
  write("cruise.conf", kCruise);
  const std::string fleet = write("fleet.conf",
                                  "include: \"cruise.conf\"\n"
                                  "node { name: \"global\" abstract: true parent: \"cruise\"\n"
                                  "       config { dccl { proto_files: \"b.proto\" } } }\n"
                                  "node { name: \"glider\" abstract: true parent: \"cruise\"\n"
                                  "       config { dccl { proto_files: \"a.proto\" proto_files: \"c.proto\" } } }\n"
                                  "node { name: \"g1\" parent: \"global\" parent: \"glider\" }\n");
  ResolvedNode node = Fleet::load(fleet).resolve("g1");
  EXPECT_EQ(node.lineage, (std::vector<std::string>{"cruise", "global", "glider", "g1"}));
  ASSERT_EQ(node.config.dccl().proto_files_size(), 3) << node.config.ShortDebugString();
  EXPECT_EQ(node.config.dccl().proto_files(0), (dir_ / "a.proto").string());
  EXPECT_EQ(node.config.dccl().proto_files(1), (dir_ / "b.proto").string());
  EXPECT_EQ(node.config.dccl().proto_files(2), (dir_ / "c.proto").string());
  EXPECT_EQ(node.config.mac().slot_size(), 3);  // cruise's list once, not twice
}

TEST_F(FleetFiles, ErrorsNameTheFileAndLine) {
  const std::string a = write("a.conf", "node { name: \"x\" }\nnode { name: \"y\" parent: \"nobody\" }\n");
  const std::string b = write("b.conf", "include: \"a.conf\"\n\nnode { name: \"x\" }\n");
  try {
    Fleet::load(b);
    FAIL() << "a name defined twice loaded";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), b);
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.problem().find(a + ":1"), std::string::npos) << e.problem();
  }
  try {
    Fleet::load(a).resolve("y");
    FAIL() << "a missing parent resolved";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), a);
    EXPECT_EQ(e.line(), 2);
  }
  const std::string loop = write("loop.conf", "node { name: \"p\" parent: \"q\" }\nnode { name: \"q\" parent: \"p\" }\n");
  EXPECT_THROW(Fleet::load(loop).resolve("p"), ConfigError);
  const std::string missing = write("missing.conf", "\ninclude: \"nothere.conf\"\n");
  try {
    Fleet::load(missing);
    FAIL() << "a missing include loaded";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), missing);
    EXPECT_EQ(e.line(), 2);
  }
}

TEST_F(FleetFiles, ANodesConfigErrorNamesTheFleetLineTheFieldCameFrom) {
  const std::string fleet = write("fleet.conf",
                                  "node { name: \"c\" abstract: true\n"
                                  "  config { grpc {\n"
                                  "    tcp_listen: \"nonsense\" } } }\n"
                                  "node { name: \"n\" parent: \"c\" }\n");
  try {
    load_fleet_node_config(fleet, "n");
    FAIL() << "a bad tcp_listen loaded";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.file(), fleet);
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.field(), "grpc.tcp_listen");
  }
  EXPECT_THROW(load_fleet_node_config(fleet, "c"), ConfigError);  // a class is not run
}

TEST(FleetImport, ImportingTheExampleFleetsNodesGivesTheSameConfigsBack) {
  Fleet example = Fleet::load(ACOMMS_SOURCE_DIR "/examples/fleet/fleet.conf");
  std::vector<std::pair<std::string, v1::Config>> configs;
  for (const std::string& name : example.node_names()) configs.emplace_back(name, example.resolve(name).config);
  ASSERT_EQ(configs.size(), 5u);
  v1::FleetFile imported = import_fleet(configs);
  // "common" holds what all share: the cycle, not the modem ids.
  EXPECT_EQ(imported.node(0).config().mac().slot_size(), 5);
  EXPECT_EQ(imported.node(0).config().driver().modem_id(), 0u);
  Fleet again = Fleet::parse(render_located(imported, nullptr).text, "/nowhere/imported.conf");
  for (const auto& [name, config] : configs) {
    v1::Config round = again.resolve(name).config;
    EXPECT_TRUE(pb::util::MessageDifferencer::Equals(round, config))
        << name << ":\n" << round.DebugString() << "\nwas\n" << config.DebugString();
  }
}

}  // namespace
}  // namespace acomms::core
