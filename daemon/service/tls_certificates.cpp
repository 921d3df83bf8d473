#include "service/tls_certificates.h"

#include <grpc/grpc.h>
#include <grpc/grpc_security.h>

#include <ctime>

#include "core/pem_files.h"

namespace acomms::service {
namespace {

// grpc::ServerCredentials around gRPC core's SSL server credentials, which
// gRPC C++ 1.51 has no public constructor for (SslServerCredentials takes
// fixed PEM text only). ServerBuilder calls AddPortToServer once per port.
class FetchedSslCredentials final : public grpc::ServerCredentials {
 public:
  explicit FetchedSslCredentials(grpc_server_credentials* core) : core_(core) {}
  ~FetchedSslCredentials() override { grpc_server_credentials_release(core_); }
  void SetAuthMetadataProcessor(const std::shared_ptr<grpc::AuthMetadataProcessor>&) override {}

 private:
  int AddPortToServer(const std::string& address, grpc_server* server) override {
    return grpc_server_add_http2_port(server, address.c_str(), core_);
  }
  grpc_server_credentials* core_;
};

}  // namespace

TlsCertificates::TlsCertificates(const v1::TlsConfig& files) : files_(files), pending_(load()) {
  description_ = core::describe_certificate(pending_->cert);
}

TlsCertificates::~TlsCertificates() = default;

TlsCertificates::Files TlsCertificates::load() const {
  std::time_t now = std::time(nullptr);
  core::PemFile cert{"grpc.tls.cert_file", files_.cert_file()};
  Files loaded;
  loaded.cert = core::read_certificate(cert, now);
  loaded.key = core::read_private_key({"grpc.tls.key_file", files_.key_file()}, loaded.cert, cert);
  if (!files_.client_ca_file().empty()) {
    loaded.client_ca = core::read_ca_certificates({"grpc.tls.client_ca_file", files_.client_ca_file()}, now);
  }
  return loaded;
}

void TlsCertificates::reload() {
  Files loaded = load();
  std::lock_guard lock(mutex_);
  description_ = core::describe_certificate(loaded.cert);
  pending_ = std::move(loaded);
}

std::string TlsCertificates::description() const {
  std::lock_guard lock(mutex_);
  return description_;
}

int TlsCertificates::fetch(void* self, void* config) {
  auto* certificates = static_cast<TlsCertificates*>(self);
  std::lock_guard lock(certificates->mutex_);
  if (!certificates->pending_) return GRPC_SSL_CERTIFICATE_CONFIG_RELOAD_UNCHANGED;
  const Files& files = *certificates->pending_;
  grpc_ssl_pem_key_cert_pair pair{files.key.c_str(), files.cert.c_str()};
  // gRPC 1.51 asserts that a fetched config has root certificates even when
  // no client certificate is requested (ssl_security_connector.cc); they
  // are then never used, so without mutual TLS the daemon's own chain
  // stands in. Copies the strings: pending_ can go.
  const std::string& roots = files.client_ca.empty() ? files.cert : files.client_ca;
  *static_cast<grpc_ssl_server_certificate_config**>(config) =
      grpc_ssl_server_certificate_config_create(roots.c_str(), &pair, 1);
  certificates->pending_.reset();
  return GRPC_SSL_CERTIFICATE_CONFIG_RELOAD_NEW;
}

std::shared_ptr<grpc::ServerCredentials> TlsCertificates::credentials() {
  grpc_ssl_server_certificate_config_callback callback = [](void* self,
                                                           grpc_ssl_server_certificate_config** config) {
    return static_cast<grpc_ssl_certificate_config_reload_status>(fetch(self, config));
  };
  grpc_ssl_server_credentials_options* options =
      grpc_ssl_server_credentials_create_options_using_config_fetcher(
          mutual() ? GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY
                   : GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE,
          callback, this);
  // Takes ownership of options.
  return std::make_shared<FetchedSslCredentials>(grpc_ssl_server_credentials_create_with_options(options));
}

}  // namespace acomms::service
