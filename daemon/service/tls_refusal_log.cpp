#include "service/tls_refusal_log.h"

#include <grpc/support/log.h>
#include <spdlog/spdlog.h>

#include <mutex>
#include <string>
#include <string_view>

namespace acomms::service {
namespace {

std::mutex files_mutex;
v1::TlsConfig logged_files;  // guarded by files_mutex

bool contains(std::string_view text, std::string_view part) { return text.find(part) != std::string_view::npos; }

std::string explain_refusal(std::string_view openssl) {
  std::lock_guard lock(files_mutex);
  const std::string client_ca = "grpc.tls.client_ca_file " + logged_files.client_ca_file();
  if (contains(openssl, "peer did not return a certificate")) {
    return "refused a client without a certificate (" + client_ca + " requires one)";
  }
  if (contains(openssl, "certificate verify failed")) {
    return "refused a client certificate that does not verify against " + client_ca +
           " (issued by another CA, expired or not yet valid)";
  }
  if (contains(openssl, "wrong version number") || contains(openssl, "http request") ||
      contains(openssl, "unknown protocol")) {
    return "refused a client that does not speak TLS (plaintext: acommsctl needs --ca, not --insecure)";
  }
  if (contains(openssl, "unknown ca") || contains(openssl, "bad certificate")) {
    return "a client refused this daemon's certificate, grpc.tls.cert_file " + logged_files.cert_file() +
           " (give the client the CA that issued it: acommsctl --ca)";
  }
  return "TLS handshake failed";
}

void forward(gpr_log_func_args* args) {
  std::string_view message = args->message;
  constexpr std::string_view kHandshake = "Handshake failed with fatal error";
  if (message.rfind(kHandshake, 0) == 0) {
    spdlog::warn("grpc: {} [{}]", explain_refusal(message), message);
    return;
  }
  switch (args->severity) {
    case GPR_LOG_SEVERITY_ERROR: spdlog::error("grpc: {} ({}:{})", message, args->file, args->line); break;
    case GPR_LOG_SEVERITY_INFO: spdlog::info("grpc: {}", message); break;
    default: spdlog::debug("grpc: {}", message); break;
  }
}

}  // namespace

void log_tls_refusals(const v1::TlsConfig& files) {
  {
    std::lock_guard lock(files_mutex);
    logged_files = files;
  }
  gpr_set_log_function(forward);
}

}  // namespace acomms::service
