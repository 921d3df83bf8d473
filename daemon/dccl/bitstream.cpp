#include "dccl/bitstream.h"

#include <algorithm>

namespace acomms::dccl {

void BitWriter::write(uint64_t value, unsigned n) {
  if (n < 64) value &= (uint64_t{1} << n) - 1;  // n == 0 gives 0
  out_->resize((bit_ + n + 7) / 8, '\0');
  while (n > 0) {
    unsigned offset = bit_ % 8;
    unsigned take = std::min(8u - offset, n);
    auto byte = static_cast<unsigned char>((*out_)[bit_ / 8]);
    byte |= static_cast<unsigned char>((value & ((1u << take) - 1)) << offset);
    (*out_)[bit_ / 8] = static_cast<char>(byte);
    value >>= take;
    n -= take;
    bit_ += take;
  }
}

void BitWriter::write_zeros(uint64_t n) {
  bit_ += n;
  out_->resize((bit_ + 7) / 8, '\0');
}

void BitWriter::write_bytes(std::string_view bytes) {
  if (bit_ % 8 == 0) {
    out_->resize(bit_ / 8);
    out_->append(bytes);
    bit_ += uint64_t{bytes.size()} * 8;
    return;
  }
  for (char c : bytes) write(static_cast<unsigned char>(c), 8);
}

void BitReader::require(uint64_t n) const {
  if (n > remaining()) throw TruncatedRead{bit_ - origin_, n, remaining()};
}

uint64_t BitReader::read(unsigned n) {
  require(n);
  uint64_t value = 0;
  unsigned got = 0;
  while (got < n) {
    unsigned offset = bit_ % 8;
    unsigned take = std::min(8u - offset, n - got);
    uint64_t byte = static_cast<unsigned char>(data_[bit_ / 8]);
    value |= ((byte >> offset) & ((1u << take) - 1)) << got;
    got += take;
    bit_ += take;
  }
  return value;
}

void BitReader::read_bytes(uint64_t n, std::string* out) {
  if (n > remaining() / 8) throw TruncatedRead{bit_ - origin_, n * 8, remaining()};
  out->clear();
  if (bit_ % 8 == 0) {
    out->assign(data_.substr(bit_ / 8, n));
    bit_ += n * 8;
    return;
  }
  out->reserve(n);
  for (uint64_t i = 0; i < n; ++i) out->push_back(static_cast<char>(read(8)));
}

}  // namespace acomms::dccl
