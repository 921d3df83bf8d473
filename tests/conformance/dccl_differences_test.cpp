// DCCL conformance, second file: every difference once found between
// acommsd and the reference DCCL 4.2 (shared/conformance/dccl/differences.txt,
// schemas gv.proto and probe.proto). A fielded vehicle runs the reference,
// so in lenient mode (the default) each entry must give exactly the
// reference's bytes, and decoding those bytes must give exactly the message
// the reference decodes, with the receiver clock the file states. An
// `error` entry is a type the reference refuses: it must be refused here
// too, for the stated reason, while the rest of its file loads.
//
// The file is read at run time: nothing of it is copied here.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "dccl/codec.h"
#include "dccl/hex.h"
#include "dccl/vector_line.h"

namespace {

namespace gp = google::protobuf;
using acomms::dccl::Codec;

const std::string kDir = std::string(ACOMMS_SHARED_DIR) + "/conformance/dccl";
const std::string kFile = kDir + "/differences.txt";

struct Entry {
  int line = 0;
  std::string cls;      // "FLOAT", "TIMEUS", ...
  std::string type;     // input
  std::string text;
  std::string hex;      // "=>" (empty for an error entry)
  std::string error;    // "=> error: ..."
  std::string decoded;  // "<=" line: |type| text
};

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<Entry> read_entries() {
  std::vector<Entry> out;
  std::ifstream in(kFile);
  std::string cls;
  int n = 0;
  for (std::string raw; std::getline(in, raw);) {
    ++n;
    std::string line = trim(raw);
    if (line.rfind("## ", 0) == 0) {
      cls = line.substr(3, line.find(':') - 3);
    } else if (!line.empty() && line[0] == '|') {
      acomms::dccl::VectorLine v = acomms::dccl::parse_vector_line(line);
      out.push_back(Entry{n, cls, v.type, v.text, "", "", ""});
    } else if (line.rfind("=> ", 0) == 0 && !out.empty()) {
      std::string rhs = line.substr(3);
      if (rhs.rfind("error: ", 0) == 0) {
        out.back().error = rhs.substr(7);
      } else {
        out.back().hex = rhs;
      }
    } else if (line.rfind("<= ", 0) == 0 && !out.empty()) {
      out.back().decoded = line.substr(3);
    }
  }
  return out;
}

// "the clock at 2026-11-23 20:00:00 UTC (1795464000)" in the file's header.
double stated_clock() {
  std::ifstream in(kFile);
  std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::smatch m;
  if (!std::regex_search(all, m, std::regex(R"(clock at [^(]*\((\d+)\))"))) return -1;
  return std::stod(m[1].str());
}

Codec& codec() {
  static Codec* c = [] {
    auto* codec = new Codec;
    codec->load(kDir + "/gv.proto", {ACOMMS_PROTO_DIR});
    codec->load(kDir + "/probe.proto", {ACOMMS_PROTO_DIR});
    const double now = stated_clock();
    codec->set_clock([now] { return now; });
    return codec;
  }();
  return *c;
}

void PrintTo(const Entry& e, std::ostream* os) {
  *os << "line " << e.line << " " << e.cls << " |" << e.type << "| " << e.text;
}

class Differences : public ::testing::TestWithParam<Entry> {};

TEST_P(Differences, EncodesAndDecodesExactlyLikeReference) {
  const Entry& e = GetParam();
  ASSERT_TRUE(e.error.empty());
  ASSERT_FALSE(e.hex.empty()) << "entry without '=>'";
  auto msg = codec().new_message(e.type);
  ASSERT_TRUE(gp::TextFormat::ParseFromString(e.text, msg.get())) << e.text;
  EXPECT_EQ(acomms::dccl::to_hex(codec().encode(*msg)), e.hex);

  ASSERT_FALSE(e.decoded.empty()) << "entry without '<='";
  acomms::dccl::VectorLine want_line = acomms::dccl::parse_vector_line(e.decoded);
  auto want = codec().new_message(want_line.type);
  // The reference's decoding may leave required fields unset.
  gp::TextFormat::Parser parser;
  parser.AllowPartialMessage(true);
  ASSERT_TRUE(parser.ParseFromString(want_line.text, want.get())) << want_line.text;
  auto all = codec().decode(acomms::dccl::from_hex(e.hex));
  ASSERT_EQ(all.size(), 1u);
  EXPECT_TRUE(gp::util::MessageDifferencer::Equals(*want, *all[0]))
      << "want " << want->ShortDebugString() << "\n got " << all[0]->ShortDebugString();
}

class RefusedTypes : public ::testing::TestWithParam<Entry> {};

TEST_P(RefusedTypes, AreRefusedForTheStatedReasonWhileTheirFileLoads) {
  const Entry& e = GetParam();
  ASSERT_FALSE(e.error.empty());
  EXPECT_EQ(codec().find_type(e.type), nullptr);
  try {
    codec().new_message(e.type);
    ADD_FAILURE() << e.type << " was not refused";
  } catch (const acomms::dccl::Error& err) {
    EXPECT_NE(std::string(err.what()).find(e.error), std::string::npos) << err.what();
  }
  // The type is listed with its reason; the file's other types loaded.
  EXPECT_FALSE(codec().refusal(e.type).empty());
  EXPECT_NE(codec().find_type("probe.Statics"), nullptr);
}

std::string entry_name(const ::testing::TestParamInfo<Entry>& info) {
  std::string name = info.param.cls + "_line" + std::to_string(info.param.line);
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

std::vector<Entry> encodable() {
  std::vector<Entry> out;
  for (const Entry& e : read_entries()) {
    if (e.error.empty()) out.push_back(e);
  }
  return out;
}
std::vector<Entry> refused() {
  std::vector<Entry> out;
  for (const Entry& e : read_entries()) {
    if (!e.error.empty()) out.push_back(e);
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(Entries, Differences, ::testing::ValuesIn(encodable()), entry_name);
INSTANTIATE_TEST_SUITE_P(Entries, RefusedTypes, ::testing::ValuesIn(refused()), entry_name);

TEST(DifferencesFile, StatesTheReceiverClock) { EXPECT_EQ(stated_clock(), 1795464000.0); }

TEST(DifferencesFile, HasEveryClassOfDifference) {
  std::vector<std::string> classes;
  for (const Entry& e : read_entries()) {
    if (classes.empty() || classes.back() != e.cls) classes.push_back(e.cls);
  }
  EXPECT_EQ(classes.size(), 14u);
  EXPECT_EQ(read_entries().size(), 33u);
}

}  // namespace
