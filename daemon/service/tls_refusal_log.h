#pragma once
// The daemon's side of a refused TLS client, in its own log.
//
// gRPC writes a failed TLS handshake to stderr in its own format, in
// OpenSSL's words ("Handshake failed with fatal error SSL_ERROR_SSL:
// error:0A0000C7:SSL routines::peer did not return a certificate."). With
// TLS on, gRPC's log goes through spdlog instead, and a refusal becomes one
// warning that says which rule the client broke and which file sets it.
// Everything else gRPC logs keeps its severity.

#include "acomms/v1/config.pb.h"

namespace acomms::service {

// Process-wide (gRPC has one log function); the last call wins.
void log_tls_refusals(const v1::TlsConfig& files);

}  // namespace acomms::service
