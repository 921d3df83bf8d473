#pragma once
// Reads a sentence's fields by number for the typed parsers, checking each
// against its bound, so an error names the sentence, the field and the
// bound ("CACYC field 4 (rate) '9' is outside 0..6"). The first error
// sticks; reads after it return defaults, so a parser reads every field in
// a straight line and checks once at the end (finish()).
//
// Numbers may carry leading zeros and signs ("001", "-01", "+3"): the
// modem writes them so (spec §2.1).

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

class FieldReader {
 public:
  // Fails (kWrongSentence) unless the sentence's address is one of `addresses`.
  FieldReader(const Sentence& sentence, std::initializer_list<std::string_view> addresses);

  bool ok() const { return !error_; }
  size_t field_count() const { return sentence_.fields.size(); }
  // Fails (kMissingField) if the sentence has fewer than `count` fields.
  void require(size_t count);

  int64_t integer(size_t number, std::string_view name, int64_t min, int64_t max);
  // An absent or empty field is nullopt; a present one must be a number.
  std::optional<int64_t> optional_integer(size_t number, std::string_view name, int64_t min,
                                          int64_t max);
  std::optional<double> optional_real(size_t number, std::string_view name);
  double real(size_t number, std::string_view name);
  bool flag(size_t number, std::string_view name) { return integer(number, name, 0, 1) == 1; }
  std::string text(size_t number) const { return std::string(sentence_.field(number)); }
  // Fields `number`.. joined by ',' (free text that may hold commas).
  std::string rest(size_t number) const;
  // The payload of a hex field, decoded.
  std::string hex(size_t number, std::string_view name);
  void fail(ErrorKind kind, std::string text);

  template <typename T>
  Result<T> finish(T value) const {
    if (error_) return *error_;
    return value;
  }

 private:
  std::string where(size_t number, std::string_view name) const;
  const Sentence& sentence_;
  std::optional<Error> error_;
};

// Appends free text that may hold commas (FieldReader::rest) as the
// fields it came from.
void append_fields(Sentence& sentence, std::string_view text);

// Numbers as the modem writes them: integers plainly, reals in their
// shortest exact form ("-6.48", "26").
std::string format_real(double value);

}  // namespace acomms::micromodem
