#include "dccl/bitstream.h"

#include <gtest/gtest.h>

namespace acomms::dccl {
namespace {

TEST(BitWriter, PacksLsbFirst) {
  std::string out;
  BitWriter w(&out);
  w.write(0b101, 3);    // bits 0..2
  w.write(0b11111, 5);  // bits 3..7
  w.write(0x1ff, 9);    // bits 8..16
  ASSERT_EQ(out.size(), 3u);
  EXPECT_EQ(static_cast<unsigned char>(out[0]), 0xfd);
  EXPECT_EQ(static_cast<unsigned char>(out[1]), 0xff);
  EXPECT_EQ(static_cast<unsigned char>(out[2]), 0x01);
  EXPECT_EQ(w.position(), 17u);
}

TEST(BitWriter, IgnoresHighBitsAndHandles64) {
  std::string out;
  BitWriter w(&out);
  w.write(0xff, 4);
  w.write(~uint64_t{0}, 64);
  w.write(123, 0);
  EXPECT_EQ(w.position(), 68u);
  EXPECT_EQ(out, std::string("\xff\xff\xff\xff\xff\xff\xff\xff\x0f", 9));
}

TEST(BitWriter, BytesAtOddPositionAndAlign) {
  std::string out;
  BitWriter w(&out);
  w.write(1, 1);
  w.write_bytes("\x01\x02");
  w.align();
  EXPECT_EQ(out, std::string("\x03\x04\x00", 3));
  EXPECT_EQ(w.position(), 24u);
}

TEST(BitReader, ReadsWhatWriterWrote) {
  std::string out;
  BitWriter w(&out);
  w.write(5, 3);
  w.write(0x123456789abcdefULL, 61);
  w.write_bytes("hi");
  BitReader r(out);
  EXPECT_EQ(r.read(3), 5u);
  EXPECT_EQ(r.read(61), 0x123456789abcdefULL);
  std::string s;
  r.read_bytes(2, &s);
  EXPECT_EQ(s, "hi");
  EXPECT_EQ(r.remaining(), 0u);
}

TEST(BitReader, ThrowsOnTruncation) {
  std::string data("\xff", 1);
  BitReader r(data);
  EXPECT_EQ(r.read(5), 31u);
  try {
    r.read(4);
    FAIL() << "no throw";
  } catch (const TruncatedRead& t) {
    EXPECT_EQ(t.position, 5u);
    EXPECT_EQ(t.needed, 4u);
    EXPECT_EQ(t.left, 3u);
  }
  std::string s;
  EXPECT_THROW(r.read_bytes(1, &s), TruncatedRead);
  EXPECT_THROW(r.read_bytes(uint64_t{1} << 62, &s), TruncatedRead);
}

}  // namespace
}  // namespace acomms::dccl
