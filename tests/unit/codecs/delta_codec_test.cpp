// The delta-difference codec plugin: bytes against a hand-computed encoding,
// decoded values, strict-mode errors, load-time validation, and the version
// suffix lookup that selects it.

#include "delta/delta_codec.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "dccl/codec.h"
#include "dccl/hex.h"
#include "dccl/plugin_codecs.h"

namespace acomms::codecs {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

using dccl::to_hex;

class DeltaCodecTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-delta-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    dccl::install_plugin_codecs(codec_.registry());
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Loads `fields` as the body of message test.Series (id 1, v4).
  void load(const std::string& fields) { load_into(codec_, fields); }
  void load_into(dccl::Codec& codec, const std::string& fields) {
    std::string path = (dir_ / ("series" + std::to_string(++files_) + ".proto")).string();
    std::ofstream(path) << "syntax = \"proto2\";\n"
                           "import \"dccl/option_extensions.proto\";\n"
                           "import \"acomms/codecs/delta.proto\";\n"
                           "package test;\n"
                           "message Series {\n"
                           "  option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 64 };\n"
                        << fields << "\n}\n";
    codec.load(path);
  }
  // Each schema gets a codec of its own: a pool holds one test.Series.
  std::string load_error(const std::string& fields) {
    dccl::Codec codec;
    dccl::install_plugin_codecs(codec.registry());
    try {
      load_into(codec, fields);
    } catch (const dccl::Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "loaded without error";
    return "";
  }
  std::unique_ptr<pb::Message> series(const std::vector<double>& values) {
    auto message = codec_.new_message("test.Series");
    const pb::FieldDescriptor* v = message->GetDescriptor()->FindFieldByName("v");
    for (double x : values) message->GetReflection()->AddDouble(message.get(), v, x);
    return message;
  }
  std::vector<double> values(const pb::Message& message) {
    const pb::FieldDescriptor* v = message.GetDescriptor()->FindFieldByName("v");
    std::vector<double> out;
    for (int i = 0; i < message.GetReflection()->FieldSize(message, v); ++i) {
      out.push_back(message.GetReflection()->GetRepeatedDouble(message, v, i));
    }
    return out;
  }

  fs::path dir_;
  int files_ = 0;
  dccl::Codec codec_;
};

constexpr const char* kSeriesField =
    "  repeated double v = 1 [(dccl.field) = { codec: \"acomms.delta\" min: 0 max: 100 "
    "precision: 1 max_repeat: 4 [acomms.codecs.delta] { max_delta: 2 } }];";

TEST_F(DeltaCodecTest, EncodesKeyPlusDeltasBitExact) {
  load(kSeriesField);
  // id 1 -> 0x02. Body, LSB first: count 4 (3 bits), key 10.0 -> 100 (10 bits),
  // 10.5 -> (10.5 + 2 - 10) * 10 + 1 = 26, 8.0 -> 0 + 1 = 1 (6 bits each), and
  // 12.1 is 2.1 from the key, beyond max_delta -> 0. 31 bits = 0x000b4324.
  std::string bytes = codec_.encode(*series({10.0, 10.5, 8.0, 12.1}));
  EXPECT_EQ(to_hex(bytes), "0224430b00");

  auto decoded = codec_.decode(bytes);
  ASSERT_EQ(decoded.size(), 1u);
  std::vector<double> v = values(*decoded[0]);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_DOUBLE_EQ(v[0], 10.0);
  EXPECT_DOUBLE_EQ(v[1], 10.5);
  EXPECT_DOUBLE_EQ(v[2], 8.0);
  EXPECT_TRUE(std::isnan(v[3])) << "out-of-range delta decodes as not available";
}

TEST_F(DeltaCodecTest, BitBudgetIsKeyPlusNarrowDeltas) {
  load(kSeriesField);
  const dccl::TypeInfo* info = codec_.find_type("test.Series");
  ASSERT_NE(info, nullptr);
  ASSERT_EQ(info->fields.size(), 1u);
  EXPECT_EQ(info->fields[0].codec, "acomms.delta");
  EXPECT_EQ(info->fields[0].bits.min, 3u);            // count only
  EXPECT_EQ(info->fields[0].bits.max, 3u + 10 + 3 * 6);  // versus 3 + 4 * 10 with _default4
}

TEST_F(DeltaCodecTest, EmptyAndSingleSampleSeries) {
  load(kSeriesField);
  EXPECT_EQ(to_hex(codec_.encode(*series(std::vector<double>{}))), "0200");
  std::string one = codec_.encode(*series({99.9}));
  EXPECT_EQ(values(*codec_.decode(one)[0]), std::vector<double>{99.9});
}

TEST_F(DeltaCodecTest, RoundTripsWithinHalfAResolution) {
  load(kSeriesField);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> key(2, 98), step(-2, 2);
  for (int trial = 0; trial < 500; ++trial) {
    std::vector<double> in = {key(random)};
    for (int i = 0; i < 3; ++i) in.push_back(in[0] + step(random));
    std::vector<double> out = values(*codec_.decode(codec_.encode(*series(in)))[0]);
    ASSERT_EQ(out.size(), in.size());
    // Each value is within half a step of its own quantisation; deltas add
    // the key's quantisation error at most once more.
    EXPECT_NEAR(out[0], in[0], 0.05 + 1e-9);
    for (size_t i = 1; i < in.size(); ++i) {
      if (std::fabs(in[i] - out[0]) <= 2.0 - 0.05) {
        EXPECT_NEAR(out[i], in[i], 0.1 + 1e-9) << "trial " << trial << " element " << i;
      }
    }
  }
}

TEST_F(DeltaCodecTest, StrictModeRefusesDeltasOutOfRange) {
  load(kSeriesField);
  codec_.set_strict(true);
  try {
    codec_.encode(*series({10.0, 12.5}));
    FAIL() << "no error";
  } catch (const dccl::Error& e) {
    EXPECT_EQ(std::string(e.what()), "test.Series.v: 12.5 is more than max_delta 2 from the key 10");
  }
  EXPECT_THROW(codec_.encode(*series({1, 1, 1, 1, 1})), dccl::Error) << "too many repeats";
}

TEST_F(DeltaCodecTest, FloatFieldsWork) {
  load("  repeated float v = 1 [(dccl.field) = { codec: \"acomms.delta\" min: -10 max: 10 "
       "precision: 2 max_repeat: 3 [acomms.codecs.delta] { max_delta: 0.5 } }];");
  auto message = codec_.new_message("test.Series");
  const pb::FieldDescriptor* v = message->GetDescriptor()->FindFieldByName("v");
  for (float x : {1.25f, 1.5f, 0.75f}) message->GetReflection()->AddFloat(message.get(), v, x);
  auto decoded = codec_.decode(codec_.encode(*message));
  const pb::Reflection* r = decoded[0]->GetReflection();
  ASSERT_EQ(r->FieldSize(*decoded[0], v), 3);
  EXPECT_FLOAT_EQ(r->GetRepeatedFloat(*decoded[0], v, 0), 1.25f);
  EXPECT_FLOAT_EQ(r->GetRepeatedFloat(*decoded[0], v, 1), 1.5f);
  EXPECT_FLOAT_EQ(r->GetRepeatedFloat(*decoded[0], v, 2), 0.75f);
}

TEST_F(DeltaCodecTest, LoadTimeRulesNameTheField) {
  EXPECT_NE(load_error("  repeated double v = 1 [(dccl.field) = { codec: \"acomms.delta\" min: 0 "
                       "max: 1 max_repeat: 2 }];")
                .find("test.Series.v: codec acomms.delta needs (acomms.codecs.delta).max_delta"),
            std::string::npos);
  EXPECT_NE(load_error("  optional double v = 1 [(dccl.field) = { codec: \"acomms.delta\" min: 0 "
                       "max: 1 [acomms.codecs.delta] { max_delta: 1 } }];")
                .find("test.Series.v: codec acomms.delta is for repeated fields"),
            std::string::npos);
  EXPECT_NE(load_error("  repeated int32 v = 1 [(dccl.field) = { codec: \"acomms.delta\" min: 0 "
                       "max: 1 max_repeat: 2 [acomms.codecs.delta] { max_delta: 1 } }];")
                .find("test.Series.v: codec acomms.delta is for float and double fields"),
            std::string::npos);
  EXPECT_NE(load_error("  repeated double v = 1 [(dccl.field) = { codec: \"acomms.delta\" min: 0 "
                       "max: 1 max_repeat: 2 [acomms.codecs.delta] { max_delta: -1 } }];")
                .find("max_delta must be a positive number"),
            std::string::npos);
}

// A codec registered as name + codec_version wins over the plain name, as
// for the built-ins ("dccl.time" in a v4 message is "dccl.time4").
TEST_F(DeltaCodecTest, VersionSuffixedRegistrationIsPreferred) {
  bool suffixed_used = false;
  codec_.registry().add("acomms.delta4", [&](const dccl::FieldContext& ctx) {
    suffixed_used = true;
    dccl::CodecRegistry plain;
    register_delta_codec(plain);
    return (*plain.find(kDeltaCodecName, 4))(ctx);
  });
  load(kSeriesField);
  EXPECT_TRUE(suffixed_used);
  EXPECT_EQ(codec_.find_type("test.Series")->fields[0].codec, "acomms.delta4");
}

}  // namespace
}  // namespace acomms::codecs
