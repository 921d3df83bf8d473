// The arithmetic codec plugin ("dccl.arithmetic"): the reference vector,
// exact bit consumption (fields and messages after an arithmetic field still
// decode), random round trips over static and adaptive models, out-of-range
// values, strict mode, load-time errors, truncated input and the model
// registry.

#include "arithmetic/arithmetic_codec.h"

#include <google/protobuf/compiler/importer.h>
#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "dccl/arithmetic_coder.h"
#include "dccl/codec.h"
#include "dccl/hex.h"
#include "acomms/v1/config.pb.h"
#include "dccl/plugin_codecs.h"

namespace acomms::codecs {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;
namespace arith = dccl::arith;

using dccl::from_hex;
using dccl::to_hex;

ArithmeticModel make_model(const std::string& name, std::vector<double> bounds, std::vector<uint32_t> freq,
                           uint32_t eof = 1, uint32_t out_of_range = 0, bool adaptive = false) {
  ArithmeticModel m;
  m.name = name;
  m.value_bound = std::move(bounds);
  m.frequency = std::move(freq);
  m.eof_frequency = eof;
  m.out_of_range_frequency = out_of_range;
  m.is_adaptive = adaptive;
  return m;
}

// The model of the spec's vector (Howard & Vitter's example): EOF 0.4,
// value 0 ("b") 0.5, value 1 0.1.
ArithmeticModel spec_model() { return make_model("model", {0, 1, 2}, {5, 1}, 4, 0); }

class ArithmeticCodecTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-arith-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    models_ = std::make_shared<ArithmeticModels>();
    register_arithmetic_codec(codec_.registry(), models_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Writes a .proto with the arithmetic import and `body` (messages).
  std::string write_proto(const std::string& body) {
    std::string path = (dir_ / ("arith" + std::to_string(++files_) + ".proto")).string();
    std::ofstream(path) << "syntax = \"proto2\";\n"
                           "import \"dccl/option_extensions.proto\";\n"
                           "import \"dccl/arithmetic/protobuf/arithmetic_extensions.proto\";\n"
                           "package test;\n"
                        << body << "\n";
    return path;
  }
  // Message test.Series (id 1, v4) holding `fields`.
  static std::string series(const std::string& fields, int id = 1) {
    return "message Series" + std::to_string(id) + " {\n  option (dccl.msg) = { codec_version: 4 id: " +
           std::to_string(id) + " max_bytes: 200 };\n" + fields + "\n}\n";
  }
  static std::string field(const std::string& label_type, const std::string& name, int number,
                           const std::string& model, int max_repeat = 0, const std::string& extra = "") {
    std::string o = "  " + label_type + " " + name + " = " + std::to_string(number) +
                    " [(dccl.field).codec = \"dccl.arithmetic\", (dccl.field).(arithmetic).model = \"" + model +
                    "\"";
    if (max_repeat > 0) o += ", (dccl.field).max_repeat = " + std::to_string(max_repeat);
    return o + extra + "];\n";
  }
  void load(const std::string& body) { codec_.load(write_proto(body)); }
  std::string load_error(const std::string& body) {
    dccl::Codec codec;
    register_arithmetic_codec(codec.registry(), models_);
    try {
      codec.load(write_proto(body));
    } catch (const dccl::Error& e) {
      EXPECT_EQ(e.kind(), dccl::Error::Kind::kSchema);
      return e.what();
    }
    ADD_FAILURE() << "loaded without error";
    return "";
  }

  std::unique_ptr<pb::Message> message(const std::string& type, const std::string& text) {
    auto m = codec_.new_message(type);
    EXPECT_TRUE(pb::TextFormat::ParseFromString(text, m.get())) << text;
    return m;
  }
  static std::vector<double> doubles(const pb::Message& m, const std::string& name) {
    const pb::FieldDescriptor* f = m.GetDescriptor()->FindFieldByName(name);
    std::vector<double> out;
    for (int i = 0; i < m.GetReflection()->FieldSize(m, f); ++i) {
      out.push_back(m.GetReflection()->GetRepeatedDouble(m, f, i));
    }
    return out;
  }
  std::string decode_text(const std::string& bytes) {
    auto decoded = codec_.decode(bytes);
    EXPECT_EQ(decoded.size(), 1u);
    return decoded.empty() ? "" : decoded[0]->ShortDebugString();
  }

  fs::path dir_;
  int files_ = 0;
  std::shared_ptr<ArithmeticModels> models_;
  dccl::Codec codec_;
};

// ---------------------------------------------------------------- the vector

TEST_F(ArithmeticCodecTest, SpecVector) {
  models_->add(spec_model());
  load(series(field("repeated double", "value", 1, "model", 4)));
  auto in = message("test.Series1", "value: [0, 0, 0, 1]");
  std::string bytes = codec_.encode(*in);
  EXPECT_EQ(to_hex(bytes), "020b");
  EXPECT_EQ(doubles(*codec_.decode(bytes)[0], "value"), (std::vector<double>{0, 0, 0, 1}));
}

// The coder itself: bits 1101000 (Howard & Vitter's 0.1101 plus the zeros
// that pin [0.8125, 0.825)), first coder bit first in the stream.
TEST(ArithmeticCoderTest, SpecVectorBitsAndOrder) {
  arith::FrequencyTable table({0, 4, 5, 1});  // out-of-range, EOF, value 0, value 1
  std::string out;
  dccl::BitWriter w(&out);
  arith::Encoder e(w);
  for (size_t s : {2, 2, 2, 3}) e.encode(table, s);
  e.finish();
  EXPECT_EQ(w.position(), 7u);
  EXPECT_EQ(to_hex(out), "0b");
}

// Whatever bits follow, the decoder stops on the last bit the encoder wrote
// and gets the symbols back: random alphabets (zero frequencies and very
// unlikely symbols included), random offsets and random trailing bits.
TEST(ArithmeticCoderTest, DecoderStopsOnTheLastBitWritten) {
  std::mt19937 random(1);
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<uint32_t> freq(1 + random() % 6);
    for (uint32_t& f : freq) f = random() % (trial % 3 == 0 ? 3 : trial % 3 == 1 ? 1000 : 1u << 20);
    freq[random() % freq.size()] += 1;
    arith::FrequencyTable table(freq);
    std::vector<size_t> symbols(random() % 20);
    for (size_t& s : symbols) {
      do s = random() % freq.size();
      while (table.frequency(s) == 0);
    }
    std::string out;
    dccl::BitWriter w(&out);
    const unsigned offset = random() % 8;
    w.write(random(), offset);
    arith::Encoder encoder(w);
    for (size_t s : symbols) encoder.encode(table, s);
    encoder.finish();
    const uint64_t end = w.position();
    w.write(random(), 16);

    dccl::BitReader r(out, offset);
    arith::Decoder decoder(r);
    for (size_t i = 0; i < symbols.size(); ++i) ASSERT_EQ(decoder.decode(table), symbols[i]) << "trial " << trial;
    ASSERT_EQ(r.position(), end) << "trial " << trial;
  }
}

// A list shorter than max_repeat ends with EOF; a full one does not need it.
TEST_F(ArithmeticCodecTest, EofOnlyForShortLists) {
  models_->add(spec_model());
  load(series(field("repeated double", "value", 1, "model", 4)));
  for (const char* text :
       {"", "value: 0", "value: 1 value: 1", "value: 0 value: 0 value: 0", "value: 1 value: 1 value: 1 value: 1"}) {
    std::string bytes = codec_.encode(*message("test.Series1", text));
    EXPECT_EQ(decode_text(bytes), text) << to_hex(bytes);
  }
  // Only EOF, [0, 0.4): 2 bits, "00" pins [0, 0.25).
  EXPECT_EQ(to_hex(codec_.encode(*message("test.Series1", ""))), "0200");
}

// The reference's own edge cases: four very likely symbols fit in one bit,
// four unlikely ones (p = 0.02 each) need 23 or 24 bits.
TEST_F(ArithmeticCodecTest, LikelySymbolsCostLessThanABit) {
  models_->add(make_model("enum", {1, 2, 3, 4}, {2, 3, 85}, 10, 0));
  load("enum E { A = 1; B = 2; C = 3; }\n" + series(field("repeated E", "value", 1, "enum", 4)));
  EXPECT_EQ(to_hex(codec_.encode(*message("test.Series1", "value: [C, C, C, C]"))), "0201");
  std::string rare = codec_.encode(*message("test.Series1", "value: [A, A, A, A]"));
  EXPECT_EQ(rare.size(), 1u + 3u) << to_hex(rare);
  EXPECT_EQ(decode_text(rare), "value: A value: A value: A value: A");
}

// ------------------------------------------------------- exact consumption

// Random lists over several models. Each message carries the arithmetic field
// between two other fields, and messages are decoded back to back from one
// buffer: both only work if the decoder stops on the encoder's last bit.
TEST_F(ArithmeticCodecTest, RandomRoundTripsConsumeExactlyTheirBits) {
  struct Case {
    ArithmeticModel model;
    int max_repeat;
  };
  std::vector<Case> cases = {
      {spec_model(), 4},
      {make_model("skewed", {-5, -1, 0, 0.5, 2, 100}, {1000, 1, 300, 7, 2}, 3, 1), 12},
      {make_model("flat", {0, 1, 2, 3, 4, 5, 6, 7, 8}, {1, 1, 1, 1, 1, 1, 1, 1}, 1, 1), 20},
      {make_model("adaptive", {0, 1, 2}, {1, 1}, 1, 1, true), 30},
      {make_model("adaptive_skewed", {0, 10, 20, 30}, {50, 5, 1}, 2, 0, true), 16},
      {make_model("certain", {0, 1}, {1}, 0, 0), 5},  // one symbol, no EOF: 0 bits
  };
  // A big model with rough random frequencies.
  {
    std::mt19937 random(3);
    ArithmeticModel big = make_model("big", {}, {}, 17, 3);
    for (int i = 0; i <= 300; ++i) big.value_bound.push_back(i * 0.5);
    for (int i = 0; i < 300; ++i) big.frequency.push_back(1 + random() % 5000);
    cases.push_back({big, 40});
  }
  std::mt19937 random(11);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.model.name);
    dccl::Codec codec;
    register_arithmetic_codec(codec.registry(), models_);
    models_->add(c.model);
    std::string body =
        "  required uint32 before = 1 [(dccl.field) = { min: 0 max: 7 }];\n" +
        field("repeated double", "value", 2, c.model.name, c.max_repeat) +
        "  required uint32 after = 3 [(dccl.field) = { min: 0 max: 1000 }];\n" +
        field("repeated double", "again", 4, c.model.name, c.max_repeat);
    codec.load(write_proto(series(body, 1) + series(field("repeated double", "v", 1, c.model.name, 3), 2)));
    const dccl::TypeInfo* info = codec.find_type("test.Series1");
    ASSERT_NE(info, nullptr);

    const auto& m = c.model;
    std::uniform_int_distribution<size_t> pick(0, m.frequency.size() - 1);
    for (int trial = 0; trial < 300; ++trial) {
      std::string frame;
      std::vector<std::unique_ptr<pb::Message>> sent;
      for (int k = 0; k < 3; ++k) {
        auto msg = codec.new_message(k == 1 ? "test.Series2" : "test.Series1");
        const pb::Reflection* r = msg->GetReflection();
        const pb::Descriptor* d = msg->GetDescriptor();
        auto fill = [&](const char* name, int max) {
          const pb::FieldDescriptor* f = d->FindFieldByName(name);
          // Lists full or short; every value a symbol's lower bound so it
          // decodes unchanged (the certain model must always be full).
          int n = m.eof_frequency == 0 ? max : static_cast<int>(random() % (max + 1));
          for (int i = 0; i < n; ++i) r->AddDouble(msg.get(), f, m.value_bound[pick(random)]);
        };
        if (k == 1) {
          fill("v", 3);
        } else {
          r->SetUInt32(msg.get(), d->FindFieldByName("before"), random() % 8);
          r->SetUInt32(msg.get(), d->FindFieldByName("after"), random() % 1001);
          fill("value", c.max_repeat);
          fill("again", c.max_repeat);
        }
        std::string bytes = codec.encode(*msg);
        if (k != 1) {
          ASSERT_LE(bytes.size(), 1 + (info->body.max + 7) / 8) << "size bound too small";
        }
        frame += bytes;
        sent.push_back(std::move(msg));
      }
      auto decoded = codec.decode(frame);
      ASSERT_EQ(decoded.size(), sent.size()) << to_hex(frame);
      for (size_t k = 0; k < sent.size(); ++k) {
        ASSERT_EQ(decoded[k]->ShortDebugString(), sent[k]->ShortDebugString()) << "trial " << trial;
      }
    }
  }
}

// Out-of-range symbols keep their place in the list: NaN for doubles.
TEST_F(ArithmeticCodecTest, OutOfRangeSymbol) {
  models_->add(make_model("oor", {0, 1, 2}, {5, 1}, 4, 2));
  load(series(field("repeated double", "value", 1, "oor", 4)) +
       series(field("repeated int32", "value", 1, "oor", 4), 2));
  std::vector<double> out =
      doubles(*codec_.decode(codec_.encode(*message("test.Series1", "value: [1, -3, 2, 0.5]")))[0], "value");
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0], 1);
  EXPECT_TRUE(std::isnan(out[1]));
  EXPECT_TRUE(std::isnan(out[2])) << "the upper bound is outside";
  EXPECT_EQ(out[3], 0) << "decodes as the symbol's lower bound";
  // Integer types have no NaN: the element is left out.
  EXPECT_EQ(decode_text(codec_.encode(*message("test.Series2", "value: [1, 7, 0]"))), "value: 1 value: 0");
}

// With out_of_range_frequency 0 a value outside the bounds cannot be sent:
// the list ends before it (reference behaviour), or strict mode refuses.
TEST_F(ArithmeticCodecTest, OutOfRangeWithoutSymbol) {
  models_->add(spec_model());
  load(series(field("repeated double", "value", 1, "model", 4)));
  EXPECT_EQ(decode_text(codec_.encode(*message("test.Series1", "value: [1, 0, 5, 0]"))), "value: 1 value: 0");
  EXPECT_EQ(decode_text(codec_.encode(*message("test.Series1", "value: [nan, 0]"))), "");
  codec_.set_strict(true);
  try {
    codec_.encode(*message("test.Series1", "value: [1, 0, 5, 0]"));
    FAIL() << "no error";
  } catch (const dccl::Error& e) {
    EXPECT_EQ(e.kind(), dccl::Error::Kind::kEncode);
    EXPECT_EQ(std::string(e.what()), "test.Series1.value: 5 is outside arithmetic model \"model\" [0, 2)");
  }
}

TEST_F(ArithmeticCodecTest, StrictModeAndTooManyElements) {
  models_->add(spec_model());
  load(series(field("repeated double", "value", 1, "model", 4)));
  auto five = message("test.Series1", "value: [0, 1, 0, 1, 1]");
  EXPECT_EQ(decode_text(codec_.encode(*five)), "value: 0 value: 1 value: 0 value: 1") << "extra dropped";
  codec_.set_strict(true);
  try {
    codec_.encode(*five);
    FAIL() << "no error";
  } catch (const dccl::Error& e) {
    EXPECT_EQ(std::string(e.what()), "test.Series1.value: 5 elements exceed max_repeat 4");
  }
  EXPECT_EQ(to_hex(codec_.encode(*message("test.Series1", "value: [0, 0, 0, 1]"))), "020b");
}

// eof_frequency 0: only full lists can be sent (the reference's Bodden test
// model); anything shorter is an encode error in either mode.
TEST_F(ArithmeticCodecTest, NoEofSymbolMeansFullListsOnly) {
  models_->add(make_model("noeof", {1, 2, 3, 4, 5, 6}, {2, 1, 3, 1, 1}, 0, 0));
  load("enum E { A = 1; B = 2; C = 3; D = 4; E5 = 5; }\n" + series(field("repeated E", "value", 1, "noeof", 8)));
  const char* text = "value: A value: B value: C value: C value: E5 value: D value: A value: C";
  EXPECT_EQ(decode_text(codec_.encode(*message("test.Series1", text))), text);
  try {
    codec_.encode(*message("test.Series1", "value: [A, B]"));
    FAIL() << "no error";
  } catch (const dccl::Error& e) {
    EXPECT_EQ(e.kind(), dccl::Error::Kind::kEncode);
    EXPECT_NE(std::string(e.what()).find("test.Series1.value: arithmetic model \"noeof\" has eof_frequency 0"),
              std::string::npos)
        << e.what();
  }
}

// Singular fields: one symbol, or EOF for an unset optional field.
TEST_F(ArithmeticCodecTest, SingularFields) {
  models_->add(make_model("enum", {1, 2, 3, 4}, {2, 3, 85}, 10, 0));
  models_->add(make_model("num", {-10, 0, 10}, {1, 1}, 1, 1));
  models_->add(make_model("bool", {0, 1, 2}, {1, 1}));
  load("enum E { A = 1; B = 2; C = 3; }\n" +
       series(field("required E", "e", 1, "enum") + field("optional double", "x", 2, "num") +
              field("optional sint64", "i", 3, "num") + field("optional bool", "b", 4, "bool")));
  for (const char* text : {"e: B", "e: C x: -10", "e: A i: 0 b: true", "e: C x: 0 i: -10 b: false"}) {
    EXPECT_EQ(decode_text(codec_.encode(*message("test.Series1", text))), text);
  }
  EXPECT_EQ(decode_text(codec_.encode(*message("test.Series1", "e: A x: 3.5 i: 9"))), "e: A x: 0 i: 0")
      << "values decode as their symbol's lower bound";
  std::string nan = decode_text(codec_.encode(*message("test.Series1", "e: A x: 11 i: 11")));
  EXPECT_EQ(nan, "e: A x: nan") << "out of range: NaN for doubles, unset for integers";
}

// Integer fields decode the lowest integer of the symbol; float fields
// compare in float, so 100.1f is in the symbol starting at 100.1.
TEST_F(ArithmeticCodecTest, IntegerAndFloatFields) {
  models_->add(make_model("fractional", {100.0, 100.1, 100.2, 100.3, 102.5, 110}, {100, 100, 100, 90, 125}, 25, 10));
  load(series(field("repeated float", "f", 1, "fractional", 4) + field("repeated int64", "i", 2, "fractional", 4)));
  EXPECT_EQ(decode_text(codec_.encode(*message("test.Series1", "f: [100.1, 100.2, 100.3, 102.5]"))),
            "f: 100.1 f: 100.2 f: 100.3 f: 102.5");
  EXPECT_EQ(decode_text(codec_.encode(*message("test.Series1", "i: [100, 101, 104, 109]"))),
            "i: 100 i: 101 i: 103 i: 103");
}

// Adaptive models start afresh in every message: the same message always
// encodes the same, and a run of one symbol gets cheaper than with a static
// model of the same starting frequencies.
TEST_F(ArithmeticCodecTest, AdaptiveModelsRestartEachMessage) {
  models_->add(make_model("static", {0, 1, 2}, {1, 1}, 1, 1, false));
  models_->add(make_model("adaptive", {0, 1, 2}, {1, 1}, 1, 1, true));
  load(series(field("repeated double", "value", 1, "static", 30)) +
       series(field("repeated double", "value", 1, "adaptive", 30), 2));
  std::string ones = "value: [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]";
  std::string first = codec_.encode(*message("test.Series2", ones));
  EXPECT_EQ(codec_.encode(*message("test.Series2", ones)), first);
  EXPECT_LT(first.size(), codec_.encode(*message("test.Series1", ones)).size());
  auto both = codec_.decode(first + first);
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(doubles(*both[1], "value"), std::vector<double>(20, 1.0));
}

TEST_F(ArithmeticCodecTest, DebugAssertOptionIsAccepted) {
  models_->add(spec_model());
  load(series(field("repeated double", "value", 1, "model", 4, ", (dccl.field).(arithmetic).debug_assert = true")));
  EXPECT_EQ(to_hex(codec_.encode(*message("test.Series1", "value: [0, 0, 0, 1]"))), "020b");
}

// ----------------------------------------------------------- bad input

TEST_F(ArithmeticCodecTest, TruncatedAndGarbageInputThrowDecodeErrors) {
  models_->add(make_model("skewed", {-5, -1, 0, 0.5, 2, 100}, {1000, 1, 300, 7, 2}, 3, 1, true));
  load(series(field("repeated double", "value", 1, "skewed", 30) +
              "  required uint32 after = 2 [(dccl.field) = { min: 0 max: 1000 }];\n"));
  std::string bytes = codec_.encode(*message("test.Series1", "value: [-1, 2, 2, 0.5, -5, 0.5, -1] after: 999"));
  ASSERT_GT(bytes.size(), 3u);
  for (size_t n = 1; n < bytes.size(); ++n) {
    try {
      codec_.decode(bytes.substr(0, n));
      ADD_FAILURE() << "decoded " << n << " bytes";
    } catch (const dccl::Error& e) {
      EXPECT_EQ(e.kind(), dccl::Error::Kind::kDecode);
    }
  }
  try {
    codec_.decode(bytes.substr(0, 2));
  } catch (const dccl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.Series1.value: message truncated"), std::string::npos) << e.what();
  }
  // Garbage after a valid id: decodes to something or throws dccl::Error.
  std::mt19937 random(5);
  for (int trial = 0; trial < 2000; ++trial) {
    std::string junk = "\x02";
    for (int i = 0, n = static_cast<int>(random() % 12); i < n; ++i) junk += static_cast<char>(random());
    try {
      codec_.decode(junk);
    } catch (const dccl::Error&) {
    }
  }
}

// ------------------------------------------------------------ load time

TEST_F(ArithmeticCodecTest, LoadErrorsNameFieldAndModel) {
  models_->add(spec_model());
  EXPECT_NE(load_error(series(field("repeated double", "value", 1, "nope", 4)))
                .find("test.Series1.value: arithmetic model \"nope\" is not registered"),
            std::string::npos);
  EXPECT_NE(load_error(series("  repeated double value = 1 [(dccl.field).codec = \"dccl.arithmetic\", "
                              "(dccl.field).max_repeat = 4];"))
                .find("test.Series1.value: codec dccl.arithmetic needs (dccl.field).(arithmetic).model"),
            std::string::npos);
  EXPECT_NE(load_error(series(field("repeated string", "value", 1, "model", 4, ", (dccl.field).max_length = 3")))
                .find("test.Series1.value: codec dccl.arithmetic is for numeric, enum and bool fields"),
            std::string::npos);
  EXPECT_NE(load_error(series(field("repeated double", "value", 1, "model")))
                .find("test.Series1.value: repeated field needs (dccl.field).max_repeat"),
            std::string::npos);
  // Without the import the option cannot even be written; the codec alone
  // says what is missing.
  dccl::Codec codec;
  register_arithmetic_codec(codec.registry(), models_);
  std::string path = (dir_ / "noimport.proto").string();
  std::ofstream(path) << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage t;\n"
                         "message M { option (dccl.msg) = { codec_version: 4 id: 9 max_bytes: 8 };\n"
                         "  repeated double v = 1 [(dccl.field) = { codec: \"dccl.arithmetic\" max_repeat: 2 }]; }\n";
  try {
    codec.load(path);
    FAIL() << "no error";
  } catch (const dccl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("t.M.v: codec dccl.arithmetic needs import "
                                         "\"dccl/arithmetic/protobuf/arithmetic_extensions.proto\""),
              std::string::npos)
        << e.what();
  }
}

// The size budget feeds max_bytes validation.
TEST_F(ArithmeticCodecTest, SizeBoundsAreReported) {
  models_->add(spec_model());
  load(series(field("repeated double", "value", 1, "model", 4)));
  const dccl::TypeInfo* info = codec_.find_type("test.Series1");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(info->fields[0].codec, "dccl.arithmetic");
  EXPECT_EQ(info->fields[0].bits.min, 0u);
  // Four symbols of p = 0.1: 13.3 bits; + 2 flush + 1 margin.
  EXPECT_EQ(info->fields[0].bits.max, 17u);
  // A budget it cannot meet is a load error.
  EXPECT_NE(load_error("message Tight { option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 2 };\n" +
                       field("repeated double", "value", 1, "model", 4) + "}\n")
                .find("max_bytes"),
            std::string::npos);
}

// A definition written for the reference library (its package, option
// syntax and import) loads unchanged and finds the models given in the
// Codec's settings (acommsd's dccl.arithmetic_models), installed the way
// the daemon installs every plugin codec.
TEST_F(ArithmeticCodecTest, ReferenceStyleDefinitionLoadsWithModelsFromSettings) {
  acomms::v1::DcclConfig settings;
  ASSERT_TRUE(pb::TextFormat::ParseFromString(
      "arithmetic_models { name: 'model' value_bound: [0, 1, 2] frequency: [5, 1] eof_frequency: 4 }", &settings));
  dccl::Codec codec;
  dccl::install_plugin_codecs(codec.registry(), &settings);
  std::string path = (dir_ / "reference.proto").string();
  std::ofstream(path) << R"(syntax = "proto2";
import "dccl/option_extensions.proto";
import "dccl/arithmetic/protobuf/arithmetic_extensions.proto";
package dccl.test.arith;

message ArithmeticDoubleTestMsg
{
    option (dccl.msg).id = 1;
    option (dccl.msg).max_bytes = 512;
    option (dccl.msg).codec_version = 4;

    repeated double value = 101 [
        (dccl.field).codec = "dccl.arithmetic",
        (dccl.field).(arithmetic).model = "model",
        (dccl.field).(arithmetic).debug_assert = true,
        (dccl.field).max_repeat = 4
    ];
}
)";
  codec.load(path);
  auto msg = codec.new_message("dccl.test.arith.ArithmeticDoubleTestMsg");
  ASSERT_TRUE(pb::TextFormat::ParseFromString("value: [0, 0, 0, 1]", msg.get()));
  EXPECT_EQ(to_hex(codec.encode(*msg)), "020b");
}

// --------------------------------------------------------------- models

TEST(ArithmeticModelTest, ValidationNamesTheModel) {
  ArithmeticModels models;
  auto error = [&](const ArithmeticModel& m) -> std::string {
    try {
      models.add(m);
    } catch (const dccl::Error& e) {
      EXPECT_EQ(e.kind(), dccl::Error::Kind::kSchema);
      return e.what();
    }
    return "added";
  };
  EXPECT_EQ(error(make_model("a", {0, 1}, {1, 1})),
            "arithmetic model \"a\": needs one value_bound more than frequency (has 2 and 2)");
  EXPECT_EQ(error(make_model("b", {0, 1, 1}, {1, 1})),
            "arithmetic model \"b\": value_bound must be strictly increasing (1 then 1)");
  EXPECT_EQ(error(make_model("c", {0, 1, 2}, {1, 0})), "arithmetic model \"c\": frequency of symbol 1 is 0");
  EXPECT_EQ(error(make_model("d", {0, 1}, {1u << 30})),
            "arithmetic model \"d\": total frequency 1073741825 exceeds 1073741823");
  EXPECT_EQ(error(make_model("", {0, 1}, {1})), "arithmetic model \"\": needs a name");
  EXPECT_EQ(error(make_model("e", {}, {})), "arithmetic model \"e\": needs at least one symbol (frequency)");
  EXPECT_EQ(error(spec_model()), "added");
  EXPECT_TRUE(models.find("model").has_value());
  EXPECT_FALSE(models.find("a").has_value());
}

TEST(ArithmeticModelTest, ParsesTextForm) {
  ArithmeticModel m = ArithmeticModel::parse_text(
      "name: 'depth' value_bound: [0, 10, 50] frequency: [3, 1] out_of_range_frequency: 2 is_adaptive: true");
  EXPECT_EQ(m.name, "depth");
  EXPECT_EQ(m.value_bound, (std::vector<double>{0, 10, 50}));
  EXPECT_EQ(m.frequency, (std::vector<uint32_t>{3, 1}));
  EXPECT_EQ(m.eof_frequency, 1u) << "default";
  EXPECT_EQ(m.out_of_range_frequency, 2u);
  EXPECT_TRUE(m.is_adaptive);
  EXPECT_NO_THROW(m.validate());
  try {
    ArithmeticModel::parse_text("name: 'x' frequncy: 3");
    FAIL() << "no error";
  } catch (const dccl::Error& e) {
    EXPECT_NE(std::string(e.what()).find("arithmetic model text: 1:"), std::string::npos) << e.what();
  }
}

// The shipped arithmetic_model.proto and the descriptor parse_text() uses
// agree: a model read through the .proto gives the same struct.
TEST(ArithmeticModelTest, ShippedProtoMatches) {
  pb::compiler::DiskSourceTree tree;
  tree.MapPath("", ACOMMS_PROTO_DIR);
  pb::compiler::Importer importer(&tree, nullptr);
  const pb::FileDescriptor* file = importer.Import("acomms/codecs/arithmetic_model.proto");
  ASSERT_NE(file, nullptr);
  const pb::Descriptor* d = file->pool()->FindMessageTypeByName("acomms.codecs.v1.ArithmeticModel");
  ASSERT_NE(d, nullptr);
  pb::DynamicMessageFactory factory;
  std::unique_ptr<pb::Message> msg(factory.GetPrototype(d)->New());
  const std::string text = "name: 'm' value_bound: [0, 1, 2] frequency: [5, 1] eof_frequency: 4";
  ASSERT_TRUE(pb::TextFormat::ParseFromString(text, msg.get()));
  ArithmeticModel a = ArithmeticModel::from_message(*msg);
  ArithmeticModel b = ArithmeticModel::parse_text(text);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.value_bound, b.value_bound);
  EXPECT_EQ(a.frequency, b.frequency);
  EXPECT_EQ(a.eof_frequency, 4u);
  EXPECT_EQ(b.eof_frequency, 4u);
  EXPECT_EQ(a.out_of_range_frequency, b.out_of_range_frequency);
  // Defaults agree too.
  std::unique_ptr<pb::Message> empty(factory.GetPrototype(d)->New());
  EXPECT_EQ(ArithmeticModel::from_message(*empty).eof_frequency, ArithmeticModel::parse_text("").eof_frequency);
  // Field numbers of the reference's model message.
  EXPECT_EQ(d->FindFieldByName("frequency")->number(), 10);
  EXPECT_EQ(d->FindFieldByName("eof_frequency")->number(), 11);
  EXPECT_EQ(d->FindFieldByName("out_of_range_frequency")->number(), 12);
  EXPECT_EQ(d->FindFieldByName("value_bound")->number(), 20);
  EXPECT_EQ(d->FindFieldByName("is_adaptive")->number(), 30);
}

}  // namespace
}  // namespace acomms::codecs
