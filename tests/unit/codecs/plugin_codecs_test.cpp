// Plugin codecs found by name (every folder under plugins/codecs registers
// itself) and configured per Codec: the arithmetic codec's models come from
// the settings each Codec is set up with, so two Codecs in one process may
// hold different models under the same name.

#include "dccl/plugin_codecs.h"

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "acomms/v1/config.pb.h"
#include "dccl/codec.h"
#include "dccl/hex.h"

namespace acomms::dccl {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

class PluginCodecsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-plugins-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    schema_ = (dir_ / "series.proto").string();
    std::ofstream(schema_) << "syntax = \"proto2\";\n"
                              "import \"dccl/option_extensions.proto\";\n"
                              "import \"dccl/arithmetic/protobuf/arithmetic_extensions.proto\";\n"
                              "package test;\n"
                              "message Series {\n"
                              "  option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 32 };\n"
                              "  repeated double value = 1 [(dccl.field) = { codec: \"dccl.arithmetic\" "
                              "max_repeat: 4 [arithmetic] { model: \"m\" } }];\n"
                              "}\n";
  }
  void TearDown() override { fs::remove_all(dir_); }

  static v1::DcclConfig settings(const std::string& text) {
    v1::DcclConfig config;
    EXPECT_TRUE(pb::TextFormat::ParseFromString(text, &config)) << text;
    return config;
  }
  static std::unique_ptr<pb::Message> series(const Codec& codec, const std::string& text) {
    auto message = codec.new_message("test.Series");
    EXPECT_TRUE(pb::TextFormat::ParseFromString(text, message.get())) << text;
    return message;
  }

  fs::path dir_;
  std::string schema_;
};

TEST_F(PluginCodecsTest, EveryCodecFolderRegistersItselfByName) {
  EXPECT_EQ(plugin_codec_names(), (std::vector<std::string>{"acomms.delta", "dccl.arithmetic"}));
  CodecRegistry registry;
  install_plugin_codecs(registry);
  EXPECT_TRUE(registry.contains("acomms.delta"));
  EXPECT_TRUE(registry.contains("dccl.arithmetic"));
}

// Both codecs are set up before either loads the schema: if the models were
// shared, the second set-up would replace the first one's model "m".
TEST_F(PluginCodecsTest, TwoCodecsHoldDifferentModelsOfTheSameName) {
  // The spec's vector model (value 0 likely), and the same symbols with the
  // frequencies swapped (value 1 likely).
  v1::DcclConfig likely_zero =
      settings("arithmetic_models { name: 'm' value_bound: [0, 1, 2] frequency: [5, 1] eof_frequency: 4 }");
  v1::DcclConfig likely_one =
      settings("arithmetic_models { name: 'm' value_bound: [0, 1, 2] frequency: [1, 5] eof_frequency: 4 }");
  Codec a, b;
  install_plugin_codecs(a.registry(), &likely_zero);
  install_plugin_codecs(b.registry(), &likely_one);
  a.load(schema_);
  b.load(schema_);

  const std::string values = "value: [0, 0, 0, 1]";
  std::string from_a = a.encode(*series(a, values));
  std::string from_b = b.encode(*series(b, values));
  EXPECT_EQ(to_hex(from_a), "020b") << "the spec's vector, with a's own model";
  EXPECT_NE(from_a, from_b);
  // Mostly zeros cost more under the model that expects ones.
  EXPECT_GT(from_b.size(), from_a.size());
  ASSERT_EQ(a.decode(from_a).size(), 1u);
  ASSERT_EQ(b.decode(from_b).size(), 1u);
  EXPECT_EQ(a.decode(from_a)[0]->ShortDebugString(), "value: 0 value: 0 value: 0 value: 1");
  EXPECT_EQ(b.decode(from_b)[0]->ShortDebugString(), "value: 0 value: 0 value: 0 value: 1");
}

TEST_F(PluginCodecsTest, WithoutSettingsTheArithmeticCodecHasNoModels) {
  Codec codec;
  install_plugin_codecs(codec.registry());
  try {
    codec.load(schema_);
    FAIL() << "loaded a field whose model nobody gave";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("arithmetic model \"m\" is not registered"), std::string::npos)
        << e.what();
  }
}

TEST_F(PluginCodecsTest, BadModelInTheSettingsNamesTheSettingsField) {
  v1::DcclConfig bad = settings("arithmetic_models { name: 'bad' value_bound: [0, 1] frequency: [1, 2] }");
  Codec codec;
  try {
    install_plugin_codecs(codec.registry(), &bad);
    FAIL() << "installed a model with mismatched bounds";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kSchema);
    EXPECT_EQ(std::string(e.what()).rfind("arithmetic_models: arithmetic model \"bad\"", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace acomms::dccl
