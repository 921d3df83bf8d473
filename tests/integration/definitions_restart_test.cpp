// DCCL definitions loaded through the API, through the real acommsd: an
// inline .proto loaded with LoadDefinitions, a message of its type
// submitted, the daemon SIGKILLed and started again on the same data dir:
// the type is listed and the message is still queued (the definitions are
// recorded in the store and loaded again before the queues restore).
// Also Events (the queued event) and Encode/Decode of the new type.

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kAcommsd = ACOMMSD_BINARY;

constexpr const char* kMissionProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package mission;
message Waypoint {
  option (dccl.msg) = { codec_version: 4 id: 77 max_bytes: 32 };
  required int32 index = 1 [(dccl.field) = { min: 0 max: 100 }];
  required double depth = 2 [(dccl.field) = { min: 0 max: 500 precision: 1 }];
  enum Action { HOLD = 1; SURVEY = 2; }
  optional Action action = 3;
}
)";

class DefinitionsRestartTest : public ::testing::Test {
 protected:
  void SetUp() override {
    socket_ = (dir_ / "api.sock").string();
    config_ = (dir_ / "acommsd.conf").string();
    // The only slot is another node's: this daemon never transmits, so
    // nothing leaves its queue while the test looks.
    DaemonConfig{.data_dir = dir_ / "data",
                 .unix_socket = socket_,
                 .rest = "log_level: DEBUG\n"
                         "driver { name: \"sim\" modem_id: 3 }\n"
                         "mac { name: \"fixed\" slot { src: 5 seconds: 10 } }\n"}
        .write(config_);
  }

  std::unique_ptr<ChildProcess> start(const std::string& log_name) {
    auto daemon = std::make_unique<ChildProcess>(kAcommsd, std::vector<std::string>{"--config", config_},
                                                 (dir_ / log_name).string());
    EXPECT_TRUE(wait_serving(*daemon, socket_)) << daemon->stderr_text();
    return daemon;
  }

  // A context whose call cannot hang the test.
  static std::unique_ptr<grpc::ClientContext> context() {
    auto c = std::make_unique<grpc::ClientContext>();
    c->set_deadline(std::chrono::system_clock::now() + 20s);
    return c;
  }

  grpc::Status load_inline(v1::Acomms::Stub& stub, const std::string& name, const std::string& text,
                           v1::LoadDefinitionsResponse* response) {
    v1::LoadDefinitionsRequest request;
    auto* definition = request.add_inline_();
    definition->set_name(name);
    definition->set_text(text);
    return stub.LoadDefinitions(context().get(), request, response);
  }

  grpc::Status submit(v1::Acomms::Stub& stub, const std::string& type, const std::string& json,
                      v1::SubmitResponse* response) {
    v1::SubmitRequest request;
    request.set_type(type);
    request.set_json(json);
    return stub.Submit(context().get(), request, response);
  }

  // Short base path: unix socket paths are limited to 107 bytes.
  TempDir dir_{"acomms-defs-it", "/tmp"};
  std::string socket_;
  std::string config_;
};

TEST_F(DefinitionsRestartTest, LoadedTypeAndItsQueuedMessageSurviveSigkill) {
  int64_t id = 0;
  {
    auto daemon = start("first");
    ASSERT_TRUE(daemon->running());
    auto stub = api(socket_);

    v1::LoadDefinitionsResponse loaded;
    grpc::Status status = load_inline(*stub, "mission.proto", kMissionProto, &loaded);
    ASSERT_TRUE(status.ok()) << status.error_message();
    ASSERT_EQ(loaded.types_size(), 1);
    EXPECT_EQ(loaded.types(0).name(), "mission.Waypoint");
    EXPECT_EQ(loaded.types(0).dccl_id(), 77);

    v1::SubmitResponse submitted;
    status = submit(*stub, "mission.Waypoint", R"({"index": 7, "depth": 12.5, "action": "SURVEY"})", &submitted);
    ASSERT_TRUE(status.ok()) << status.error_message();
    id = submitted.message_id();
    EXPECT_GT(id, 0);

    daemon->signal(SIGKILL);
    EXPECT_FALSE(daemon->wait(15s).has_value());
    EXPECT_EQ(daemon->exit_signal(), SIGKILL);
  }

  auto again = start("second");
  ASSERT_TRUE(again->running()) << again->stderr_text();
  auto stub = api(socket_);

  v1::ListTypesRequest list_types;
  v1::ListTypesResponse types;
  grpc::Status status = stub->ListTypes(context().get(), list_types, &types);
  ASSERT_TRUE(status.ok()) << status.error_message();
  bool listed = false;
  for (const auto& type : types.types()) listed = listed || type.name() == "mission.Waypoint";
  EXPECT_TRUE(listed) << "the type loaded through the API is gone after a restart: " << types.DebugString();

  v1::ListQueuedRequest list_queued;
  v1::ListQueuedResponse queued;
  status = stub->ListQueued(context().get(), list_queued, &queued);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(queued.messages_size(), 1) << "the queued message is gone after a restart: " << queued.DebugString()
                                       << "\n" << again->stderr_text();
  EXPECT_EQ(queued.messages(0).message_id(), id);
  EXPECT_EQ(queued.messages(0).type(), "mission.Waypoint");
  EXPECT_NE(queued.messages(0).json().find("\"index\":7"), std::string::npos) << queued.messages(0).json();
  EXPECT_NE(queued.messages(0).json().find("SURVEY"), std::string::npos) << queued.messages(0).json();

  // The type can still be used, and it still cannot change.
  v1::SubmitResponse more;
  status = submit(*stub, "mission.Waypoint", R"({"index": 8, "depth": 1})", &more);
  ASSERT_TRUE(status.ok()) << status.error_message();
  EXPECT_GT(more.message_id(), id) << "a message id was handed out twice";
  v1::LoadDefinitionsResponse same;
  status = load_inline(*stub, "mission.proto", kMissionProto, &same);
  EXPECT_TRUE(status.ok()) << "the same text again was refused: " << status.error_message();
  std::string changed = kMissionProto;
  changed.replace(changed.find("max: 100"), 8, "max: 200");
  v1::LoadDefinitionsResponse refused;
  status = load_inline(*stub, "mission.proto", changed, &refused);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("types cannot change"), std::string::npos) << status.error_message();

  again->signal(SIGTERM);
  EXPECT_EQ(again->wait(15s), std::optional<int>(0)) << again->stderr_text();
}

TEST_F(DefinitionsRestartTest, EventsEncodeAndDecodeForALoadedType) {
  auto daemon = start("events");
  ASSERT_TRUE(daemon->running());
  auto stub = api(socket_);
  v1::LoadDefinitionsResponse loaded;
  grpc::Status status = load_inline(*stub, "mission.proto", kMissionProto, &loaded);
  ASSERT_TRUE(status.ok()) << status.error_message();
  v1::SubmitResponse submitted;
  status = submit(*stub, "mission.Waypoint", R"({"index": 3, "depth": 40})", &submitted);
  ASSERT_TRUE(status.ok()) << status.error_message();

  // The event is written behind the Submit's commit: poll for it.
  v1::EventsRequest events_request;
  events_request.add_kinds("queued");
  events_request.add_types("mission.Waypoint");
  v1::EventsResponse events;
  wait_until(
      [&] {
        events.Clear();
        status = stub->Events(context().get(), events_request, &events);
        return !status.ok() || events.events_size() > 0;  // a failed call stops the wait
      },
      20s, 50ms);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_EQ(events.events_size(), 1) << events.DebugString();
  EXPECT_EQ(events.events(0).kind(), "queued");
  EXPECT_EQ(events.events(0).type(), "mission.Waypoint");
  EXPECT_EQ(events.events(0).message_id(), submitted.message_id());
  EXPECT_FALSE(events.truncated());

  v1::EventsRequest by_id;
  by_id.set_message_id(submitted.message_id());
  v1::EventsResponse history;
  ASSERT_TRUE(stub->Events(context().get(), by_id, &history).ok());
  ASSERT_GE(history.events_size(), 1);
  EXPECT_EQ(history.events(0).kind(), "queued");

  v1::EventsRequest bad_kind;
  bad_kind.add_kinds("bogus");
  v1::EventsResponse ignored;
  status = stub->Events(context().get(), bad_kind, &ignored);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("queued"), std::string::npos) << status.error_message();

  // Encode, then Decode with and without the type.
  v1::EncodeRequest encode;
  encode.set_type("mission.Waypoint");
  encode.set_json(R"({"index": 9, "depth": 250.5, "action": "HOLD"})");
  v1::EncodeResponse encoded;
  status = stub->Encode(context().get(), encode, &encoded);
  ASSERT_TRUE(status.ok()) << status.error_message();
  ASSERT_FALSE(encoded.encoded().empty());
  EXPECT_LE(encoded.encoded().size(), 32u);

  for (const std::string& type : {std::string(), std::string("mission.Waypoint")}) {
    v1::DecodeRequest decode;
    decode.set_encoded(encoded.encoded());
    decode.set_type(type);
    v1::DecodeResponse decoded;
    status = stub->Decode(context().get(), decode, &decoded);
    ASSERT_TRUE(status.ok()) << status.error_message();
    ASSERT_EQ(decoded.messages_size(), 1);
    EXPECT_EQ(decoded.messages(0).type(), "mission.Waypoint");
    const std::string& json = decoded.messages(0).json();
    EXPECT_NE(json.find("\"index\":9"), std::string::npos) << json;
    EXPECT_NE(json.find("250.5"), std::string::npos) << json;
    EXPECT_NE(json.find("HOLD"), std::string::npos) << json;
    EXPECT_FALSE(decoded.messages(0).payload().empty());

    // The decoded payload encodes to the same bytes.
    v1::EncodeRequest reencode;
    reencode.set_type("mission.Waypoint");
    reencode.set_payload(decoded.messages(0).payload());
    v1::EncodeResponse reencoded;
    ASSERT_TRUE(stub->Encode(context().get(), reencode, &reencoded).ok());
    EXPECT_EQ(reencoded.encoded(), encoded.encoded());
  }

  // Two messages back to back decode as two.
  {
    v1::DecodeRequest decode;
    decode.set_encoded(encoded.encoded() + encoded.encoded());
    v1::DecodeResponse decoded;
    status = stub->Decode(context().get(), decode, &decoded);
    ASSERT_TRUE(status.ok()) << status.error_message();
    EXPECT_EQ(decoded.messages_size(), 2);
  }

  v1::DecodeRequest garbage;
  garbage.set_encoded(std::string("\xff\xff\xff\xff\xff\xff", 6));
  v1::DecodeResponse not_decoded;
  status = stub->Decode(context().get(), garbage, &not_decoded);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT) << status.error_message();

  v1::DecodeRequest unknown;
  unknown.set_encoded(encoded.encoded());
  unknown.set_type("mission.Nope");
  status = stub->Decode(context().get(), unknown, &not_decoded);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::NOT_FOUND) << status.error_message();

  v1::EncodeRequest missing;
  missing.set_type("mission.Waypoint");
  missing.set_json(R"({"index": 9})");
  v1::EncodeResponse not_encoded;
  status = stub->Encode(context().get(), missing, &not_encoded);
  EXPECT_EQ(status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(status.error_message().find("depth"), std::string::npos) << status.error_message();

  daemon->signal(SIGTERM);
  EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << daemon->stderr_text();
}

// A field with (dccl.field).omit is not on the wire: a decoded message of
// such a type lacks it even when it is required. Decode still answers
// with what was decoded.
TEST_F(DefinitionsRestartTest, DecodeOfATypeWithAnOmittedRequiredField) {
  auto daemon = start("omit");
  ASSERT_TRUE(daemon->running());
  auto stub = api(socket_);
  v1::LoadDefinitionsResponse loaded;
  grpc::Status status = load_inline(*stub, "local.proto", R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package local;
message Local {
  option (dccl.msg) = { codec_version: 4 id: 78 max_bytes: 16 };
  required int32 kept = 1 [(dccl.field) = { min: 0 max: 100 }];
  required int32 local_only = 2 [(dccl.field).omit = true];
}
)", &loaded);
  ASSERT_TRUE(status.ok()) << status.error_message();
  v1::EncodeRequest encode;
  encode.set_type("local.Local");
  encode.set_json(R"({"kept": 42, "local_only": 7})");
  v1::EncodeResponse encoded;
  status = stub->Encode(context().get(), encode, &encoded);
  ASSERT_TRUE(status.ok()) << status.error_message();

  v1::DecodeRequest decode;
  decode.set_encoded(encoded.encoded());
  v1::DecodeResponse decoded;
  status = stub->Decode(context().get(), decode, &decoded);
  EXPECT_TRUE(status.ok()) << grpc::StatusCode(status.error_code()) << ": " << status.error_message();
  if (status.ok()) {
    ASSERT_EQ(decoded.messages_size(), 1);
    EXPECT_NE(decoded.messages(0).json().find("\"kept\":42"), std::string::npos) << decoded.messages(0).json();
  }
  EXPECT_TRUE(daemon->running()) << daemon->stderr_text();
  daemon->signal(SIGTERM);
  EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << daemon->stderr_text();
}

}  // namespace
}  // namespace acomms::testing
