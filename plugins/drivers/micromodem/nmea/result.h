#pragma once
// What a Micro-Modem NMEA parser says about a line it could not use.
//
// The serial port is outside input: power-up noise, half sentences after
// the port opens, binary garbage from a serial-to-TCP gateway. None of it
// may crash the driver or throw through it, so every parser in this folder
// returns a Result: the value, or an Error whose kind a driver can count
// (spec §2.3 rule 5: count, log, never crash) and whose text names the
// sentence, the field and the bound for the log.

#include <cassert>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace acomms::micromodem {

enum class ErrorKind {
  kEmpty,               // nothing but the line end
  kNoDollar,            // the line does not start with '$'
  kEmbeddedDollar,      // a second '$': the sentence before it was cut short
  kTooLong,             // longer than kMaxLineLength
  kNonPrintable,        // a byte outside 0x20..0x7E
  kBadAddress,          // the address is not letters/digits
  kUnsupportedAddress,  // well formed, but not a 2+3 address ($PUBX, $UPMFWA): skip it
  kMissingChecksum,     // no "*HH" where one is required (modem output)
  kMalformedChecksum,   // "*" not followed by exactly 2 (or 8) hex digits
  kBadChecksum,         // the XOR does not match
  kWrongSentence,       // a typed parser was given another sentence
  kMissingField,        // too few fields
  kBadField,            // a field is not what the sentence allows
};

std::string_view to_string(ErrorKind kind);

struct Error {
  ErrorKind kind;
  std::string text;
};

// A value or an Error (std::expected is C++23).
template <typename T>
class Result {
 public:
  Result(T value) : state_(std::move(value)) {}  // NOLINT: implicit by design
  Result(Error error) : state_(std::move(error)) {}  // NOLINT
  bool ok() const { return std::holds_alternative<T>(state_); }
  explicit operator bool() const { return ok(); }
  // REQUIRES: ok()
  const T& value() const& { assert(ok()); return std::get<T>(state_); }
  T& value() & { assert(ok()); return std::get<T>(state_); }
  T&& value() && { assert(ok()); return std::get<T>(std::move(state_)); }
  const T& operator*() const& { return value(); }
  const T* operator->() const { return &value(); }
  // REQUIRES: !ok()
  const Error& error() const { assert(!ok()); return std::get<Error>(state_); }

 private:
  std::variant<T, Error> state_;
};

}  // namespace acomms::micromodem
