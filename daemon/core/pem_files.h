#pragma once
// TLS files checked before gRPC sees them.
//
// gRPC reports a bad certificate or key as a failed handshake at best
// ("certificate verify failed", on the other end) and as a port that did not
// bind at worst. A person needs to know which file and why: expired (and
// when), not yet valid, not PEM, or a key that belongs to another
// certificate. So both ends read their files here first, and every error
// names the file by the setting that gave it (for example
// "grpc.tls.cert_file /etc/acommsd/server.pem" or "--cert client.pem").
//
// Thread-safe: each call reads its own file and keeps nothing.

#include <ctime>
#include <stdexcept>
#include <string>

namespace acomms::core {

// Thrown with a message that starts with the setting and the path.
class PemFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One file as named to the user: `setting` is how the user gave it
// ("grpc.tls.cert_file", "--cert").
struct PemFile {
  std::string setting;
  std::string path;
};

// A certificate (chain) whose first certificate is valid at `now`.
std::string read_certificate(const PemFile& file, std::time_t now);

// Trusted CA certificates: at least one, none of them expired at `now`.
std::string read_ca_certificates(const PemFile& file, std::time_t now);

// A private key that matches the first certificate of `certificate_pem`
// (read from `certificate`).
std::string read_private_key(const PemFile& file, const std::string& certificate_pem,
                             const PemFile& certificate);

// "CN=acommsd, valid until 2027-11-23 17:00:00 UTC": for the log.
std::string describe_certificate(const std::string& certificate_pem);

}  // namespace acomms::core
