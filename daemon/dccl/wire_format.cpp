#include "dccl/wire_format.h"

#include <google/protobuf/message.h>

#include <chrono>

#include "dccl/bitstream.h"
#include "dccl/error.h"
#include "util/seconds.h"

namespace acomms::dccl {
namespace gp = google::protobuf;

namespace {

double system_clock_seconds() {
  return util::unix_seconds_now();
}

// Reads the DCCL id: one byte `id << 1`, or when its bit 0 is set two bytes
// little-endian of `(id << 1) | 1`.
int read_id(BitReader& in) {
  try {
    uint64_t v = in.read(8);
    if (v & 1) v |= in.read(8) << 8;
    return static_cast<int>(v >> 1);
  } catch (const TruncatedRead&) {
    throw decode_error("message truncated in the DCCL id");
  }
}

void write_id(const TypeInfo& info, BitWriter& out) {
  uint64_t id = static_cast<uint64_t>(info.id);
  if (info.id_bits == 8) {
    out.write(id << 1, 8);
  } else {
    out.write((id << 1) | 1, 16);
  }
}

}  // namespace

WireFormat::WireFormat() : clock_(system_clock_seconds) {}

bool WireFormat::encrypts(const TypeInfo& info) const {
  return cipher_.has_value() && (info.omit_id || exempt_ids_.count(info.id) == 0);
}

std::string WireFormat::encode(const TypePlan& plan, const gp::Message& msg) const {
  const TypeInfo& info = plan.info;
  std::string out;
  out.reserve(info.max_bytes);
  BitWriter w(&out);
  if (!info.omit_id) write_id(info, w);
  EncodeContext ctx{strict_};
  plan.head.encode(msg, w, ctx);
  w.align();
  const size_t head_bytes = w.position() / 8;
  out.resize(head_bytes);
  plan.body.encode(msg, w, ctx);
  w.align();
  out.resize(w.position() / 8);
  if (encrypts(info)) {
    // The cleartext head (id included) seeds the key stream: see crypto.h.
    cipher_->apply(std::string_view(out).substr(0, head_bytes), out.data() + head_bytes, out.size() - head_bytes);
  }
  // Encrypt, then tag: the tag covers the body as it goes on the water.
  if (authenticates(info)) authenticator_->seal(out, clock_());
  return out;
}

std::unique_ptr<gp::Message> WireFormat::decode(const TypePlan& plan, std::string_view bytes,
                                                size_t* consumed) const {
  std::unique_ptr<gp::Message> msg(plan.prototype->New());
  DecodeContext ctx{&clock_};
  BitReader in(bytes);
  if (!plan.info.omit_id) read_id(in);
  plan.head.decode(in, msg.get(), ctx);
  in.align();
  const uint64_t body_start = in.position();
  const size_t head_bytes = body_start / 8;

  if (encrypts(plan.info)) {
    // The body length is only known after decoding, so decrypt everything
    // that follows; CTR makes the extra bytes harmless.
    std::string clear(bytes);
    cipher_->apply(bytes.substr(0, head_bytes), clear.data() + head_bytes, clear.size() - head_bytes);
    BitReader body(clear, body_start);
    plan.body.decode(body, msg.get(), ctx);
    body.align();
    if (consumed) *consumed = with_trailer(plan.info, bytes, body.position() / 8);
    return msg;
  }
  plan.body.decode(in, msg.get(), ctx);
  in.align();
  if (consumed) *consumed = with_trailer(plan.info, bytes, in.position() / 8);
  return msg;
}

size_t WireFormat::with_trailer(const TypeInfo& info, std::string_view bytes, size_t used) const {
  if (!authenticates(info)) return used;
  const size_t trailer = authenticator_->trailer_bytes();
  if (bytes.size() - used < trailer) {
    throw decode_error(info.name + ": authentication trailer truncated (" + std::to_string(bytes.size() - used) +
                       " of " + std::to_string(trailer) + " bytes)");
  }
  return used + trailer;
}

bool WireFormat::authenticates(const TypeInfo& info) const {
  return authenticator_ != nullptr && authenticated_types_.count(info.name) > 0;
}

void WireFormat::set_authentication(std::shared_ptr<const MessageAuthenticator> authenticator,
                                    std::set<std::string> types) {
  authenticator_ = std::move(authenticator);
  authenticated_types_ = authenticator_ ? std::move(types) : std::set<std::string>();
}

int WireFormat::id_of(std::string_view bytes) {
  BitReader in(bytes);
  return read_id(in);
}

void WireFormat::set_crypto(std::string_view passphrase, std::set<int> exempt_ids) {
  cipher_.emplace(passphrase);
  exempt_ids_ = std::move(exempt_ids);
}

void WireFormat::clear_crypto() {
  cipher_.reset();
  exempt_ids_.clear();
}

void WireFormat::set_clock(std::function<double()> clock) {
  clock_ = clock ? std::move(clock) : std::function<double()>(system_clock_seconds);
}

}  // namespace acomms::dccl
