#pragma once
// Little-endian fixed-width fields for the state a stream end keeps in the
// store (stream_sender.h, stream_receiver.h): a reader that says "no"
// instead of throwing, because stored bytes from another version are a
// reason to start the stream over, not to stop the daemon.

#include <cstdint>
#include <string>
#include <string_view>

#include "util/little_endian.h"

namespace acomms::telemetry {

class StateWriter {
 public:
  void put(uint64_t value, int bytes) { util::put_le(&out_, value, bytes); }
  void put_bytes(std::string_view bytes) {
    put(bytes.size(), 4);
    out_.append(bytes);
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class StateReader {
 public:
  explicit StateReader(std::string_view in) : in_(in) {}
  bool get(int bytes, uint64_t* value) { return util::take_le(&in_, bytes, value); }
  bool get_bytes(std::string* out) {
    uint64_t n = 0;
    if (!get(4, &n) || n > in_.size()) return false;
    out->assign(in_.substr(0, n));
    in_.remove_prefix(n);
    return true;
  }
  bool done() const { return in_.empty(); }

 private:
  std::string_view in_;
};

}  // namespace acomms::telemetry
