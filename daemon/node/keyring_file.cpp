#include "node/keyring_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace acomms::node {
namespace {

bool is_hex(const std::string& text) {
  for (char c : text) {
    if (!std::isxdigit(static_cast<unsigned char>(c))) return false;
  }
  return !text.empty() && text.size() % 2 == 0;
}

std::string from_hex(const std::string& hex) {
  std::string out;
  for (size_t i = 0; i < hex.size(); i += 2) out.push_back(static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  return out;
}

// Refuses a file others could read or change, before reading it.
void check_file(const std::string& path, const std::string& where) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw std::runtime_error(where + "cannot read: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw std::runtime_error(where + "is not a regular file");
  if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    throw std::runtime_error(where + "is open to group or others (mode " + mode +
                             "): keys must be readable only by the daemon's user (chmod 600)");
  }
  if (st.st_uid != ::geteuid()) {
    throw std::runtime_error(where + "belongs to uid " + std::to_string(st.st_uid) + ", not the daemon's user (uid " +
                             std::to_string(::geteuid()) + ")");
  }
}

}  // namespace

std::optional<double> parse_utc_time(const std::string& text) {
  std::tm tm{};
  std::istringstream in(text);
  in >> std::get_time(&tm, "%Y-%m-%dT%H:%M:%SZ");
  if (in.fail() || text.size() != 20 || text.back() != 'Z') return std::nullopt;
  return static_cast<double>(::timegm(&tm));
}

dccl::Keyring read_keyring_file(const std::string& path) {
  const std::string where = "auth.keyring_file " + path + ": ";
  check_file(path, where);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(where + "cannot read: " + std::strerror(errno));
  dccl::Keyring ring;
  bool signed_by = false;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string at = where + "line " + std::to_string(number) + ": ";
    std::istringstream words(line);
    std::string word;
    if (!(words >> word) || word[0] == '#') continue;
    if (word == "key") {
      long id = -1;
      std::string hex, until_word, until;
      if (!(words >> id) || id < 0 || id > 255) throw std::runtime_error(at + "key needs an id from 0 to 255");
      if (!(words >> hex) || !is_hex(hex)) throw std::runtime_error(at + "key " + std::to_string(id) + " needs its key in hex");
      dccl::AuthKey key;
      key.key = from_hex(hex);
      if (key.key.size() != 16 && key.key.size() != 24 && key.key.size() != 32) {
        throw std::runtime_error(at + "key " + std::to_string(id) + " is " + std::to_string(key.key.size()) +
                                 " bytes: an AES key is 16, 24 or 32 bytes (32, 48 or 64 hex digits)");
      }
      if (words >> until_word) {
        if (until_word != "until" || !(words >> until) || !(key.accept_until = parse_utc_time(until))) {
          throw std::runtime_error(at + "after the key, only `until YYYY-MM-DDTHH:MM:SSZ` may follow");
        }
      }
      if (words >> word) throw std::runtime_error(at + "unexpected \"" + word + "\" after the key");
      if (!ring.keys.emplace(static_cast<uint8_t>(id), std::move(key)).second) {
        throw std::runtime_error(at + "key " + std::to_string(id) + " is given twice");
      }
    } else if (word == "sign") {
      long id = -1;
      if (!(words >> id) || id < 0 || id > 255) throw std::runtime_error(at + "sign needs a key id from 0 to 255");
      if (signed_by) throw std::runtime_error(at + "a second sign line");
      ring.sign_id = static_cast<uint8_t>(id);
      signed_by = true;
    } else {
      throw std::runtime_error(at + "\"" + word + "\" is not `key` or `sign`");
    }
  }
  if (!signed_by) throw std::runtime_error(where + "no `sign <id>` line: which key seals what this node sends?");
  try {
    dccl::MessageAuthenticator::check_keyring(ring);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(where + e.what());
  }
  return ring;
}

}  // namespace acomms::node
