// `acommsctl dccl` as a user runs it: offline encode, decode and analyze
// against the conformance schema, with error lines and exit codes.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <vector>

#include "child_process.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;

const std::string kAcommsctl = ACOMMSCTL_BINARY;
const std::string kGvProto = ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto";
const std::string kVectors = ACOMMS_SHARED_DIR "/conformance/dccl/vectors.txt";

class AcommsctlDccl : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-ctl-dccl-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  RunResult dccl(const std::vector<std::string>& args, const std::string& input) {
    std::vector<std::string> all = {"dccl"};
    all.insert(all.end(), args.begin(), args.end());
    return run_with_input(kAcommsctl, all, (dir_ / "ctl").string(), input);
  }
  fs::path dir_;
};

TEST_F(AcommsctlDccl, EncodesEveryConformanceVector) {
  std::ifstream file(kVectors);
  std::string input, expected;
  for (std::string line; std::getline(file, line);) {
    if (line.empty()) continue;
    input += line.substr(0, line.rfind(" => ")) + "\n";
    expected += line.substr(line.rfind(" => ") + 4) + "\n";
  }
  RunResult result = dccl({"encode", "-f", kGvProto}, input);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out, expected);
}

TEST_F(AcommsctlDccl, EncodeReportsBadLinesAndFailsAtTheEnd) {
  RunResult result = dccl({"encode", "-f", kGvProto},
                          "|gv.Id1|\n"
                          "|gv.Nope| x: 1\n"
                          "gv.Id1\n"
                          "|gv.Num4| ri: banana\n"
                          "|gv.Id127|\n");
  EXPECT_EQ(result.exit_code, 1);
  std::vector<std::string> out = acomms::testing::lines_of(result.out);
  ASSERT_EQ(out.size(), 5u) << result.out;
  EXPECT_EQ(out[0], "02");
  EXPECT_EQ(out[1].rfind("error: line 2: ", 0), 0u) << out[1];
  EXPECT_NE(out[1].find("gv.Nope"), std::string::npos) << out[1];
  EXPECT_EQ(out[2].rfind("error: line 3: expected |type.Name|", 0), 0u) << out[2];
  EXPECT_EQ(out[3].rfind("error: line 4: gv.Num4 text format:", 0), 0u) << out[3];
  EXPECT_EQ(out[4], "fe");
}

// " => " starts the vector hex only outside string literals (issue 17):
// the first two lines are the same message ('=' written as \075 in the
// second), the third adds a vector tail.
TEST_F(AcommsctlDccl, ArrowInsideAStringIsPartOfTheString) {
  RunResult result = dccl({"encode", "-f", kGvProto},
                          "|gv.Str4| s: \"a => b\" r: \"abc\"\n"
                          "|gv.Str4| s: \"a \\075> b\" r: \"abc\"\n"
                          "|gv.Str4| s: \"a => b\" r: \"abc\" => 00\n");
  EXPECT_EQ(result.exit_code, 0) << result.out;
  std::vector<std::string> out = acomms::testing::lines_of(result.out);
  ASSERT_EQ(out.size(), 3u) << result.out;
  EXPECT_EQ(out[0], out[1]);
  EXPECT_EQ(out[0], out[2]);
  // id 8 bits; s: presence 1 + length 4 + 6 bytes; r: length 2 + 3 bytes; b: 1.
  EXPECT_EQ(out[0].size(), 2u * ((8 + 1 + 4 + 48 + 2 + 24 + 1 + 7) / 8)) << out[0];
}

TEST_F(AcommsctlDccl, StrictModeRefusesOutOfRangeValues) {
  RunResult lenient = dccl({"encode", "-f", kGvProto}, "|gv.Num4| ri: 101 ru: 0\n");
  EXPECT_EQ(lenient.exit_code, 0);
  EXPECT_EQ(lenient.out, "140000000000\n");
  RunResult strict = dccl({"encode", "--strict", "-f", kGvProto}, "|gv.Num4| ri: 101 ru: 0\n");
  EXPECT_EQ(strict.exit_code, 1);
  EXPECT_NE(strict.out.find("error: line 1: gv.Num4.ri"), std::string::npos) << strict.out;
}

TEST_F(AcommsctlDccl, DecodesConcatenatedMessagesAndReportsGarbage) {
  RunResult result = dccl({"decode", "-f", kGvProto},
                          "f834987170463213f8000000358c3801\n"
                          "02\n"
                          "zz\n"
                          "14\n");
  EXPECT_EQ(result.exit_code, 1);
  std::vector<std::string> out = acomms::testing::lines_of(result.out);
  ASSERT_EQ(out.size(), 5u) << result.out;
  EXPECT_EQ(out[0], "|gv.NavigationReport| x: 450 y: 550 z: -100 veh_class: AUV battery_ok: true");
  EXPECT_EQ(out[1], "|gv.NavigationReport| x: -10000 y: 10000 z: 0");
  EXPECT_EQ(out[2], "|gv.Id1|");
  EXPECT_EQ(out[3], "error: line 3: not a hex digit at position 1: 'z'");
  EXPECT_EQ(out[4].rfind("error: line 4: ", 0), 0u) << out[4];
  EXPECT_NE(out[4].find("truncated"), std::string::npos) << out[4];
}

TEST_F(AcommsctlDccl, OmitIdTypesDecodeWithANamedType) {
  RunResult without = dccl({"decode", "-f", kGvProto}, "aa\n");
  EXPECT_EQ(without.exit_code, 1);
  RunResult named = dccl({"decode", "-f", kGvProto, "--type", "gv.OmitId4"}, "aaab\n");
  EXPECT_EQ(named.exit_code, 0) << named.out;
  EXPECT_EQ(named.out, "|gv.OmitId4| v: 170\n|gv.OmitId4| v: 171\n");
}

TEST_F(AcommsctlDccl, PassphraseEncryptsAsTheSpecVectorSays) {
  RunResult encrypted = dccl(
      {"encode", "-f", kGvProto, "--passphrase", "my_passphrase!"},
      "|gv.NavigationReport| x: 450 y: 550 z: -100 veh_class: AUV battery_ok: true\n");
  EXPECT_EQ(encrypted.exit_code, 0) << encrypted.out;
  EXPECT_EQ(encrypted.out, "f8a02b71dfcb815f\n");
  RunResult decrypted =
      dccl({"decode", "-f", kGvProto, "--passphrase", "my_passphrase!"}, "f8a02b71dfcb815f\n");
  EXPECT_EQ(decrypted.out,
            "|gv.NavigationReport| x: 450 y: 550 z: -100 veh_class: AUV battery_ok: true\n");
}

TEST_F(AcommsctlDccl, AnalyzePrintsTheBitBudget) {
  RunResult result = dccl({"analyze", "-f", kGvProto, "--type", "gv.NavigationReport"}, "");
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("id:             124 (8 bits)"), std::string::npos) << result.out;
  // x and y: 20001 values at 0.1 -> 18 bits; z: 5001 values -> 13 bits.
  EXPECT_NE(result.out.find("  x                                _default4          body     18         0.1"),
            std::string::npos) << result.out;
  EXPECT_NE(result.out.find("  z                                _default4          body     13         1"),
            std::string::npos) << result.out;
  EXPECT_NE(result.out.find("body:  53 bits -> 7..7 byte(s)"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("encoded size: min 8, max 8 bytes (max_bytes 32)"), std::string::npos)
      << result.out;

  RunResult unknown = dccl({"analyze", "-f", kGvProto, "--type", "gv.Nope"}, "");
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.err.find("no DCCL type gv.Nope"), std::string::npos) << unknown.err;
}

TEST_F(AcommsctlDccl, BrokenSchemaIsOneClearError) {
  std::string bad = (dir_ / "bad.proto").string();
  std::ofstream(bad) << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\n"
                        "message Bad {\n  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 8 };\n"
                        "  required int32 x = 1;\n}\n";
  RunResult result = dccl({"encode", "-f", bad}, "|Bad| x: 1\n");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.err.find("Bad.x"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("min"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace acomms::testing
