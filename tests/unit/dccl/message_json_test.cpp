// JsonReader, message_json and indented_message_json (dccl/message_json.h):
// DCCL types parsed from JSON without insisting on required fields, clear
// reasons for bad JSON and unknown fields, enums by name, proto field names
// on output.

#include "dccl/message_json.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <google/protobuf/reflection.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <vector>

#include "dccl/codec.h"

namespace acomms::dccl {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package jt;
message Report {
  option (dccl.msg) = { codec_version: 4 id: 20 max_bytes: 32 };
  required int32 count = 1 [(dccl.field) = { min: 0 max: 100 }];
  required int32 depth_m = 2 [(dccl.field) = { min: 0 max: 100 }];
  enum Mode { IDLE = 1; RUN = 2; }
  optional Mode mode = 3;
  optional bool battery_ok = 4;
  message Fix {
    required int32 quality = 1 [(dccl.field) = { min: 0 max: 10 }];
    optional int32 sats = 2 [(dccl.field) = { min: 0 max: 20 }];
  }
  optional Fix fix = 5;
}
)";

class JsonReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("acomms-json-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "jt.proto") << kProto;
    codec_.load((dir_ / "jt.proto").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::unique_ptr<pb::Message> report() { return codec_.new_message("jt.Report"); }
  const pb::FieldDescriptor* field(const pb::Message& m, const std::string& name) {
    const pb::FieldDescriptor* f = m.GetDescriptor()->FindFieldByName(name);
    EXPECT_NE(f, nullptr) << name;
    return f;
  }

  fs::path dir_;
  Codec codec_;
  JsonReader reader_;
};

TEST_F(JsonReaderTest, RequiredFieldMissingStillParsesAndLeavesItUnset) {
  auto message = report();
  EXPECT_EQ(reader_.parse(R"({"count": 5})", message.get()), "");
  const pb::Reflection* r = message->GetReflection();
  EXPECT_EQ(r->GetInt32(*message, field(*message, "count")), 5);
  EXPECT_FALSE(r->HasField(*message, field(*message, "depth_m")));
  EXPECT_FALSE(message->IsInitialized());
  EXPECT_NE(message->InitializationErrorString().find("depth_m"), std::string::npos);
}

TEST_F(JsonReaderTest, EmptyObjectParses) {
  auto message = report();
  EXPECT_EQ(reader_.parse("{}", message.get()), "");
  EXPECT_EQ(message->ByteSizeLong(), 0u);
}

TEST_F(JsonReaderTest, NestedRequiredFieldMissingStillParses) {
  auto message = report();
  EXPECT_EQ(reader_.parse(R"({"count": 1, "depth_m": 2, "fix": {"sats": 7}})", message.get()), "");
  const pb::Message& fix = message->GetReflection()->GetMessage(*message, field(*message, "fix"));
  EXPECT_EQ(fix.GetReflection()->GetInt32(fix, field(fix, "sats")), 7);
  EXPECT_FALSE(fix.GetReflection()->HasField(fix, field(fix, "quality")));
}

TEST_F(JsonReaderTest, CompleteMessageParsesAndEncodes) {
  auto message = report();
  ASSERT_EQ(reader_.parse(R"({"count": 5, "depth_m": 60, "battery_ok": true, "fix": {"quality": 3}})",
                          message.get()),
            "");
  EXPECT_TRUE(message->IsInitialized()) << message->InitializationErrorString();
  auto decoded = codec_.decode(codec_.encode(*message));
  ASSERT_EQ(decoded.size(), 1u);
  EXPECT_EQ(decoded[0]->ShortDebugString(), message->ShortDebugString());
}

TEST_F(JsonReaderTest, EnumByName) {
  auto message = report();
  ASSERT_EQ(reader_.parse(R"({"mode": "RUN"})", message.get()), "");
  const pb::EnumValueDescriptor* mode = message->GetReflection()->GetEnum(*message, field(*message, "mode"));
  EXPECT_EQ(mode->name(), "RUN");

  auto bad = report();
  std::string why = reader_.parse(R"({"mode": "FAST"})", bad.get());
  EXPECT_FALSE(why.empty()) << "an enum name that does not exist was accepted";
}

TEST_F(JsonReaderTest, ProtoAndJsonFieldNamesAreBothAccepted) {
  auto proto_name = report();
  ASSERT_EQ(reader_.parse(R"({"depth_m": 9})", proto_name.get()), "");
  auto json_name = report();
  ASSERT_EQ(reader_.parse(R"({"depthM": 9})", json_name.get()), "");
  EXPECT_EQ(proto_name->SerializePartialAsString(), json_name->SerializePartialAsString());
}

TEST_F(JsonReaderTest, MalformedJsonIsReportedWithAReason) {
  for (const char* json : {R"({"count": )", "not json", R"({"count": 1)", R"({"count" 1})", ""}) {
    auto message = report();
    std::string why = reader_.parse(json, message.get());
    EXPECT_FALSE(why.empty()) << "accepted: " << json;
    EXPECT_NE(why.rfind(": ", 0), 0u) << "empty path left in front: " << why;
  }
}

TEST_F(JsonReaderTest, UnknownFieldIsReportedByName) {
  auto message = report();
  std::string why = reader_.parse(R"({"count": 1, "no_such_field": 2})", message.get());
  ASSERT_FALSE(why.empty()) << "an unknown field was accepted";
  EXPECT_NE(why.find("no_such_field"), std::string::npos) << why;
}

TEST_F(JsonReaderTest, WrongValueTypeIsReported) {
  auto message = report();
  std::string why = reader_.parse(R"({"count": "many"})", message.get());
  EXPECT_FALSE(why.empty());
}

TEST_F(JsonReaderTest, MessageJsonUsesProtoFieldNamesAndLeavesDefaultsOut) {
  auto message = report();
  ASSERT_EQ(reader_.parse(R"({"count": 5, "depth_m": 0, "battery_ok": true, "mode": "IDLE"})", message.get()),
            "");
  std::string json = message_json(*message);
  EXPECT_NE(json.find("\"battery_ok\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"IDLE\""), std::string::npos) << json;
  EXPECT_EQ(json.find("fix"), std::string::npos) << "an unset field was printed: " << json;
  // And back.
  auto again = report();
  ASSERT_EQ(reader_.parse(json, again.get()), "") << json;
  EXPECT_EQ(again->SerializePartialAsString(), message->SerializePartialAsString());
}

// The client's JSON is one line (a reply field, a line of `acommsctl sub`);
// the prompt's is indented for a person; both read back to the message.
TEST_F(JsonReaderTest, MessageJsonIsOneLineAndIndentedMessageJsonTheSameOverSeveral) {
  auto message = report();
  ASSERT_EQ(reader_.parse(R"({"count": 5, "fix": {"quality": 3}})", message.get()), "");
  const std::string line = message_json(*message);
  const std::string indented = indented_message_json(*message);
  EXPECT_EQ(line, R"({"count":5,"fix":{"quality":3}})");
  EXPECT_NE(indented.find('\n'), std::string::npos) << indented;
  EXPECT_NE(indented.find("\n \"count\": 5,\n"), std::string::npos) << indented;
  for (const std::string& json : {line, indented}) {
    auto again = report();
    ASSERT_EQ(reader_.parse(json, again.get()), "") << json;
    EXPECT_EQ(again->SerializePartialAsString(), message->SerializePartialAsString()) << json;
  }
}

// A DCCL field with (dccl.field).omit is not on the wire, so a decoded
// message can lack a required field. Such messages reach message_json on the
// core thread (Subscribe) and in Decode: it must not throw.
TEST_F(JsonReaderTest, MessageJsonOfADecodedMessageWithAnOmittedRequiredFieldDoesNotThrow) {
  std::ofstream(dir_ / "omit.proto") << R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package jo;
message Local {
  option (dccl.msg) = { codec_version: 4 id: 21 max_bytes: 16 };
  required int32 kept = 1 [(dccl.field) = { min: 0 max: 100 }];
  required int32 local_only = 2 [(dccl.field).omit = true];
}
)";
  codec_.load((dir_ / "omit.proto").string());
  auto message = codec_.new_message("jo.Local");
  ASSERT_EQ(reader_.parse(R"({"kept": 42, "local_only": 7})", message.get()), "");
  auto decoded = codec_.decode(codec_.encode(*message));
  ASSERT_EQ(decoded.size(), 1u);
  ASSERT_FALSE(decoded[0]->IsInitialized()) << "omitted field came back: nothing to test";
  std::string json;
  try {
    json = message_json(*decoded[0]);
  } catch (const std::exception& e) {
    FAIL() << "message_json threw: " << e.what();
  }
  EXPECT_NE(json.find("\"kept\":42"), std::string::npos) << json;
}

TEST_F(JsonReaderTest, ConcurrentParsesAgree) {
  std::vector<std::future<std::string>> results;
  for (int t = 0; t < 4; ++t) {
    results.push_back(std::async(std::launch::async, [this, t] {
      std::string out;
      for (int i = 0; i < 200; ++i) {
        auto message = report();
        std::string why = reader_.parse("{\"count\": " + std::to_string((t * 7 + i) % 100) + "}", message.get());
        if (!why.empty()) return why;
      }
      return out;
    }));
  }
  for (auto& result : results) EXPECT_EQ(result.get(), "");
}

}  // namespace
}  // namespace acomms::dccl
