#include "tls_probe.h"

#include <netdb.h>
#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/ssl.h>
#include <openssl/x509v3.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <memory>

namespace acomms::cli {
namespace {

struct Host {
  std::string name;
  std::string port;
};

Host split(const std::string& address) {
  size_t colon = address.rfind(':');
  std::string host = address.substr(0, colon);
  if (host.size() > 1 && host.front() == '[') host = host.substr(1, host.size() - 2);
  return {host, colon == std::string::npos ? "" : address.substr(colon + 1)};
}

int connect_tcp(const Host& host, double timeout_s) {
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (::getaddrinfo(host.name.c_str(), host.port.c_str(), &hints, &found) != 0) return -1;
  int fd = -1;
  timeval timeout{static_cast<time_t>(timeout_s), static_cast<suseconds_t>((timeout_s - static_cast<long>(timeout_s)) * 1e6)};
  for (addrinfo* a = found; a != nullptr && fd < 0; a = a->ai_next) {
    fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof(timeout));
    if (::connect(fd, a->ai_addr, a->ai_addrlen) != 0) {
      ::close(fd);
      fd = -1;
    }
  }
  ::freeaddrinfo(found);
  return fd;
}

struct CtxFree {
  void operator()(SSL_CTX* ctx) const { SSL_CTX_free(ctx); }
};
struct SslFree {
  void operator()(SSL* ssl) const { SSL_free(ssl); }
};

// Loads the PEM texts (already checked by core::read_* in connection.cpp).
bool configure(SSL_CTX* ctx, const TlsPem& pem) {
  SSL_CTX_set_verify(ctx, SSL_VERIFY_PEER, nullptr);
  if (pem.ca.empty()) {
    SSL_CTX_set_default_verify_paths(ctx);
  } else {
    BIO* bio = BIO_new_mem_buf(pem.ca.data(), static_cast<int>(pem.ca.size()));
    X509_STORE* store = SSL_CTX_get_cert_store(ctx);
    while (X509* cert = PEM_read_bio_X509(bio, nullptr, nullptr, nullptr)) {
      X509_STORE_add_cert(store, cert);
      X509_free(cert);
    }
    BIO_free(bio);
  }
  if (!pem.cert.empty()) {
    BIO* cert_bio = BIO_new_mem_buf(pem.cert.data(), static_cast<int>(pem.cert.size()));
    X509* cert = PEM_read_bio_X509(cert_bio, nullptr, nullptr, nullptr);
    BIO_free(cert_bio);
    BIO* key_bio = BIO_new_mem_buf(pem.key.data(), static_cast<int>(pem.key.size()));
    EVP_PKEY* key = PEM_read_bio_PrivateKey(key_bio, nullptr, nullptr, nullptr);
    BIO_free(key_bio);
    bool ok = cert && key && SSL_CTX_use_certificate(ctx, cert) == 1 && SSL_CTX_use_PrivateKey(ctx, key) == 1;
    X509_free(cert);
    EVP_PKEY_free(key);
    if (!ok) return false;
  }
  // gRPC's server insists on HTTP/2 by ALPN.
  static const unsigned char kH2[] = {2, 'h', '2'};
  SSL_CTX_set_alpn_protos(ctx, kH2, sizeof(kH2));
  ERR_clear_error();
  return true;
}

std::string last_openssl_error() {
  unsigned long code = ERR_peek_last_error();
  const char* reason = code ? ERR_reason_error_string(code) : nullptr;
  ERR_clear_error();
  return reason ? reason : "";
}

}  // namespace

TlsProbe probe_tls(const std::string& address, const TlsPem& pem, double timeout_s) {
  TlsProbe probe;
  Host host = split(address);
  std::unique_ptr<SSL_CTX, CtxFree> ctx(SSL_CTX_new(TLS_client_method()));
  if (!ctx || !configure(ctx.get(), pem)) return probe;
  int fd = connect_tcp(host, timeout_s);
  if (fd < 0) return probe;
  probe.reached = true;
  std::unique_ptr<SSL, SslFree> ssl(SSL_new(ctx.get()));
  SSL_set_fd(ssl.get(), fd);
  // Checks the name as gRPC does: an address against IP entries, a name
  // against DNS entries of subjectAltName.
  X509_VERIFY_PARAM* param = SSL_get0_param(ssl.get());
  if (X509_VERIFY_PARAM_set1_ip_asc(param, host.name.c_str()) != 1) {
    ERR_clear_error();
    X509_VERIFY_PARAM_set1_host(param, host.name.c_str(), 0);
    SSL_set_tlsext_host_name(ssl.get(), host.name.c_str());
  }
  if (SSL_connect(ssl.get()) != 1) {
    long verify = SSL_get_verify_result(ssl.get());
    if (verify != X509_V_OK) probe.verify_error = X509_verify_cert_error_string(verify);
    probe.openssl_error = last_openssl_error();
  } else {
    probe.handshake_done = true;
    // The daemon's verdict on this client arrives now: an alert or the
    // connection closing, or its first HTTP/2 bytes (or nothing until the
    // timeout: accepted).
    char byte;
    if (SSL_read(ssl.get(), &byte, 1) <= 0) {
      int error = SSL_get_error(ssl.get(), 0);
      bool timed_out = error == SSL_ERROR_WANT_READ || (error == SSL_ERROR_SYSCALL && errno == EAGAIN);
      probe.closed_after_handshake = !timed_out;
      probe.openssl_error = last_openssl_error();
    }
  }
  ::close(fd);
  return probe;
}

}  // namespace acomms::cli
