#include "connection.h"

#include <grpc/support/log.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <stdexcept>

#include "acomms/v1/acomms.grpc.pb.h"
#include "rpc_error.h"
#include "tls_probe.h"
#include "core/pem_files.h"

namespace acomms::cli {
namespace {

bool is_tcp(const std::string& endpoint) { return endpoint.rfind("tcp:", 0) == 0; }

// gRPC only says "failed to connect"; the file system says why.
void check_unix_socket(const std::string& endpoint) {
  struct stat info {};
  if (::stat(endpoint.c_str(), &info) != 0) {
    throw std::runtime_error("cannot reach acommsd at " + endpoint +
                             ": no such socket (is acommsd running? see --socket)");
  }
  if (!S_ISSOCK(info.st_mode)) {
    throw std::runtime_error("cannot reach acommsd at " + endpoint + ": not a socket");
  }
  if (::access(endpoint.c_str(), W_OK) != 0) {
    throw std::runtime_error("cannot reach acommsd at " + endpoint +
                             ": permission denied (is this user in the daemon's group?)");
  }
}

// This end's files are checked here, so that an expired or mismatched one
// is named before the daemon's refusal would hide which.
TlsPem read_tls_files(const GlobalOptions& options) {
  if (options.cert_file.empty() != options.key_file.empty()) {
    throw UsageError("--cert and --key go together (the client certificate and its private key)");
  }
  std::time_t now = std::time(nullptr);
  TlsPem pem;
  if (!options.ca_file.empty()) pem.ca = core::read_ca_certificates({"--ca", options.ca_file}, now);
  if (!options.cert_file.empty()) {
    core::PemFile cert{"--cert", options.cert_file};
    pem.cert = core::read_certificate(cert, now);
    pem.key = core::read_private_key({"--key", options.key_file}, pem.cert, cert);
  }
  return pem;
}

std::shared_ptr<grpc::ChannelCredentials> credentials_for(const TlsPem& pem) {
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = pem.ca;  // empty: the system's CAs
  ssl.pem_cert_chain = pem.cert;
  ssl.pem_private_key = pem.key;
  return grpc::SslCredentials(ssl);
}

bool contains(const std::string& text, const char* part) { return text.find(part) != std::string::npos; }

// A failed TLS connection in terms of the files and options a person can
// change, from acommsctl's own handshake (see tls_probe.h).
std::string explain_tls_failure(const GlobalOptions& options, const TlsProbe& probe,
                                const std::string& grpc_reason) {
  const std::string ca = options.ca_file.empty() ? "the system's CAs" : "--ca " + options.ca_file;
  const std::string cert = "--cert " + options.cert_file;
  const std::string& alert = probe.openssl_error;
  if (!probe.verify_error.empty()) {
    if (contains(probe.verify_error, "local issuer") || contains(probe.verify_error, "self-signed") ||
        contains(probe.verify_error, "self signed")) {
      return "the daemon's certificate is not trusted by " + ca + ": it is issued by another CA (" +
             probe.verify_error + ")";
    }
    if (contains(probe.verify_error, "mismatch")) {
      return "the daemon's certificate does not name the host in --socket in its subjectAltName (" +
             probe.verify_error + ")";
    }
    return "the daemon's certificate is not trusted by " + ca + ": " + probe.verify_error;
  }
  if (contains(alert, "certificate required") ||
      (options.cert_file.empty() && contains(alert, "handshake failure"))) {
    return "the daemon requires a client certificate (mutual TLS): pass --cert and --key "
           "(or set $ACOMMSD_CERT and $ACOMMSD_KEY)";
  }
  if (contains(alert, "unknown ca")) {
    return "the daemon refused the client certificate " + cert +
           ": it is not issued by the CA in the daemon's grpc.tls.client_ca_file";
  }
  if (contains(alert, "certificate expired")) {
    return "the daemon refused the client certificate " + cert + ": expired";
  }
  // The daemon took this end's certificate (or the lack of one) and hung up.
  if (probe.closed_after_handshake) {
    if (options.cert_file.empty()) {
      return "the daemon requires a client certificate (mutual TLS): pass --cert and --key "
             "(or set $ACOMMSD_CERT and $ACOMMSD_KEY)";
    }
    return "the daemon refused the client certificate " + cert +
           ": it is not issued by the CA in the daemon's grpc.tls.client_ca_file";
  }
  if (probe.reached && !probe.handshake_done) {
    return "no TLS answer (a daemon with grpc.insecure_tcp serves plaintext: pass --insecure)" +
           (alert.empty() ? std::string() : "; OpenSSL said: " + alert);
  }
  if (!probe.reached) {
    return "connection refused or timed out (is acommsd running with grpc.tcp_listen?); gRPC said: " +
           grpc_reason;
  }
  return "the TLS connection failed (" + (alert.empty() ? grpc_reason : "OpenSSL said: " + alert) + ")";
}

// Over TCP a call, not only a connection, proves the way through: with TLS
// 1.3 the client's side of the handshake completes before the daemon has
// checked the client's certificate, so a refused client first sees a
// connection that works and then breaks. A call fails fast (not waiting for
// the daemon) and carries gRPC's reason. Returns the reason, or empty.
std::string tcp_probe(const std::shared_ptr<grpc::Channel>& channel, double timeout_s) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(timeout_s * 1000)));
  v1::Status status;
  grpc::Status result = v1::Acomms::NewStub(channel)->GetStatus(&context, v1::GetStatusRequest(), &status);
  if (result.ok() || result.error_code() != grpc::StatusCode::UNAVAILABLE) return {};
  return result.error_message();
}

// gRPC writes a line of its own for a failed handshake ("E1123 ...
// ssl_transport_security.cc:1501] Handshake failed with fatal error ...");
// acommsctl says what went wrong in its own one line instead.
void log_without_handshake_failures(gpr_log_func_args* args) {
  if (std::string(args->message).rfind("Handshake failed", 0) == 0) return;
  std::fprintf(stderr, "acommsctl: grpc: %s\n", args->message);
}

std::shared_ptr<grpc::Channel> connect_tcp(const GlobalOptions& options) {
  gpr_set_log_function(log_without_handshake_failures);
  const std::string address = target_for(options.endpoint);
  auto fail = [&](const std::string& why) {
    return std::runtime_error("cannot reach acommsd at " + options.endpoint + ": " + why);
  };
  if (options.insecure) {
    auto channel = grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
    std::string failure = tcp_probe(channel, options.timeout_s);
    if (failure.empty()) return channel;
    if (contains(failure, "Connection refused")) {
      throw fail("connection refused (is acommsd running with grpc.tcp_listen?)");
    }
    throw fail("no plaintext answer (the daemon serves TLS unless grpc.insecure_tcp is set: drop "
               "--insecure and pass --ca); gRPC said: " + failure);
  }
  TlsPem pem = read_tls_files(options);
  auto channel = grpc::CreateChannel(address, credentials_for(pem));
  std::string failure = tcp_probe(channel, options.timeout_s);
  if (failure.empty()) return channel;
  throw fail(explain_tls_failure(options, probe_tls(address, pem, options.timeout_s), failure));
}

}  // namespace

std::string default_socket() {
  const char* from_env = std::getenv("ACOMMSD_SOCKET");
  return from_env && *from_env ? from_env : "/run/acommsd/acommsd.sock";
}

std::string target_for(const std::string& endpoint) {
  if (is_tcp(endpoint)) return endpoint.substr(4);
  return "unix:" + endpoint;
}

std::shared_ptr<grpc::Channel> connect(const GlobalOptions& options) {
  const std::string& endpoint = options.endpoint;
  if (is_tcp(endpoint)) return connect_tcp(options);
  check_unix_socket(endpoint);
  auto channel = grpc::CreateChannel(target_for(endpoint), grpc::InsecureChannelCredentials());
  auto deadline = std::chrono::system_clock::now() +
                  std::chrono::milliseconds(static_cast<int64_t>(options.timeout_s * 1000));
  if (!channel->WaitForConnected(deadline)) {
    throw std::runtime_error("cannot reach acommsd at " + endpoint +
                             ": connection refused or timed out (is acommsd running?)");
  }
  return channel;
}

}  // namespace acomms::cli
