// The daemon's codec from config: definitions load, encryption and its
// exempt ids follow the config, and problems are start-up errors.

#include "node/codec_setup.h"

#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/config_error.h"
#include "core/config_loader.h"
#include "dccl/hex.h"

namespace acomms::node {
namespace {

namespace fs = std::filesystem;
const std::string kGvProto = ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto";

std::string encode_nav(const dccl::Codec& codec) {
  auto message = codec.new_message("gv.NavigationReport");
  google::protobuf::TextFormat::ParseFromString("x: 450 y: 550 z: -100 veh_class: AUV battery_ok: true",
                                                message.get());
  return dccl::to_hex(codec.encode(*message));
}

v1::DcclConfig dccl_config(const std::string& text) {
  return core::parse_config("dccl { " + text + " }", "test.conf").dccl();
}

TEST(CodecSetup, LoadsTheConfiguredFiles) {
  auto codec = make_codec(dccl_config("proto_files: \"" + kGvProto + "\""));
  EXPECT_NE(codec->find_type("gv.NavigationReport"), nullptr);
  EXPECT_EQ(encode_nav(*codec), "f834987170463213");
}

// probe.proto holds a type the reference DCCL refuses (dccl.static on an
// enum): the daemon still starts, with the file's other types, and says so.
TEST(CodecSetup, ARefusedTypeIsReportedAtStartAndTheRestOfItsFileLoads) {
  std::ostringstream log;
  auto previous = spdlog::default_logger();
  spdlog::set_default_logger(
      std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(log)));
  std::unique_ptr<dccl::Codec> codec;
  EXPECT_NO_THROW(codec = make_codec(dccl_config("proto_files: \"" ACOMMS_SHARED_DIR
                                                 "/conformance/dccl/probe.proto\"")));
  spdlog::set_default_logger(previous);
  ASSERT_NE(codec, nullptr);
  EXPECT_NE(codec->find_type("probe.Statics"), nullptr);
  EXPECT_EQ(codec->find_type("probe.StaticEnum"), nullptr);
  EXPECT_NE(log.str().find("type probe.StaticEnum refused: probe.StaticEnum.e: dccl.static does not support enum"),
            std::string::npos)
      << log.str();
}

TEST(CodecSetup, PassphraseEncryptsAsTheSpecVector) {
  auto codec = make_codec(dccl_config("proto_files: \"" + kGvProto + "\" passphrase: \"my_passphrase!\""));
  EXPECT_EQ(encode_nav(*codec), "f8a02b71dfcb815f");
}

TEST(CodecSetup, ExemptIdsStayInClear) {
  auto codec = make_codec(dccl_config("proto_files: \"" + kGvProto +
                                      "\" passphrase: \"my_passphrase!\" crypto_exempt_ids: 124"));
  EXPECT_EQ(encode_nav(*codec), "f834987170463213");
}

TEST(CodecSetup, PassphraseFileLosesItsTrailingNewline) {
  fs::path file = fs::temp_directory_path() / ("acomms-pass-" + std::to_string(::getpid()));
  std::ofstream(file) << "my_passphrase!\n";
  auto codec = make_codec(
      dccl_config("proto_files: \"" + kGvProto + "\" passphrase_file: \"" + file.string() + "\""));
  EXPECT_EQ(encode_nav(*codec), "f8a02b71dfcb815f");
  fs::remove(file);
  try {
    make_codec(dccl_config("passphrase_file: \"" + file.string() + "\""));
    FAIL() << "no error for a missing passphrase file";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "dccl.passphrase_file " + file.string() + ": cannot read");
  }
}

TEST(CodecSetup, StrictComesFromConfig) {
  auto codec = make_codec(dccl_config("proto_files: \"" + kGvProto + "\" strict: true"));
  auto message = codec->new_message("gv.Num4");
  google::protobuf::TextFormat::ParseFromString("ri: 101 ru: 0", message.get());
  EXPECT_THROW(codec->encode(*message), dccl::Error);
}

TEST(CodecSetup, BrokenDefinitionsNameTheFileAndField) {
  fs::path file = fs::temp_directory_path() / ("acomms-bad-" + std::to_string(::getpid()) + ".proto");
  std::ofstream(file) << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\n"
                         "message Bad {\n  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 8 };\n"
                         "  required int32 x = 1;\n}\n";
  try {
    make_codec(dccl_config("proto_files: \"" + file.string() + "\""));
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    std::string what = e.what();
    EXPECT_EQ(what.rfind("dccl definitions " + file.string() + ":\n", 0), 0u) << what;
    EXPECT_NE(what.find("Bad.x"), std::string::npos) << what;
  }
  fs::remove(file);
}

// Position telemetry's ids (110, 111) are reserved: the daemon loads its
// types first, so a file whose type claims one is refused at load (a
// start-up error, as any clash of ids), naming both types.
TEST(CodecSetup, AUserTypeClaimingATelemetryIdIsRefusedNamingBoth) {
  fs::path file = fs::temp_directory_path() / ("acomms-clash-" + std::to_string(::getpid()) + ".proto");
  std::ofstream(file) << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage mine;\n"
                         "message Clash {\n  option (dccl.msg) = { codec_version: 4 id: 110 max_bytes: 8 };\n"
                         "  optional int32 x = 1 [(dccl.field) = { min: 0 max: 10 }];\n}\n";
  try {
    make_codec(dccl_config("proto_files: \"" + file.string() + "\""));
    ADD_FAILURE() << "a type claiming telemetry's id 110 loaded";
  } catch (const std::runtime_error& e) {
    std::string what = e.what();
    EXPECT_EQ(what.rfind("dccl definitions " + file.string() + ":\n", 0), 0u) << what;
    EXPECT_NE(what.find("mine.Clash: DCCL id 110 is already used by acomms.telemetry.PositionFull"),
              std::string::npos)
        << what;
  }
  fs::remove(file);
}

// The arithmetic codec's model comes from config; the spec vector: values
// [0,0,0,1] with this model encode to 020b.
TEST(CodecSetup, ArithmeticModelsComeFromConfig) {
  fs::path file = fs::temp_directory_path() / ("acomms-arith-" + std::to_string(::getpid()) + ".proto");
  std::ofstream(file) << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\n"
                         "import \"dccl/arithmetic/protobuf/arithmetic_extensions.proto\";\n"
                         "message Arith {\n  option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 32 };\n"
                         "  repeated double value = 1 [(dccl.field) = { codec: \"dccl.arithmetic\" max_repeat: 4 "
                         "[arithmetic] { model: \"config_model\" } }];\n}\n";
  auto codec = make_codec(dccl_config(
      "arithmetic_models { name: \"config_model\" eof_frequency: 4 value_bound: [0, 1, 2] "
      "frequency: [5, 1] out_of_range_frequency: 0 } proto_files: \"" + file.string() + "\""));
  auto message = codec->new_message("Arith");
  google::protobuf::TextFormat::ParseFromString("value: [0, 0, 0, 1]", message.get());
  EXPECT_EQ(dccl::to_hex(codec->encode(*message)), "020b");
  fs::remove(file);

  try {
    make_codec(dccl_config("arithmetic_models { name: \"bad\" value_bound: [0, 1] frequency: [1, 2] }"));
    FAIL() << "no error for a model with mismatched bounds";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("dccl.arithmetic_models: arithmetic model \"bad\"", 0), 0u) << e.what();
  }
}

TEST(CodecSetup, ConfigRulesAreLocated) {
  try {
    core::parse_config("dccl {\n  passphrase: \"a\"\n  passphrase_file: \"/b\"\n}\n", "c.conf");
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.field(), "dccl.passphrase_file");
  }
  try {
    core::parse_config("dccl {\n  crypto_exempt_ids: 1\n  crypto_exempt_ids: 40000\n}", "c.conf");
    FAIL() << "no error";
  } catch (const core::ConfigError& e) {
    EXPECT_EQ(e.field(), "dccl.crypto_exempt_ids");
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(e.problem().find("40000 is not a DCCL id"), std::string::npos);
  }
}

}  // namespace
}  // namespace acomms::node
