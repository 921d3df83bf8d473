// acommsctl's control commands against a real acommsd (sim driver): what a
// person types, what they see, and the exit code. Every error status the API
// documents is reached from the command line, and each success is checked
// in what the daemon then reports (queue ls, events, defs list).

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "acomms/v1/acomms.pb.h"
#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using google::protobuf::Struct;
using google::protobuf::Value;

const std::string kAcommsd = ACOMMSD_BINARY;
const std::string kAcommsctl = ACOMMSCTL_BINARY;
const std::string kTestProto = ACOMMS_TEST_PROTO_DIR "/ctl_test.proto";
const std::string kCompletionFile = ACOMMS_SOURCE_DIR "/cli/completion/acommsctl.bash";

template <typename Message>
Message parse_json(const std::string& json) {
  Message message;
  auto status = google::protobuf::util::JsonStringToMessage(json, &message);
  EXPECT_TRUE(status.ok()) << status.message() << " in: " << json;
  return message;
}

// A field of a JSON object, by dotted path ("header.src").
const Value& at(const Struct& object, const std::string& path) {
  static const Value kMissing;
  const Struct* current = &object;
  size_t begin = 0;
  while (true) {
    size_t dot = path.find('.', begin);
    auto found = current->fields().find(path.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (found == current->fields().end()) return kMissing;
    if (dot == std::string::npos) return found->second;
    current = &found->second.struct_value();
    begin = dot + 1;
  }
}

std::string read_file(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Config of one node: sim driver, and the test's DCCL types with strict
// bounds; Beacon's queue holds one message and refuses more.
std::string node_config(const fs::path& dir, const std::string& name, int modem_id, const std::string& driver_extra,
                        const std::string& mac) {
  std::ostringstream config;
  config << DaemonConfig{.data_dir = dir / name, .unix_socket = (dir / (name + ".sock")).string()}.text()
         << "driver { name: \"sim\" modem_id: " << modem_id << " " << driver_extra << " }\n"
         << "mac { " << mac << " }\n"
         << "dccl { proto_files: \"" << kTestProto << "\" strict: true }\n"
         << "queue { type { type: \"ctltest.Beacon\" policy { max_queue: 1 on_full: REFUSE_NEW } } }\n";
  return config.str();
}

class AcommsctlApi : public ::testing::Test {
 protected:
  void SetUp() override {
    // Short: unix socket paths are limited to 107 bytes.
    dir_ = fs::path("/tmp") / ("acomms-ctl-" + std::to_string(::getpid()) + "-" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    socket_ = (dir_ / "node.sock").string();
    std::ofstream(dir_ / "node.conf") << node_config(dir_, "node", 1, "", "name: \"none\"");
    daemon_ = std::make_unique<ChildProcess>(kAcommsd, std::vector<std::string>{"--config", (dir_ / "node.conf").string()},
                                             (dir_ / "acommsd").string());
    ASSERT_TRUE(wait_serving(*daemon_, socket_)) << daemon_->stderr_text();
  }

  void TearDown() override {
    if (daemon_ && daemon_->running()) {
      daemon_->signal(SIGTERM);
      daemon_->wait(10s);
    }
    fs::remove_all(dir_);
  }

  RunResult ctl(std::vector<std::string> args, const std::string& input = "") {
    args.insert(args.begin(), {"--socket", socket_});
    std::string log = (dir_ / ("ctl" + std::to_string(++runs_))).string();
    return input.empty() ? run(kAcommsctl, args, log) : run_with_input(kAcommsctl, args, log, input);
  }

  // Sends and returns the message id (failing the test if it does not).
  int64_t send(const std::vector<std::string>& args) {
    std::vector<std::string> all = {"send"};
    all.insert(all.end(), args.begin(), args.end());
    RunResult result = ctl(all);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return std::atoll(result.out.c_str());
  }

  v1::ListQueuedResponse queued(const std::string& type = "") {
    std::vector<std::string> args = {"queue", "ls", "--json"};
    if (!type.empty()) args.push_back(type);
    RunResult result = ctl(args);
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return parse_json<v1::ListQueuedResponse>(result.out);
  }

  const v1::QueuedMessage* find(const v1::ListQueuedResponse& list, int64_t id) {
    for (const auto& m : list.messages()) {
      if (m.message_id() == id) return &m;
    }
    return nullptr;
  }

  fs::path dir_;
  std::string socket_;
  std::unique_ptr<ChildProcess> daemon_;
  int runs_ = 0;
};

// ------------------------------------------------------------------ send

TEST_F(AcommsctlApi, SendFieldValuesQueuesTheMessageWithThoseValues) {
  int64_t id = send({"ctltest.VehicleStatus", "header.src=3", "header.dest=2", "depth=12.5", "mode=SURVEY",
                     "fault=true", "battery=80,75", "note=hi there", "blob=0x0a1b"});
  ASSERT_GT(id, 0);
  const v1::ListQueuedResponse list = queued();
  const v1::QueuedMessage* message = find(list, id);
  ASSERT_NE(message, nullptr);
  EXPECT_EQ(message->type(), "ctltest.VehicleStatus");
  Struct fields = parse_json<Struct>(message->json());
  EXPECT_EQ(at(fields, "header.src").number_value(), 3);
  EXPECT_EQ(at(fields, "header.dest").number_value(), 2);
  EXPECT_EQ(at(fields, "depth").number_value(), 12.5);
  EXPECT_EQ(at(fields, "mode").string_value(), "SURVEY");
  EXPECT_TRUE(at(fields, "fault").bool_value());
  ASSERT_EQ(at(fields, "battery").list_value().values_size(), 2);
  EXPECT_EQ(at(fields, "battery").list_value().values(0).number_value(), 80);
  EXPECT_EQ(at(fields, "battery").list_value().values(1).number_value(), 75);
  EXPECT_EQ(at(fields, "note").string_value(), "hi there");
  EXPECT_EQ(at(fields, "blob").string_value(), "Chs=");  // base64 of 0a1b
}

TEST_F(AcommsctlApi, SendJsonQueuesTheMessageAndAnswersInJson) {
  RunResult result = ctl({"send", "ctltest.VehicleStatus", "--json",
                          R"({"header": {"src": 4}, "depth": 7, "mode": "RETURN"})", "--ttl", "60"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  ASSERT_EQ(result.out.rfind("{\"message_id\": ", 0), 0u) << result.out;
  int64_t id = std::atoll(result.out.c_str() + 15);
  const v1::ListQueuedResponse list = queued("ctltest.VehicleStatus");
  const v1::QueuedMessage* message = find(list, id);
  ASSERT_NE(message, nullptr) << result.out;
  EXPECT_EQ(message->ttl_s(), 60);
  Struct fields = parse_json<Struct>(message->json());
  EXPECT_EQ(at(fields, "header.src").number_value(), 4);
  EXPECT_EQ(at(fields, "depth").number_value(), 7);
  EXPECT_EQ(at(fields, "mode").string_value(), "RETURN");
}

TEST_F(AcommsctlApi, GlobalJsonFlagAfterTheFieldsAnswersInJson) {
  RunResult result = ctl({"send", "ctltest.Beacon", "seq=5", "--json"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out.rfind("{\"message_id\": ", 0), 0u) << result.out;
}

TEST_F(AcommsctlApi, UnknownTypeIsNotFound) {
  RunResult json = ctl({"send", "ctltest.Nope", "--json", "{}"});
  EXPECT_EQ(json.exit_code, 1);
  EXPECT_EQ(json.err, "acommsctl: NOT_FOUND: no DCCL type \"ctltest.Nope\" is loaded\n");
  EXPECT_EQ(json.out, "");

  RunResult fields = ctl({"send", "ctltest.Nope", "x=1"});
  EXPECT_EQ(fields.exit_code, 1);
  EXPECT_EQ(fields.err.rfind("acommsctl: NOT_FOUND: ", 0), 0u) << fields.err;
  EXPECT_NE(fields.err.find("ctltest.Nope"), std::string::npos) << fields.err;
}

TEST_F(AcommsctlApi, TyposAreUsageErrorsThatNameTheValidChoices) {
  RunResult unknown = ctl({"send", "ctltest.VehicleStatus", "header.src=1", "depth=3", "foo=1"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown field \"foo\" of ctltest.VehicleStatus"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("header.src, header.dest, depth, mode, fault, battery, note, blob"), std::string::npos)
      << unknown.err;

  RunResult nested = ctl({"send", "ctltest.VehicleStatus", "header.nope=1"});
  EXPECT_EQ(nested.exit_code, 2);
  EXPECT_NE(nested.err.find("unknown field \"header.nope\""), std::string::npos) << nested.err;

  RunResult enum_value = ctl({"send", "ctltest.VehicleStatus", "header.src=1", "depth=3", "mode=FLYING"});
  EXPECT_EQ(enum_value.exit_code, 2);
  EXPECT_NE(enum_value.err.find("mode: \"FLYING\" is not one of IDLE, SURVEY, RETURN"), std::string::npos)
      << enum_value.err;

  RunResult number = ctl({"send", "ctltest.VehicleStatus", "header.src=1", "depth=deep"});
  EXPECT_EQ(number.exit_code, 2);
  EXPECT_NE(number.err.find("depth: \"deep\" is not a number"), std::string::npos) << number.err;

  RunResult bytes = ctl({"send", "ctltest.VehicleStatus", "header.src=1", "depth=1", "blob=zz"});
  EXPECT_EQ(bytes.exit_code, 2);
  EXPECT_NE(bytes.err.find("blob: bytes are written in hex"), std::string::npos) << bytes.err;

  // Required fields are the daemon's to check (it fills role fields first).
  RunResult missing = ctl({"send", "ctltest.VehicleStatus", "depth=1"});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err.rfind("acommsctl: INVALID_ARGUMENT: ", 0), 0u) << missing.err;
  EXPECT_NE(missing.err.find("required field(s) missing: header"), std::string::npos) << missing.err;

  RunResult no_equals = ctl({"send", "ctltest.VehicleStatus", "depth"});
  EXPECT_EQ(no_equals.exit_code, 2);
  EXPECT_NE(no_equals.err.find("\"depth\" is not field=value"), std::string::npos) << no_equals.err;

  RunResult parse = ctl({"queue", "cancel", "seven"});
  EXPECT_EQ(parse.exit_code, 2) << parse.err;

  EXPECT_EQ(queued().messages_size(), 0);  // none of it reached a queue
}

TEST_F(AcommsctlApi, OutOfBoundsValueIsInvalidArgumentNamingFieldAndBound) {
  RunResult result = ctl({"send", "ctltest.VehicleStatus", "header.src=1", "depth=900"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err.rfind("acommsctl: INVALID_ARGUMENT: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find("depth"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("500"), std::string::npos) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
}

TEST_F(AcommsctlApi, MalformedJsonIsInvalidArgument) {
  RunResult result = ctl({"send", "ctltest.VehicleStatus", "--json", R"({"depth": )"});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err.rfind("acommsctl: INVALID_ARGUMENT: json: ", 0), 0u) << result.err;
}

TEST_F(AcommsctlApi, FullQueueThatRefusesNewIsResourceExhausted) {
  send({"ctltest.Beacon", "seq=1"});
  RunResult second = ctl({"send", "ctltest.Beacon", "seq=2"});
  EXPECT_EQ(second.exit_code, 1);
  EXPECT_EQ(second.err.rfind("acommsctl: RESOURCE_EXHAUSTED: ", 0), 0u) << second.err;
  EXPECT_NE(second.err.find("ctltest.Beacon"), std::string::npos) << second.err;
  EXPECT_EQ(queued("ctltest.Beacon").messages_size(), 1);
  // Refused before it was stored: one "queued" event (the first), nothing
  // dropped, and the refusal counted.
  RunResult events = ctl({"events", "--json", "--type", "ctltest.Beacon", "--since", "-1h"});
  ASSERT_EQ(events.exit_code, 0) << events.err;
  v1::EventsResponse log = parse_json<v1::EventsResponse>(events.out);
  ASSERT_EQ(log.events_size(), 1) << events.out;
  EXPECT_EQ(log.events(0).kind(), "queued");
  RunResult stats = ctl({"queue", "stats", "--json", "ctltest.Beacon"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  v1::QueueStatsResponse counted = parse_json<v1::QueueStatsResponse>(stats.out);
  ASSERT_EQ(counted.queues_size(), 1) << stats.out;
  EXPECT_EQ(counted.queues(0).refused(), 1u);
  EXPECT_EQ(counted.queues(0).dropped(), 0u);
}

TEST_F(AcommsctlApi, LinkCalibrateWithTooFewPacketsRefusesSayingWhatItNeeds) {
  RunResult result = ctl({"link", "calibrate", "--since", "-1h"});
  EXPECT_EQ(result.exit_code, 1) << result.out << result.err;
  EXPECT_NE(result.err.find("too few data to calibrate: 0 packets with a model prediction in the event log since -1h"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("at least 10 decoded packets"), std::string::npos) << result.err;
  EXPECT_EQ(result.out.find("physics {"), std::string::npos) << result.out;
}

TEST_F(AcommsctlApi, InteractiveSendReadsAnswersFromAPipe) {
  // header.src: out of bounds, then good; header.dest skipped; depth: not a
  // number, then good; mode; fault skipped; battery; note, blob skipped.
  const std::string answers = "40\n3\n\nabc\n12.5\nSURVEY\n\n50,60\n\n\ny\n";
  RunResult result = ctl({"send", "ctltest.VehicleStatus", "--interactive"}, answers);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  int64_t id = std::atoll(result.out.c_str());
  EXPECT_NE(result.err.find("header.src (int32, required; min 0, max 31)"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("40 is above max 31"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("depth (double, required; min 0, max 500, precision 1)"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("\"abc\" is not a number"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("mode (enum Mode, optional; one of IDLE, SURVEY, RETURN)"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("battery (repeated int32, comma-separated; min 0, max 100, max_repeat 3)"),
            std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("note (string, optional; max_length 8)"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("send? [y/N]"), std::string::npos) << result.err;

  const v1::ListQueuedResponse list = queued();
  const v1::QueuedMessage* message = find(list, id);
  ASSERT_NE(message, nullptr) << result.out;
  Struct fields = parse_json<Struct>(message->json());
  EXPECT_EQ(at(fields, "header.src").number_value(), 3);
  EXPECT_EQ(at(fields, "depth").number_value(), 12.5);
  EXPECT_EQ(at(fields, "mode").string_value(), "SURVEY");
  EXPECT_EQ(at(fields, "battery").list_value().values_size(), 2);
}

TEST_F(AcommsctlApi, InteractiveSendAnsweredNoSendsNothing) {
  RunResult no = ctl({"send", "ctltest.Beacon", "-i"}, "9\nn\n");
  EXPECT_EQ(no.exit_code, 0) << no.err;
  EXPECT_EQ(no.out, "");
  EXPECT_NE(no.err.find("not sent"), std::string::npos) << no.err;

  RunResult ended = ctl({"send", "ctltest.VehicleStatus", "-i"}, "1\n");
  EXPECT_EQ(ended.exit_code, 2);
  EXPECT_NE(ended.err.find("input ended"), std::string::npos) << ended.err;
  EXPECT_EQ(queued().messages_size(), 0);
}

TEST_F(AcommsctlApi, InteractiveSendMayLeaveRequiredFieldsToTheDaemon) {
  // depth (required) left empty: the preview still shows the message, and
  // the daemon, not the prompt, names what is missing.
  RunResult result = ctl({"send", "ctltest.VehicleStatus", "--interactive"}, "3\n\n\n\n\n\n\n\ny\n");
  EXPECT_EQ(result.exit_code, 1) << result.err;
  EXPECT_NE(result.err.find("\"src\": 3"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("acommsctl: INVALID_ARGUMENT: "), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("required field(s) missing: depth"), std::string::npos) << result.err;
  EXPECT_EQ(queued().messages_size(), 0);
}

// ------------------------------------------------------------------ queue

TEST_F(AcommsctlApi, CancelRemovesTheMessageAndTheEventLogSaysSo) {
  int64_t keep = send({"ctltest.VehicleStatus", "header.src=1", "depth=1"});
  int64_t drop = send({"ctltest.VehicleStatus", "header.src=1", "depth=2"});
  RunResult cancel = ctl({"queue", "cancel", std::to_string(drop), "--reason", "superseded"});
  ASSERT_EQ(cancel.exit_code, 0) << cancel.err;
  const v1::ListQueuedResponse list = queued();
  EXPECT_NE(find(list, keep), nullptr);
  EXPECT_EQ(find(list, drop), nullptr);

  RunResult events = ctl({"events", "--json", "--message", std::to_string(drop), "--since", "-1h"});
  ASSERT_EQ(events.exit_code, 0) << events.err;
  v1::EventsResponse log = parse_json<v1::EventsResponse>(events.out);
  std::vector<std::string> kinds;
  for (const auto& event : log.events()) {
    EXPECT_EQ(event.message_id(), drop);
    kinds.push_back(event.kind());
    if (event.kind() == "dropped") {
      EXPECT_NE(event.detail().find("superseded"), std::string::npos) << event.detail();
    }
  }
  EXPECT_EQ(kinds, (std::vector<std::string>{"queued", "dropped"})) << events.out;

  RunResult dropped = ctl({"events", "--json", "--kind", "dropped"});
  ASSERT_EQ(dropped.exit_code, 0) << dropped.err;
  EXPECT_EQ(parse_json<v1::EventsResponse>(dropped.out).events_size(), 1) << dropped.out;

  RunResult again = ctl({"queue", "cancel", std::to_string(drop)});
  EXPECT_EQ(again.exit_code, 1);
  EXPECT_EQ(again.err.rfind("acommsctl: NOT_FOUND: ", 0), 0u) << again.err;
}

TEST_F(AcommsctlApi, CancelOfUnknownIdAndFlushOfUnknownTypeAreNotFound) {
  RunResult cancel = ctl({"queue", "cancel", "987654"});
  EXPECT_EQ(cancel.exit_code, 1);
  EXPECT_EQ(cancel.err.rfind("acommsctl: NOT_FOUND: ", 0), 0u) << cancel.err;
  RunResult flush = ctl({"queue", "flush", "ctltest.Nope"});
  EXPECT_EQ(flush.exit_code, 1);
  EXPECT_EQ(flush.err.rfind("acommsctl: NOT_FOUND: ", 0), 0u) << flush.err;
  EXPECT_NE(flush.err.find("ctltest.Nope"), std::string::npos) << flush.err;
}

TEST_F(AcommsctlApi, FlushEmptiesOneTypeAndStatsCountIt) {
  send({"ctltest.VehicleStatus", "header.src=1", "depth=1"});
  send({"ctltest.VehicleStatus", "header.src=1", "depth=2"});
  int64_t beacon = send({"ctltest.Beacon", "seq=1"});
  RunResult flush = ctl({"queue", "flush", "ctltest.VehicleStatus"});
  ASSERT_EQ(flush.exit_code, 0) << flush.err;
  EXPECT_EQ(flush.out, "removed 2 message(s) of ctltest.VehicleStatus\n");
  const v1::ListQueuedResponse list = queued();
  ASSERT_EQ(list.messages_size(), 1);
  EXPECT_EQ(list.messages(0).message_id(), beacon);

  RunResult stats = ctl({"queue", "stats", "--json", "ctltest.VehicleStatus", "ctltest.Beacon"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  v1::QueueStatsResponse response = parse_json<v1::QueueStatsResponse>(stats.out);
  ASSERT_EQ(response.queues_size(), 2) << stats.out;
  for (const auto& q : response.queues()) {
    if (q.type() == "ctltest.VehicleStatus") {
      EXPECT_EQ(q.size(), 0u);
      EXPECT_EQ(q.queued(), 2u);
      EXPECT_EQ(q.dccl_id(), 90);
    } else {
      EXPECT_EQ(q.type(), "ctltest.Beacon");
      EXPECT_EQ(q.size(), 1u);
      EXPECT_EQ(q.policy().max_queue(), 1u);
      EXPECT_EQ(q.policy().on_full(), v1::QueuePolicy::REFUSE_NEW);
    }
  }
  RunResult human = ctl({"queue", "stats"});
  EXPECT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("1 refuse"), std::string::npos) << human.out;
}

// ------------------------------------------------------------------ defs

TEST_F(AcommsctlApi, DefsLoadReportsMissingFilesAndBadProtoWithFileAndLine) {
  RunResult missing = ctl({"defs", "load", (dir_ / "absent.proto").string()});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err.rfind("acommsctl: NOT_FOUND: ", 0), 0u) << missing.err;
  EXPECT_NE(missing.err.find("absent.proto"), std::string::npos) << missing.err;

  std::ofstream(dir_ / "bad.proto") << "syntax = \"proto2\";\n"
                                    << "package bad;\n"
                                    << "message Broken { required int32 x = ; }\n";
  RunResult bad = ctl({"defs", "load", (dir_ / "bad.proto").string()});
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_EQ(bad.err.rfind("acommsctl: INVALID_ARGUMENT: ", 0), 0u) << bad.err;
  EXPECT_NE(bad.err.find("bad.proto:3:"), std::string::npos) << bad.err;

  RunResult inline_bad = ctl({"defs", "load", "--inline", (dir_ / "bad.proto").string()});
  EXPECT_EQ(inline_bad.exit_code, 1);
  EXPECT_NE(inline_bad.err.find("bad.proto:3:"), std::string::npos) << inline_bad.err;

  RunResult unreadable = ctl({"defs", "load", "--inline", (dir_ / "absent.proto").string()});
  EXPECT_EQ(unreadable.exit_code, 2);
}

TEST_F(AcommsctlApi, DefsLoadAddsTypesThatListAndSendSee) {
  const std::string proto =
      "syntax = \"proto2\";\n"
      "import \"dccl/option_extensions.proto\";\n"
      "package extra;\n"
      "message Ping {\n"
      "  option (dccl.msg) = { codec_version: 4 id: 50 max_bytes: 8 };\n"
      "  required uint32 n = 1 [(dccl.field) = { min: 0 max: 15 }];\n"
      "}\n";
  std::ofstream(dir_ / "ping.proto") << proto;
  RunResult load = ctl({"defs", "load", (dir_ / "ping.proto").string()});
  ASSERT_EQ(load.exit_code, 0) << load.err;
  EXPECT_NE(load.out.find("extra.Ping"), std::string::npos) << load.out;

  std::ofstream(dir_ / "pong.proto") << std::string(proto).replace(proto.find("Ping"), 4, "Pong").replace(
      proto.find("id: 50"), 6, "id: 51");
  RunResult inline_load = ctl({"defs", "load", "--inline", (dir_ / "pong.proto").string(), "--json"});
  ASSERT_EQ(inline_load.exit_code, 0) << inline_load.err;
  EXPECT_NE(inline_load.out.find("\"extra.Pong\""), std::string::npos) << inline_load.out;

  RunResult names = ctl({"defs", "list", "--names"});
  ASSERT_EQ(names.exit_code, 0) << names.err;
  for (const char* type : {"ctltest.VehicleStatus", "ctltest.Beacon", "extra.Ping", "extra.Pong"}) {
    EXPECT_NE(names.out.find(std::string(type) + "\n"), std::string::npos) << names.out;
  }

  RunResult list = ctl({"defs", "list", "extra.Ping", "--json", "--fields"});
  ASSERT_EQ(list.exit_code, 0) << list.err;
  v1::ListTypesResponse types = parse_json<v1::ListTypesResponse>(list.out);
  ASSERT_EQ(types.types_size(), 1);
  EXPECT_EQ(types.types(0).dccl_id(), 50);
  ASSERT_EQ(types.types(0).fields_size(), 1);
  EXPECT_EQ(types.types(0).fields(0).max_bits(), 4u);  // 0..15

  RunResult table = ctl({"defs", "list", "--fields", "ctltest.VehicleStatus"});
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("ctltest.VehicleStatus"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("header.src"), std::string::npos) << table.out;

  int64_t id = send({"extra.Ping", "n=7"});
  EXPECT_NE(find(queued("extra.Ping"), id), nullptr);

  RunResult unknown = ctl({"defs", "list", "extra.Nope"});
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_EQ(unknown.err.rfind("acommsctl: NOT_FOUND: ", 0), 0u) << unknown.err;
}

// ------------------------------------------------------------------ link

TEST_F(AcommsctlApi, LinkCycleOnMacNoneIsFailedPreconditionAndBadSlotsAreUsage) {
  RunResult cycle = ctl({"link", "cycle", "1@1/10", "2:1@1/10"});
  EXPECT_EQ(cycle.exit_code, 1);
  EXPECT_EQ(cycle.err.rfind("acommsctl: FAILED_PRECONDITION: ", 0), 0u) << cycle.err;

  RunResult json = ctl({"link", "cycle", "--json", R"([{"src": 1, "rate": 1, "seconds": 10}])"});
  EXPECT_EQ(json.exit_code, 1);
  EXPECT_EQ(json.err.rfind("acommsctl: FAILED_PRECONDITION: ", 0), 0u) << json.err;

  RunResult bad = ctl({"link", "cycle", "1@x/10"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("slot \"1@x/10\": RATE is not a whole number"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("SRC[:DEST]@RATE/SECONDS"), std::string::npos) << bad.err;

  RunResult status = ctl({"link", "status", "--json"});
  ASSERT_EQ(status.exit_code, 0) << status.err;
  v1::LinkStatusResponse link = parse_json<v1::LinkStatusResponse>(status.out);
  EXPECT_EQ(link.modem_id(), 1u);
  EXPECT_EQ(link.driver().name(), "sim");
  EXPECT_EQ(link.cycle_size(), 0);

  RunResult human = ctl({"link", "status"});
  EXPECT_EQ(human.exit_code, 0) << human.err;
  EXPECT_NE(human.out.find("driver:       sim"), std::string::npos) << human.out;
}

TEST_F(AcommsctlApi, DriverSpecificRequestsOnTheSimDriverAreUnimplementedNamingTheRequest) {
  // acommsctl link ping builds a DRIVER_SPECIFIC with the Micro-Modem's
  // extension; the sim driver knows none and says which it was given.
  RunResult ping = ctl({"link", "ping", "2", "--wait", "5"});
  EXPECT_EQ(ping.exit_code, 1);
  EXPECT_EQ(ping.err.rfind("acommsctl: UNIMPLEMENTED: ", 0), 0u) << ping.err;
  EXPECT_NE(ping.err.find("driver sim does not support the driver-specific request "
                          "acomms.drivers.micromodem_transmission"),
            std::string::npos)
      << ping.err;
  RunResult mini = ctl({"link", "mini", "2", "9000"});
  EXPECT_EQ(mini.exit_code, 2);  // refused before asking: 13 bits
  EXPECT_NE(mini.err.find("0..8191"), std::string::npos) << mini.err;
  RunResult lbl = ctl({"link", "lbl", "--remus", "AB"});
  EXPECT_EQ(lbl.exit_code, 1);
  EXPECT_NE(lbl.err.find("UNIMPLEMENTED"), std::string::npos) << lbl.err;
}

// ------------------------------------------------------------------ misc

TEST_F(AcommsctlApi, EventsTimesAreCheckedBeforeAsking) {
  RunResult bad = ctl({"events", "--since", "yesterday"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("time \"yesterday\""), std::string::npos) << bad.err;
  RunResult kind = ctl({"events", "--kind", "exploded"});
  EXPECT_EQ(kind.exit_code, 2);

  send({"ctltest.Beacon", "seq=3"});
  RunResult future = ctl({"events", "--json", "--since", std::to_string(::time(nullptr) + 3600)});
  ASSERT_EQ(future.exit_code, 0) << future.err;
  EXPECT_EQ(parse_json<v1::EventsResponse>(future.out).events_size(), 0) << future.out;
  RunResult recent = ctl({"events", "--since", "-10m"});
  ASSERT_EQ(recent.exit_code, 0) << recent.err;
  EXPECT_NE(recent.out.find("queued"), std::string::npos) << recent.out;
  EXPECT_NE(recent.out.find("ctltest.Beacon"), std::string::npos) << recent.out;
}

TEST_F(AcommsctlApi, SubscriberEndsWithZeroOnSigintAndOneWhenTheDaemonStops) {
  std::set<uint64_t> before = unix_connections(socket_);
  ChildProcess interrupted(kAcommsctl, {"--socket", socket_, "sub"}, (dir_ / "sub1").string());
  ASSERT_TRUE(wait_connected(interrupted, socket_, before)) << interrupted.stderr_text();
  interrupted.signal(SIGINT);
  EXPECT_EQ(interrupted.wait(10s), 0) << interrupted.stderr_text();

  before = unix_connections(socket_);
  ChildProcess orphaned(kAcommsctl, {"--socket", socket_, "sub", "ctltest.Beacon"}, (dir_ / "sub2").string());
  ASSERT_TRUE(wait_connected(orphaned, socket_, before)) << orphaned.stderr_text();
  daemon_->signal(SIGTERM);
  EXPECT_EQ(daemon_->wait(15s), 0);
  EXPECT_EQ(orphaned.wait(10s), 1);
  EXPECT_EQ(orphaned.stderr_text().rfind("acommsctl: UNAVAILABLE: ", 0), 0u) << orphaned.stderr_text();
}

TEST_F(AcommsctlApi, UnreachableDaemonIsExitOne) {
  RunResult result = run(kAcommsctl, {"--socket", (dir_ / "nobody.sock").string(), "queue", "ls"},
                         (dir_ / "nobody").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_EQ(result.err.rfind("acommsctl: cannot reach acommsd at ", 0), 0u) << result.err;
}

// The completion script is generated from the command tree; the packaged
// copy must be that script exactly, and bash must accept it.
TEST(AcommsctlCompletion, BashScriptMatchesTheKeptCopyAndParses) {
  fs::path dir = fs::temp_directory_path() / ("acomms-ctl-completion-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  RunResult result = run(kAcommsctl, {"completion", "bash"}, (dir / "ctl").string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out, read_file(kCompletionFile))
      << "cli/completion/acommsctl.bash is stale: regenerate it with `acommsctl completion bash > "
         "cli/completion/acommsctl.bash`";
  for (const char* word : {"\"queue cancel\")", "\"link cycle\")", "--interactive", "--since", "_acommsctl_types",
                           "defs list --names"}) {
    EXPECT_NE(result.out.find(word), std::string::npos) << word;
  }
  RunResult syntax = run("/bin/bash", {"-n", kCompletionFile}, (dir / "bash").string());
  EXPECT_EQ(syntax.exit_code, 0) << syntax.err;
  fs::remove_all(dir);
}

// Two nodes on the loopback sim channel: a message sent on node 1 comes out
// of `acommsctl sub` on node 2 as one JSON line with the decoded fields.
TEST(AcommsctlSubscribe, PrintsOneJsonLinePerReceivedMessage) {
  fs::path dir = fs::path("/tmp") / ("acomms-ctl-sub-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const int port1 = free_udp_port(), port2 = free_udp_port();
  // Both nodes at the origin: no travel time to guard (max_range_m 0), so a
  // 2 s slot at rate 5 holds one frame and its ACK.
  const std::string mac =
      "name: \"fixed\" slot { src: 1 rate: 5 seconds: 2 } slot { src: 2 rate: 5 seconds: 2 } max_range_m: 0";
  auto sim = [](int listen, int peer) {
    return "sim { listen: \"127.0.0.1:" + std::to_string(listen) + "\" peers: \"127.0.0.1:" + std::to_string(peer) +
           "\" }";
  };
  std::ofstream(dir / "n1.conf") << node_config(dir, "n1", 1, sim(port1, port2), mac);
  std::ofstream(dir / "n2.conf") << node_config(dir, "n2", 2, sim(port2, port1), mac);
  ChildProcess node1(kAcommsd, {"--config", (dir / "n1.conf").string()}, (dir / "n1").string());
  ChildProcess node2(kAcommsd, {"--config", (dir / "n2.conf").string()}, (dir / "n2").string());
  const std::string socket1 = (dir / "n1.sock").string(), socket2 = (dir / "n2.sock").string();
  ASSERT_TRUE(wait_serving(node1, socket1)) << node1.stderr_text();
  ASSERT_TRUE(wait_serving(node2, socket2)) << node2.stderr_text();

  const std::set<uint64_t> before = unix_connections(socket2);
  ChildProcess sub(kAcommsctl, {"--socket", socket2, "sub", "ctltest.VehicleStatus", "--src", "1"},
                   (dir / "sub").string());
  ASSERT_TRUE(wait_connected(sub, socket2, before)) << sub.stderr_text();
  RunResult sent = run(kAcommsctl,
                       {"--socket", socket1, "send", "ctltest.VehicleStatus", "header.src=1", "depth=42.5", "mode=IDLE"},
                       (dir / "send").string());
  ASSERT_EQ(sent.exit_code, 0) << sent.err;

  wait_until([&] { return sub.stdout_text().find('\n') != std::string::npos; }, 30s, 200ms);
  const std::string out = sub.stdout_text();
  ASSERT_NE(out.find('\n'), std::string::npos) << "nothing received; sub: " << sub.stderr_text();
  Struct line = parse_json<Struct>(out.substr(0, out.find('\n')));
  EXPECT_EQ(at(line, "type").string_value(), "ctltest.VehicleStatus");
  EXPECT_EQ(at(line, "src").number_value(), 1);
  EXPECT_GT(at(line, "receive_time").number_value(), 1.6e9);
  EXPECT_EQ(at(line, "message.depth").number_value(), 42.5);
  EXPECT_EQ(at(line, "message.header.src").number_value(), 1);
  EXPECT_EQ(at(line, "link.transmission_src").number_value(), 1);

  sub.signal(SIGTERM);
  EXPECT_EQ(sub.wait(10s), 0) << sub.stderr_text();
  node1.signal(SIGTERM);
  node2.signal(SIGTERM);
  node1.wait(10s);
  node2.wait(10s);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace acomms::testing
