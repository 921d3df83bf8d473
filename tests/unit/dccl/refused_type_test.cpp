// Types refused on their own (dccl::TypeRefused): ones the reference DCCL
// refuses to load, and ones using dynamic_conditions, which acommsd does not
// evaluate. The type is left out with its reason; its file's other types load.
#include <gtest/gtest.h>

#include "dccl/codec.h"
#include "test_util.h"

namespace acomms::dccl::testing {
namespace {

const char* kSchema = R"(
enum E { A = 1; B = 2; }
message Fine {
  option (dccl.msg) = { codec_version: 4 id: 1 max_bytes: 8 };
  required uint32 v = 1 [(dccl.field) = { min: 0 max: 3 }];
}
message StaticEnum {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 8 };
  required E e = 1 [(dccl.field) = { codec: "dccl.static" static_value: "A" }];
}
message Dynamic {
  option (dccl.msg) = { codec_version: 4 id: 3 max_bytes: 8 };
  optional int32 x = 1 [(dccl.field) = { min: 0 max: 5 dynamic_conditions { max: "3" } }];
}
message Embeds {
  option (dccl.msg) = { codec_version: 4 id: 4 max_bytes: 8 };
  optional StaticEnum s = 1;
}
)";

TEST(RefusedType, IsLeftOutWithItsReasonWhileTheRestOfItsFileLoads) {
  TempDir dir;
  Codec codec;
  auto loaded = codec.load(dir.write_proto("r.proto", kSchema));
  ASSERT_EQ(loaded.size(), 1u);
  EXPECT_EQ(loaded[0]->name, "t.Fine");
  EXPECT_EQ(codec.refusal("t.StaticEnum"),
            "t.StaticEnum.e: dccl.static does not support enum fields (the reference DCCL refuses this type)");
  EXPECT_EQ(codec.refusal("t.Dynamic"),
            "t.Dynamic.x: (dccl.field).dynamic_conditions is not supported by acommsd");
  // A type that embeds a refused one cannot be encoded either.
  EXPECT_EQ(codec.refusal("t.Embeds"),
            "t.Embeds.s.e: dccl.static does not support enum fields (the reference DCCL refuses this type)");
  EXPECT_EQ(codec.refused_types().size(), 3u);
  EXPECT_EQ(codec.refusal("t.Fine"), "");
  EXPECT_EQ(codec.find_type("t.StaticEnum"), nullptr);
  EXPECT_EQ(codec.find_id(2), nullptr);
  EXPECT_EQ(error_of([&] { codec.new_message("t.Dynamic"); }),
            "unknown type t.Dynamic (refused at load: t.Dynamic.x: (dccl.field).dynamic_conditions is not "
            "supported by acommsd)");
}

TEST(RefusedType, DynamicConditionsMinAndMaxHaveTheReferenceNumbers) {
  TempDir dir;
  Codec codec;
  codec.load(dir.write_proto("r.proto", kSchema));
  auto msg = codec.new_message("t.Fine");
  const auto* pool = msg->GetDescriptor()->file()->pool();
  const auto* conditions = pool->FindMessageTypeByName("dccl.DCCLDynamicConditions");
  ASSERT_NE(conditions, nullptr);
  EXPECT_EQ(conditions->FindFieldByName("min")->number(), 10);
  EXPECT_EQ(conditions->FindFieldByName("max")->number(), 11);
}

TEST(RefusedType, LoadingTheFileAgainKeepsTheRefusal) {
  TempDir dir;
  Codec codec;
  std::string file = dir.write_proto("r.proto", kSchema);
  codec.load(file);
  EXPECT_EQ(codec.load(file).size(), 1u);
  EXPECT_FALSE(codec.refusal("t.StaticEnum").empty());
}

}  // namespace
}  // namespace acomms::dccl::testing
