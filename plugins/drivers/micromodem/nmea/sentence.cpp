#include "micromodem/nmea/sentence.h"

#include <cctype>
#include <stdexcept>

#include "util/hex.h"

namespace acomms::micromodem {
namespace {

bool printable(char c) { return c >= 0x20 && c <= 0x7E; }
bool alnum(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; }

// The two upper-case digits a sentence's XOR checksum is written as.
std::string checksum_digits(uint8_t sum) {
  const char byte = static_cast<char>(sum);
  return util::hex_encode(std::string_view(&byte, 1), util::HexCase::kUpper);
}

Error error(ErrorKind kind, std::string text) { return Error{kind, std::move(text)}; }

// Quotes a piece of a received line for a log message: bounded, and with
// non-printable bytes shown as \xHH so the log stays one readable line.
std::string quote(std::string_view text) {
  constexpr size_t kShown = 60;
  std::string out = "'";
  for (size_t i = 0; i < text.size() && i < kShown; ++i) {
    char c = text[i];
    if (printable(c)) {
      out += c;
    } else {
      out += "\\x";
      out += util::hex_encode(std::string_view(&c, 1), util::HexCase::kUpper);
    }
  }
  if (text.size() > kShown) out += "...";
  return out + "'";
}

std::vector<std::string> split_fields(std::string_view text) {
  std::vector<std::string> fields;
  size_t start = 0;
  while (true) {
    size_t comma = text.find(',', start);
    fields.emplace_back(text.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

// The checksum part after '*': two hex digits (the XOR), or eight (CRC-32).
Result<ChecksumState> check_checksum(std::string_view body, std::string_view digits,
                                     std::string_view line) {
  for (char c : digits) {
    if (util::hex_digit_value(c) < 0) {
      return error(ErrorKind::kMalformedChecksum,
                   "checksum " + quote(digits) + " is not hexadecimal in " + quote(line));
    }
  }
  if (digits.size() == 8) return ChecksumState::kUnverified;
  if (digits.size() != 2) {
    return error(ErrorKind::kMalformedChecksum,
                 "checksum " + quote(digits) + " must be 2 hex digits in " + quote(line));
  }
  int stated = util::hex_digit_value(digits[0]) * 16 + util::hex_digit_value(digits[1]);
  int computed = nmea_checksum(body);
  if (stated != computed) {
    std::string expected = checksum_digits(static_cast<uint8_t>(computed));
    return error(ErrorKind::kBadChecksum, "checksum " + std::string(digits) + " should be " +
                                              expected + " in " + quote(line));
  }
  return ChecksumState::kVerified;
}

}  // namespace

std::string_view to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kEmpty: return "empty line";
    case ErrorKind::kNoDollar: return "no leading '$'";
    case ErrorKind::kEmbeddedDollar: return "truncated sentence";
    case ErrorKind::kTooLong: return "line too long";
    case ErrorKind::kNonPrintable: return "non-printable byte";
    case ErrorKind::kBadAddress: return "bad address";
    case ErrorKind::kUnsupportedAddress: return "unsupported address";
    case ErrorKind::kMissingChecksum: return "missing checksum";
    case ErrorKind::kMalformedChecksum: return "malformed checksum";
    case ErrorKind::kBadChecksum: return "bad checksum";
    case ErrorKind::kWrongSentence: return "wrong sentence";
    case ErrorKind::kMissingField: return "missing field";
    case ErrorKind::kBadField: return "bad field";
  }
  return "unknown error";
}

bool Sentence::is(std::string_view address) const {
  return address.size() == talker.size() + type.size() && address.starts_with(talker) &&
         address.substr(talker.size()) == type;
}

std::string_view Sentence::field(size_t number) const {
  if (number == 0 || number > fields.size()) return {};
  return fields[number - 1];
}

uint8_t nmea_checksum(std::string_view body) {
  uint8_t sum = 0;
  for (char c : body) sum ^= static_cast<uint8_t>(c);
  return sum;
}

Result<Sentence> parse_sentence(std::string_view line, ChecksumRule rule) {
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.remove_suffix(1);
  if (line.empty()) return error(ErrorKind::kEmpty, "empty line");
  if (line.size() > kMaxLineLength) {
    return error(ErrorKind::kTooLong, "line of " + std::to_string(line.size()) +
                                          " characters exceeds " + std::to_string(kMaxLineLength) +
                                          ": " + quote(line));
  }
  if (line.front() != '$') return error(ErrorKind::kNoDollar, "no leading '$' in " + quote(line));
  for (size_t i = 0; i < line.size(); ++i) {
    if (!printable(line[i])) {
      return error(ErrorKind::kNonPrintable, "non-printable byte at column " +
                                                 std::to_string(i + 1) + " of " + quote(line));
    }
    if (i > 0 && line[i] == '$') {
      return error(ErrorKind::kEmbeddedDollar, "a second '$' at column " + std::to_string(i + 1) +
                                                   ": the sentence before it was cut short: " +
                                                   quote(line));
    }
  }
  std::string_view rest = line.substr(1);
  size_t star = rest.find('*');
  std::string_view body = rest.substr(0, star);
  ChecksumState checksum = ChecksumState::kAbsent;
  if (star != std::string_view::npos) {
    Result<ChecksumState> checked = check_checksum(body, rest.substr(star + 1), line);
    if (!checked) return checked.error();
    checksum = *checked;
  } else if (rule == ChecksumRule::kRequired) {
    return error(ErrorKind::kMissingChecksum,
                 "no '*HH' checksum (the modem always sends one; the line was cut short?): " +
                     quote(line));
  }
  std::vector<std::string> fields = split_fields(body);
  std::string address = std::move(fields.front());
  fields.erase(fields.begin());
  bool letters_and_digits = !address.empty();
  for (char c : address) letters_and_digits = letters_and_digits && alnum(c);
  if (!letters_and_digits) {
    return error(ErrorKind::kBadAddress,
                 "address " + quote(address) + " is not letters and digits in " + quote(line));
  }
  if (address.size() != 5) {
    return error(ErrorKind::kUnsupportedAddress,
                 "address " + quote(address) + " is not a 2+3 talker and sentence id");
  }
  return Sentence{address.substr(0, 2), address.substr(2), std::move(fields), checksum};
}

std::string serialize(const Sentence& sentence) {
  std::string body = sentence.address();
  bool address_ok = sentence.talker.size() == 2 && sentence.type.size() == 3;
  for (char c : body) address_ok = address_ok && alnum(c);
  if (!address_ok) throw std::invalid_argument("NMEA address '" + body + "' is not 2+3 letters/digits");
  for (const std::string& field : sentence.fields) {
    for (char c : field) {
      if (!printable(c) || c == ',' || c == '*' || c == '$') {
        throw std::invalid_argument("NMEA field " + quote(field) + " of " + sentence.address() +
                                    " holds a byte a sentence cannot carry");
      }
    }
    body += ',';
    body += field;
  }
  return "$" + body + "*" + checksum_digits(nmea_checksum(body));
}

}  // namespace acomms::micromodem
