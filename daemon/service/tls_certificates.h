#pragma once
// TLS for the TCP listener, with certificates replaced while the daemon
// serves (SIGHUP).
//
// gRPC 1.51's C++ TLS credentials either never change
// (StaticDataCertificateProvider) or poll their files on a timer
// (FileWatcherCertificateProvider): neither lets `systemctl reload` mean
// "now". gRPC core's SSL server credentials instead ask a callback before
// every handshake whether the certificates changed. The callback hands over a
// new set only after reload() has read and checked every file, so a reload
// takes effect from the next connection (connections already open keep the
// certificate they were made with), and a bad file never replaces good
// certificates: reload() throws and the current set stays.
//
// Thread-safety: reload() may run on any thread while gRPC's threads call
// the callback.

#include <grpcpp/grpcpp.h>

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "acomms/v1/config.pb.h"

namespace acomms::service {

class TlsCertificates {
 public:
  // Reads and checks the files of `files` (grpc.tls); throws
  // core::PemFileError naming the file and the reason.
  explicit TlsCertificates(const v1::TlsConfig& files);
  ~TlsCertificates();
  TlsCertificates(const TlsCertificates&) = delete;
  TlsCertificates& operator=(const TlsCertificates&) = delete;

  // For ServerBuilder::AddListeningPort. This object must outlive the server.
  std::shared_ptr<grpc::ServerCredentials> credentials();

  // Re-reads the files; on success new connections get them. Throws
  // core::PemFileError (the current certificates stay in use).
  void reload();

  // The latest certificate read ("/CN=..., valid until ..."), for the log.
  std::string description() const;

  // Whether clients must present a certificate (client_ca_file is set).
  bool mutual() const { return !files_.client_ca_file().empty(); }

 private:
  struct Files {
    std::string client_ca;  // empty without mutual TLS
    std::string cert;
    std::string key;
  };
  Files load() const;

  // grpc_ssl_server_certificate_config_callback.
  static int fetch(void* self, void* config);

  v1::TlsConfig files_;
  mutable std::mutex mutex_;
  std::optional<Files> pending_;  // read, checked, not yet handed to gRPC
  std::string description_;       // of the latest certificate read
};

}  // namespace acomms::service
