// The codec registry as plugins use it: a codec registered by name, found
// with the version-suffix rule, reading its own option from a
// DCCLFieldOptions extension and declaring its size for validation.
#include "dccl/registry.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>
#include <gtest/gtest.h>

#include "dccl/codec.h"
#include "dccl/field_codec.h"
#include "test_util.h"

namespace acomms::dccl {
namespace {

namespace gp = google::protobuf;
using testing::encode_hex;
using testing::error_of;

// Writes a uint32 field in a number of bits taken from the (t.raw_bits)
// option; a typical plugin shape.
class RawCodec final : public FieldCodec {
 public:
  explicit RawCodec(const FieldContext& ctx) : field_(ctx.field) {
    if (field_->cpp_type() != gp::FieldDescriptor::CPPTYPE_UINT32 || field_->is_repeated()) {
      ctx.fail("test.raw needs a singular uint32 field");
    }
    const gp::FieldDescriptor* ext = ctx.extension_field("t.raw_bits");
    if (ext == nullptr || !ctx.raw_options->GetReflection()->HasField(*ctx.raw_options, ext)) {
      ctx.fail("test.raw needs (dccl.field).(t.raw_bits)");
    }
    bits_ = ctx.raw_options->GetReflection()->GetUInt32(*ctx.raw_options, ext);
  }
  SizeBits size() const override { return {bits_, bits_}; }
  void encode(const gp::Message& msg, BitWriter& out, const EncodeContext&) const override {
    out.write(msg.GetReflection()->GetUInt32(msg, field_), bits_);
  }
  void decode(BitReader& in, gp::Message* msg, const DecodeContext&) const override {
    msg->GetReflection()->SetUInt32(msg, field_, static_cast<uint32_t>(in.read(bits_)));
  }

 private:
  const gp::FieldDescriptor* field_;
  unsigned bits_ = 0;
};

constexpr const char* kProto = R"(
extend dccl.DCCLFieldOptions { optional uint32 raw_bits = 1500; }
message Plug {
  option (dccl.msg) = { codec_version: 4 id: 50 max_bytes: 4 };
  required uint32 v = 1 [(dccl.field).codec = "test.raw", (dccl.field).(raw_bits) = 12];
}
)";

TEST(Registry, BuiltinsAndVersionSuffix) {
  CodecRegistry r = CodecRegistry::with_builtins();
  std::string name;
  ASSERT_NE(r.find("_default", 4, &name), nullptr);
  EXPECT_EQ(name, "_default4");
  ASSERT_NE(r.find("_default", 2, &name), nullptr);
  EXPECT_EQ(name, "_default2");
  ASSERT_NE(r.find("dccl.time", 4, &name), nullptr);
  EXPECT_EQ(name, "dccl.time");
  r.add("dccl.time4", [](const FieldContext&) -> std::unique_ptr<FieldCodec> { return nullptr; });
  r.find("dccl.time", 4, &name);
  EXPECT_EQ(name, "dccl.time4");  // name + version is tried first
  r.find("dccl.time", 3, &name);
  EXPECT_EQ(name, "dccl.time");
  EXPECT_EQ(r.find("dccl.default", 9), nullptr);
  EXPECT_EQ(r.find("_default4", 2, &name) != nullptr && name == "_default4", true);  // trailing digit: as is
}

TEST(Registry, PluginCodecReadsItsOptionAndIsUsed) {
  testing::TempDir dir;
  Codec codec;
  codec.registry().add("test.raw4", [](const FieldContext& ctx) { return std::make_unique<RawCodec>(ctx); });
  auto types = codec.load(dir.write_proto("p.proto", kProto));
  ASSERT_EQ(types.size(), 1u);
  EXPECT_EQ(types[0]->fields[0].codec, "test.raw4");
  EXPECT_EQ(types[0]->body.max, 12u);
  EXPECT_EQ(encode_hex(codec, "t.Plug", "v: 2748"), "64bc0a");  // 0xabc in 12 bits
  EXPECT_EQ(testing::decode_text(codec, "64bc0a"), "v: 2748");
}

TEST(Registry, PluginSizeCountsTowardsMaxBytes) {
  testing::TempDir dir;
  Codec codec;
  codec.registry().add("test.raw", [](const FieldContext& ctx) { return std::make_unique<RawCodec>(ctx); });
  std::string proto = kProto;
  proto.replace(proto.find("raw_bits) = 12"), 14, "raw_bits) = 30");
  EXPECT_EQ(error_of([&] { codec.load(dir.write_proto("p.proto", proto)); }),
            "t.Plug: encoded size can reach 5 bytes, more than max_bytes 4");
}

TEST(Registry, PluginLoadErrorsNameTheField) {
  testing::TempDir dir;
  Codec codec;
  codec.registry().add("test.raw", [](const FieldContext& ctx) { return std::make_unique<RawCodec>(ctx); });
  std::string proto = kProto;
  proto.replace(proto.find(", (dccl.field).(raw_bits) = 12"), 30, "");
  EXPECT_EQ(error_of([&] { codec.load(dir.write_proto("p.proto", proto)); }),
            "t.Plug.v: test.raw needs (dccl.field).(t.raw_bits)");
}

TEST(Registry, UnregisteredPluginIsALoadError) {
  testing::TempDir dir;
  Codec codec;
  EXPECT_EQ(error_of([&] { codec.load(dir.write_proto("p.proto", kProto)); }),
            "t.Plug.v: unknown field codec \"test.raw\"");
}

TEST(Registry, CodecGroupSelectsCodecForUnannotatedFields) {
  testing::TempDir dir;
  Codec codec;
  codec.load(dir.write_proto("g.proto", R"(
    message G {
      option (dccl.msg) = { codec_version: 4 id: 51 max_bytes: 8 codec_group: "dccl.presence" };
      optional uint32 a = 1 [(dccl.field) = { min: 0 max: 7 }];             // 1 + 3 bits
      optional uint32 b = 2 [(dccl.field) = { codec: "_default" min: 0 max: 6 }];  // 3 bits
    })"));
  const TypeInfo* info = codec.find_type("t.G");
  EXPECT_EQ(info->fields[0].codec, "dccl.presence");
  EXPECT_EQ(info->fields[1].codec, "_default4");
  EXPECT_EQ(encode_hex(codec, "t.G", "a: 7 b: 6"), "667f");  // presence 1, a 111, b 6+1 = 111
}

}  // namespace
}  // namespace acomms::dccl
