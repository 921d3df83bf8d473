#pragma once
// Why a TLS connection to the daemon failed, in OpenSSL's words.
//
// gRPC reports a refused TLS client as "Socket closed": with TLS 1.3 the
// client's half of the handshake is done before the daemon has checked the
// client's certificate, and the daemon's reason travels in a TLS alert
// ("certificate required", "unknown ca", "certificate expired") that gRPC
// does not pass on (gRPC 1.51's server even closes the connection before
// its alert is sent); nor does it say why the daemon's certificate failed
// verification. After a failure, acommsctl makes one handshake of its own
// with the same files and reads until an alert, the connection closing (the
// daemon refused this client's certificate, or the lack of one) or the
// daemon's first bytes.

#include <string>

namespace acomms::cli {

struct TlsPem {
  std::string ca;    // empty: the system's CAs
  std::string cert;  // empty: no client certificate
  std::string key;
};

struct TlsProbe {
  bool reached = false;       // a TCP connection was made
  bool handshake_done = false;  // this end's half of the TLS handshake completed
  bool closed_after_handshake = false;  // ... and then the daemon closed the connection
  std::string verify_error;   // why the daemon's certificate was not trusted, or empty
  std::string openssl_error;  // OpenSSL's reason ("tlsv13 alert certificate required"), or empty
};

// `address` is "host:port" or "[v6]:port". Waits at most `timeout_s` for
// each step.
TlsProbe probe_tls(const std::string& address, const TlsPem& pem, double timeout_s);

}  // namespace acomms::cli
