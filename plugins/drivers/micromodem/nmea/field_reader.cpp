#include "micromodem/nmea/field_reader.h"

#include <charconv>
#include <cmath>

#include "micromodem/nmea/hex.h"

namespace acomms::micromodem {
namespace {

std::string_view without_plus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

}  // namespace

FieldReader::FieldReader(const Sentence& sentence,
                         std::initializer_list<std::string_view> addresses)
    : sentence_(sentence) {
  for (std::string_view address : addresses) {
    if (sentence.is(address)) return;
  }
  std::string expected;
  for (std::string_view address : addresses) {
    expected += (expected.empty() ? "" : " or ") + std::string(address);
  }
  fail(ErrorKind::kWrongSentence, "expected " + expected + ", got " + sentence.address());
}

void FieldReader::fail(ErrorKind kind, std::string text) {
  if (!error_) error_ = Error{kind, std::move(text)};
}

std::string FieldReader::where(size_t number, std::string_view name) const {
  return sentence_.address() + " field " + std::to_string(number) + " (" + std::string(name) + ")";
}

void FieldReader::require(size_t count) {
  if (sentence_.fields.size() < count) {
    fail(ErrorKind::kMissingField, sentence_.address() + " has " +
                                       std::to_string(sentence_.fields.size()) +
                                       " fields, needs at least " + std::to_string(count));
  }
}

std::optional<int64_t> FieldReader::optional_integer(size_t number, std::string_view name,
                                                     int64_t min, int64_t max) {
  std::string_view text = without_plus(sentence_.field(number));
  if (!ok() || text.empty()) return std::nullopt;
  int64_t value = 0;
  auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (status != std::errc() || end != text.data() + text.size()) {
    fail(ErrorKind::kBadField, where(number, name) + " '" + std::string(text) + "' is not an integer");
    return std::nullopt;
  }
  if (value < min || value > max) {
    fail(ErrorKind::kBadField, where(number, name) + " " + std::to_string(value) +
                                   " is outside " + std::to_string(min) + ".." + std::to_string(max));
    return std::nullopt;
  }
  return value;
}

int64_t FieldReader::integer(size_t number, std::string_view name, int64_t min, int64_t max) {
  if (ok() && sentence_.field(number).empty()) {
    fail(sentence_.fields.size() < number ? ErrorKind::kMissingField : ErrorKind::kBadField,
         where(number, name) + " is missing");
  }
  return optional_integer(number, name, min, max).value_or(0);
}

std::optional<double> FieldReader::optional_real(size_t number, std::string_view name) {
  std::string_view text = without_plus(sentence_.field(number));
  if (!ok() || text.empty()) return std::nullopt;
  double value = 0;
  auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value,
                                       std::chars_format::fixed);
  if (status != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    fail(ErrorKind::kBadField, where(number, name) + " '" + std::string(text) + "' is not a number");
    return std::nullopt;
  }
  return value;
}

double FieldReader::real(size_t number, std::string_view name) {
  if (ok() && sentence_.field(number).empty()) {
    fail(sentence_.fields.size() < number ? ErrorKind::kMissingField : ErrorKind::kBadField,
         where(number, name) + " is missing");
  }
  return optional_real(number, name).value_or(0);
}

std::string FieldReader::rest(size_t number) const {
  std::string joined;
  for (size_t i = number; i <= sentence_.fields.size(); ++i) {
    if (i > number) joined += ',';
    joined += sentence_.fields[i - 1];
  }
  return joined;
}

std::string FieldReader::hex(size_t number, std::string_view name) {
  if (!ok()) return {};
  Result<std::string> bytes = hex_decode(sentence_.field(number));
  if (!bytes) {
    fail(ErrorKind::kBadField, where(number, name) + ": " + bytes.error().text);
    return {};
  }
  return std::move(bytes).value();
}

void append_fields(Sentence& sentence, std::string_view text) {
  size_t start = 0;
  while (true) {
    size_t comma = text.find(',', start);
    sentence.fields.emplace_back(text.substr(start, comma - start));
    if (comma == std::string_view::npos) return;
    start = comma + 1;
  }
}

std::string format_real(double value) {
  // Fixed notation, never "1e+23": the readers accept no exponent. The
  // longest finite double in fixed form has ~330 characters.
  char buffer[512];
  auto [end, status] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
  if (status != std::errc()) return "0";
  return std::string(buffer, end);
}

}  // namespace acomms::micromodem
