// Errors raised by the DCCL codec.
//
// Every failure (a schema that does not load, a message that cannot be
// encoded in strict mode, bytes that do not decode) is reported by throwing
// acomms::dccl::Error. The text always names what was wrong and where, e.g.
//   "gv.Bad.x: numeric field needs (dccl.field).min and max"
//   "gv.Num4.od: message truncated at bit 24 (needs 11 bits, 0 left)"
//   "unknown DCCL id 77"
// so callers can log it as is. kind() lets callers tell a bad schema from bad
// input without parsing the text.
//
// Thread-safe as any exception: set once when thrown, then only read.
#pragma once

#include <stdexcept>
#include <string>

namespace acomms::dccl {

class Error : public std::runtime_error {
 public:
  enum class Kind {
    kSchema,  // .proto does not parse or breaks a DCCL load-time rule
    kEncode,  // message cannot be encoded (strict mode, unknown type)
    kDecode,  // bytes cannot be decoded (truncated, unknown id, garbage)
  };

  Error(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}

  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

// A type acommsd refuses on its own, not its file: one the reference DCCL
// refuses to load (a fielded vehicle could never send it), or one that uses
// a feature acommsd cannot encode the way the reference does. Field codecs
// throw it at load time with the reason; the type is left out (see
// Codec::refused_types()) and the rest of its file loads.
class TypeRefused : public Error {
 public:
  explicit TypeRefused(const std::string& what) : Error(Kind::kSchema, what) {}
};

inline Error schema_error(const std::string& what) { return Error(Error::Kind::kSchema, what); }
inline Error encode_error(const std::string& what) { return Error(Error::Kind::kEncode, what); }
inline Error decode_error(const std::string& what) { return Error(Error::Kind::kDecode, what); }

}  // namespace acomms::dccl
