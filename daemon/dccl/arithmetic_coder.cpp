#include "dccl/arithmetic_coder.h"

#include <algorithm>

#include "dccl/error.h"

namespace acomms::dccl::arith {

FrequencyTable::FrequencyTable(const std::vector<uint32_t>& frequencies) {
  cumulative_.reserve(frequencies.size() + 1);
  cumulative_.push_back(0);
  for (uint32_t f : frequencies) cumulative_.push_back(cumulative_.back() + f);
}

size_t FrequencyTable::find(uint64_t count) const {
  // First symbol whose upper end is past count: zero-width symbols have
  // high == low and are skipped.
  auto it = std::upper_bound(cumulative_.begin() + 1, cumulative_.end(), count);
  return static_cast<size_t>(it - (cumulative_.begin() + 1));
}

void FrequencyTable::increment(size_t symbol) {
  for (size_t i = symbol + 1; i < cumulative_.size(); ++i) ++cumulative_[i];
}

namespace {

// The sub-interval of [low, high] for symbol (the WNC update). Products fit:
// range <= 2^32 and cumulative counts <= 2^30.
void narrow(const FrequencyTable& table, size_t symbol, uint64_t* low, uint64_t* high) {
  const uint64_t range = *high - *low + 1;
  *high = *low + range * table.high(symbol) / table.total() - 1;
  *low = *low + range * table.low(symbol) / table.total();
}

}  // namespace

void Encoder::emit(unsigned bit) {
  out_.write(bit, 1);
  for (; pending_ > 0; --pending_) out_.write(bit ^ 1u, 1);
}

void Encoder::encode(const FrequencyTable& table, size_t symbol) {
  narrow(table, symbol, &low_, &high_);
  for (;;) {
    if (high_ < kHalf) {
      emit(0);
    } else if (low_ >= kHalf) {
      emit(1);
      low_ -= kHalf;
      high_ -= kHalf;
    } else if (low_ >= kQuarter && high_ < kThreeQuarters) {
      // Straddles the middle: the next bit is not known yet, but whichever
      // it is, the one after will be its opposite.
      ++pending_;
      low_ -= kQuarter;
      high_ -= kQuarter;
    } else {
      break;
    }
    low_ = 2 * low_;
    high_ = 2 * high_ + 1;
  }
}

void Encoder::finish() {
  // Shortest k such that the block of 2^(32-k) code values starting at the
  // first multiple of that size >= low fits in [low, high]. With bits
  // pending, at least one bit must be written to resolve them.
  for (unsigned k = pending_ > 0 ? 1 : 0; k <= 32; ++k) {
    const unsigned shift = 32 - k;
    const uint64_t block = uint64_t{1} << shift;
    const uint64_t c = (low_ + block - 1) >> shift;
    if (((c + 1) << shift) - 1 > high_) continue;
    for (unsigned i = 0; i < k; ++i) {
      const unsigned bit = static_cast<unsigned>((c >> (k - 1 - i)) & 1u);
      if (i == 0) {
        emit(bit);
      } else {
        out_.write(bit, 1);
      }
    }
    return;
  }
}

uint64_t Decoder::count_of(const FrequencyTable& table, uint64_t value) const {
  const uint64_t range = high_ - low_ + 1;
  return ((value - low_ + 1) * table.total() - 1) / range;
}

size_t Decoder::decode(const FrequencyTable& table) {
  // Invariant: low_ <= min_ <= max_ <= high_. Every value in [min_, max_]
  // decodes as the same symbol once both ends do (the count is monotonic).
  size_t symbol = table.find(count_of(table, min_));
  while (symbol != table.find(count_of(table, max_))) {
    // unknown_ > 0 here: with every bit known min_ == max_.
    --unknown_;
    if (in_.read(1) != 0) {
      min_ |= uint64_t{1} << unknown_;
    } else {
      max_ &= ~(uint64_t{1} << unknown_);
    }
    symbol = table.find(count_of(table, min_));
  }
  // The symbol's interval holds [min_, max_] (WNC: a value lies in a
  // symbol's sub-interval exactly when its count falls in the symbol's
  // range), so the invariant survives and each renormalisation below drops
  // a bit that has been read.
  narrow(table, symbol, &low_, &high_);
  for (;;) {
    uint64_t offset;
    if (high_ < kHalf) {
      offset = 0;
    } else if (low_ >= kHalf) {
      offset = kHalf;
    } else if (low_ >= kQuarter && high_ < kThreeQuarters) {
      offset = kQuarter;
    } else {
      break;
    }
    if (unknown_ >= 32) throw dccl::decode_error("arithmetic decoder lost its place");
    low_ = 2 * (low_ - offset);
    high_ = 2 * (high_ - offset) + 1;
    min_ = 2 * (min_ - offset);
    max_ = 2 * (max_ - offset) + 1;
    ++unknown_;
  }
  return symbol;
}

}  // namespace acomms::dccl::arith
