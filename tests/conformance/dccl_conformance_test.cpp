// DCCL conformance: every vector produced by the reference DCCL 4.2 encoder
// (shared/conformance/dccl/vectors.txt) must encode to exactly the same
// bytes and decode back to what the reference decoder returns.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "dccl/codec.h"
#include "dccl/hex.h"
#include "dccl/vector_line.h"

namespace {

namespace gp = google::protobuf;
using acomms::dccl::Codec;

const std::string kDir = std::string(ACOMMS_SHARED_DIR) + "/conformance/dccl";
// Clock for dccl.time decoding: an hour after the gv.Time4 vector's time.
constexpr double kNow = 1700000000.0 + 3600;

struct Vector {
  int line = 0;
  std::string type;
  std::string text;
  std::string hex;
};

std::vector<Vector> read_vectors() {
  std::vector<Vector> out;
  std::ifstream in(kDir + "/vectors.txt");
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] != '|') continue;
    acomms::dccl::VectorLine parsed = acomms::dccl::parse_vector_line(line);
    if (parsed.hex.empty()) continue;
    out.push_back(Vector{n, parsed.type, parsed.text, parsed.hex});
  }
  return out;
}

using acomms::dccl::from_hex;
using acomms::dccl::to_hex;

Codec& codec() {
  static Codec* c = [] {
    auto* codec = new Codec;
    codec->load(kDir + "/gv.proto", {ACOMMS_PROTO_DIR});
    codec->set_clock([] { return kNow; });
    return codec;
  }();
  return *c;
}

// What the reference decoder returns where it differs from the encoded
// message by more than quantisation, by hex. The first group is README.md's
// list; the second follows from spec rules the README does not repeat per
// vector (dccl.static decodes to static_value and omit fields are not sent;
// v2/v3 bytes are fixed-length and zero padded; repeats past max_repeat are
// dropped).
const std::map<std::string, std::string>& decoded_overrides() {
  static const std::map<std::string, std::string> m = {
      // README.md
      {"140000000000", "ri: -100 ru: 0"},
      {"2000", "m: 0"},
      {"1ae130b1b100", "s: \"\" r: \"abc\" b: \"\""},
      {"1c7098d85800000000", "r: \"abc\" b: \"\\0\\0\\0\\0\""},
      {"16003e00", "q: -1 t: -60 p: 1240 f: 0"},
      {"3c7f1c", "a: 0.07 b: 0.15 c: 0 d: 0.7"},
      // spec rules
      {"30c8", "s: \"hello\" v: 200"},
      {"1c8554c4c4f47498d8d800010000", "s: \"HELLO\" r: \"abc\" b: \"\\001\\002\\000\\000\""},
      {"1e0548454c4c4f036162630304000000", "s: \"HELLO\" r: \"abc\" b: \"\\001\\002\\000\\000\""},
      {"200c193207", "a: 1 a: 2 a: 3 a: 4 m: 1 m: 2 m: 3"},
  };
  return m;
}

// How far a decoded number may be from the encoded one: half the field's
// quantum, or for integers (whose negatives round toward zero) just under
// one quantum.
double tolerance(const gp::FieldDescriptor* f) {
  bool floating = f->cpp_type() == gp::FieldDescriptor::CPPTYPE_DOUBLE ||
                  f->cpp_type() == gp::FieldDescriptor::CPPTYPE_FLOAT;
  for (const acomms::dccl::TypeInfo* t : codec().types()) {
    for (const acomms::dccl::FieldInfo& fi : t->fields) {
      if (fi.field != f || fi.resolution <= 0) continue;
      return floating ? fi.resolution / 2 * (1 + 1e-9) + 1e-12 : fi.resolution - 0.5;
    }
  }
  return 0;
}

double numeric(const gp::Message& m, const gp::FieldDescriptor* f, int i) {
  const gp::Reflection* r = m.GetReflection();
  switch (f->cpp_type()) {
    case gp::FieldDescriptor::CPPTYPE_INT32: return i < 0 ? r->GetInt32(m, f) : r->GetRepeatedInt32(m, f, i);
    case gp::FieldDescriptor::CPPTYPE_INT64:
      return static_cast<double>(i < 0 ? r->GetInt64(m, f) : r->GetRepeatedInt64(m, f, i));
    case gp::FieldDescriptor::CPPTYPE_UINT32: return i < 0 ? r->GetUInt32(m, f) : r->GetRepeatedUInt32(m, f, i);
    case gp::FieldDescriptor::CPPTYPE_UINT64:
      return static_cast<double>(i < 0 ? r->GetUInt64(m, f) : r->GetRepeatedUInt64(m, f, i));
    case gp::FieldDescriptor::CPPTYPE_DOUBLE: return i < 0 ? r->GetDouble(m, f) : r->GetRepeatedDouble(m, f, i);
    case gp::FieldDescriptor::CPPTYPE_FLOAT: return i < 0 ? r->GetFloat(m, f) : r->GetRepeatedFloat(m, f, i);
    default: return 0;
  }
}

bool is_number(const gp::FieldDescriptor* f) {
  switch (f->cpp_type()) {
    case gp::FieldDescriptor::CPPTYPE_INT32:
    case gp::FieldDescriptor::CPPTYPE_INT64:
    case gp::FieldDescriptor::CPPTYPE_UINT32:
    case gp::FieldDescriptor::CPPTYPE_UINT64:
    case gp::FieldDescriptor::CPPTYPE_DOUBLE:
    case gp::FieldDescriptor::CPPTYPE_FLOAT: return true;
    default: return false;
  }
}

// Empty when equal: presence and sizes must match exactly, numbers within
// their field's quantisation, everything else exactly.
std::string diff(const gp::Message& want, const gp::Message& got, const std::string& prefix = "") {
  std::string out;
  const gp::Reflection* rw = want.GetReflection();
  const gp::Reflection* rg = got.GetReflection();
  const gp::Descriptor* d = want.GetDescriptor();
  for (int k = 0; k < d->field_count(); ++k) {
    const gp::FieldDescriptor* f = d->field(k);
    std::string name = prefix + f->name();
    int n = 1;
    if (f->is_repeated()) {
      n = rw->FieldSize(want, f);
      if (n != rg->FieldSize(got, f)) {
        out += name + ": " + std::to_string(n) + " vs " + std::to_string(rg->FieldSize(got, f)) + " elements; ";
        continue;
      }
    } else {
      if (rw->HasField(want, f) != rg->HasField(got, f)) {
        out += name + ": presence differs; ";
        continue;
      }
      if (!rw->HasField(want, f)) continue;
    }
    for (int i = 0; i < n; ++i) {
      int idx = f->is_repeated() ? i : -1;
      std::string at = f->is_repeated() ? name + "[" + std::to_string(i) + "]" : name;
      if (f->cpp_type() == gp::FieldDescriptor::CPPTYPE_MESSAGE) {
        const gp::Message& a = idx < 0 ? rw->GetMessage(want, f) : rw->GetRepeatedMessage(want, f, idx);
        const gp::Message& b = idx < 0 ? rg->GetMessage(got, f) : rg->GetRepeatedMessage(got, f, idx);
        out += diff(a, b, at + ".");
      } else if (is_number(f)) {
        double a = numeric(want, f, idx), b = numeric(got, f, idx);
        if (!(std::fabs(a - b) <= tolerance(f))) {
          std::ostringstream s;
          s.precision(17);
          s << at << ": want " << a << " got " << b << "; ";
          out += s.str();
        }
      } else {
        std::string a, b;
        gp::TextFormat::PrintFieldValueToString(want, f, idx, &a);
        gp::TextFormat::PrintFieldValueToString(got, f, idx, &b);
        if (a != b) out += at + ": want " + a + " got " + b + "; ";
      }
    }
  }
  return out;
}

void PrintTo(const Vector& v, std::ostream* os) { *os << "line " << v.line << " |" << v.type << "| " << v.text; }

class Conformance : public ::testing::TestWithParam<Vector> {};

TEST_P(Conformance, EncodesAndDecodesLikeReference) {
  const Vector& v = GetParam();
  auto msg = codec().new_message(v.type);
  ASSERT_TRUE(gp::TextFormat::ParseFromString(v.text, msg.get())) << v.text;

  std::string encoded = codec().encode(*msg);
  EXPECT_EQ(to_hex(encoded), v.hex) << "line " << v.line << ": " << v.type << " " << v.text;

  std::unique_ptr<gp::Message> decoded;
  const acomms::dccl::TypeInfo* info = codec().find_type(v.type);
  ASSERT_NE(info, nullptr);
  if (info->omit_id) {
    size_t used = 0;
    decoded = codec().decode_as(v.type, from_hex(v.hex), &used);
    EXPECT_EQ(used, v.hex.size() / 2);
  } else {
    auto all = codec().decode(from_hex(v.hex));
    ASSERT_EQ(all.size(), 1u);
    decoded = std::move(all[0]);
  }
  ASSERT_EQ(decoded->GetDescriptor()->full_name(), v.type);

  auto want = codec().new_message(v.type);
  auto it = decoded_overrides().find(v.hex);
  ASSERT_TRUE(gp::TextFormat::ParseFromString(it == decoded_overrides().end() ? v.text : it->second, want.get()));
  EXPECT_EQ(diff(*want, *decoded), "") << "line " << v.line << ": decoded " << decoded->ShortDebugString();

  // What the decoder returns encodes to the same bytes again.
  EXPECT_EQ(to_hex(codec().encode(*decoded)), v.hex) << "line " << v.line;
}

std::string vector_name(const ::testing::TestParamInfo<Vector>& info) {
  std::string name = "line" + std::to_string(info.param.line) + "_" + info.param.type;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Vectors, Conformance, ::testing::ValuesIn(read_vectors()), vector_name);

TEST(ConformanceFile, HasAllVectors) { EXPECT_EQ(read_vectors().size(), 59u); }

TEST(ConformanceExtra, TwoNavigationReportsBackToBack) {
  auto all = codec().decode(from_hex("f834987170463213f8000000358c3801"));
  ASSERT_EQ(all.size(), 2u);
  auto first = codec().new_message("gv.NavigationReport");
  auto second = codec().new_message("gv.NavigationReport");
  ASSERT_TRUE(gp::TextFormat::ParseFromString("x: 450 y: 550 z: -100 veh_class: AUV battery_ok: true", first.get()));
  ASSERT_TRUE(gp::TextFormat::ParseFromString("x: -10000 y: 10000 z: 0", second.get()));
  EXPECT_EQ(diff(*first, *all[0]), "") << all[0]->ShortDebugString();
  EXPECT_EQ(diff(*second, *all[1]), "") << all[1]->ShortDebugString();
}

TEST(ConformanceExtra, EncryptionVector) {
  Codec c;
  c.load(kDir + "/gv.proto", {ACOMMS_PROTO_DIR});
  c.set_crypto("my_passphrase!");
  auto msg = c.new_message("gv.NavigationReport");
  ASSERT_TRUE(gp::TextFormat::ParseFromString("x: 450 y: 550 z: -100 veh_class: AUV battery_ok: true", msg.get()));
  EXPECT_EQ(to_hex(c.encode(*msg)), "f8a02b71dfcb815f");
  auto back = c.decode(from_hex("f8a02b71dfcb815f"));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(diff(*msg, *back[0]), "") << back[0]->ShortDebugString();
}

}  // namespace
