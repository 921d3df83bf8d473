#include "core/pem_files.h"

#include <openssl/err.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

namespace acomms::core {
namespace {

struct BioFree {
  void operator()(BIO* bio) const { BIO_free(bio); }
};
struct X509Free {
  void operator()(X509* cert) const { X509_free(cert); }
};
struct KeyFree {
  void operator()(EVP_PKEY* key) const { EVP_PKEY_free(key); }
};
using Certificate = std::unique_ptr<X509, X509Free>;

std::string where(const PemFile& file) { return file.setting + " " + file.path; }

std::string read_file(const PemFile& file) {
  std::ifstream in(file.path, std::ios::binary);
  if (!in) throw PemFileError(where(file) + ": cannot read: " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<Certificate> parse_certificates(const std::string& pem) {
  std::unique_ptr<BIO, BioFree> bio(BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size())));
  std::vector<Certificate> certificates;
  while (X509* cert = PEM_read_bio_X509(bio.get(), nullptr, nullptr, nullptr)) {
    certificates.emplace_back(cert);
  }
  ERR_clear_error();  // the read that ends the loop leaves "no start line"
  return certificates;
}

std::string utc(const ASN1_TIME* time) {
  std::tm parts{};
  if (ASN1_TIME_to_tm(time, &parts) != 1) return "(unreadable time)";
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M:%S UTC", &parts);
  return text;
}

std::string subject(X509* cert) {
  char name[256];
  X509_NAME_oneline(X509_get_subject_name(cert), name, sizeof(name));
  return name;
}

// Why `cert` cannot be used at `now`, or empty.
std::string validity_problem(X509* cert, std::time_t now) {
  std::time_t at = now;
  if (X509_cmp_time(X509_get0_notBefore(cert), &at) > 0) {
    return "certificate " + subject(cert) + " is not valid until " +
           utc(X509_get0_notBefore(cert)) + " (check this machine's clock, or reissue it)";
  }
  if (X509_cmp_time(X509_get0_notAfter(cert), &at) < 0) {
    return "certificate " + subject(cert) + " expired on " + utc(X509_get0_notAfter(cert)) +
           " (issue a new one)";
  }
  return {};
}

std::vector<Certificate> read_certificates(const PemFile& file, const std::string& pem) {
  std::vector<Certificate> certificates = parse_certificates(pem);
  if (certificates.empty()) {
    throw PemFileError(where(file) + ": no PEM certificate in it (expected \"-----BEGIN CERTIFICATE-----\")");
  }
  return certificates;
}

}  // namespace

std::string read_certificate(const PemFile& file, std::time_t now) {
  std::string pem = read_file(file);
  std::vector<Certificate> chain = read_certificates(file, pem);
  // Only the first is this end's own; the rest are intermediates, whose
  // validity the peer checks against its own trust.
  std::string problem = validity_problem(chain.front().get(), now);
  if (!problem.empty()) throw PemFileError(where(file) + ": " + problem);
  return pem;
}

std::string read_ca_certificates(const PemFile& file, std::time_t now) {
  std::string pem = read_file(file);
  for (const Certificate& cert : read_certificates(file, pem)) {
    std::string problem = validity_problem(cert.get(), now);
    if (!problem.empty()) throw PemFileError(where(file) + ": CA " + problem);
  }
  return pem;
}

std::string read_private_key(const PemFile& file, const std::string& certificate_pem,
                             const PemFile& certificate) {
  std::string pem = read_file(file);
  std::unique_ptr<BIO, BioFree> bio(BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size())));
  std::unique_ptr<EVP_PKEY, KeyFree> key(PEM_read_bio_PrivateKey(bio.get(), nullptr, nullptr, nullptr));
  ERR_clear_error();
  if (!key) {
    throw PemFileError(where(file) +
                       ": no unencrypted PEM private key in it (expected \"-----BEGIN PRIVATE KEY-----\")");
  }
  std::vector<Certificate> chain = parse_certificates(certificate_pem);
  if (chain.empty() || X509_check_private_key(chain.front().get(), key.get()) != 1) {
    ERR_clear_error();
    throw PemFileError(where(file) + ": this key does not belong to the certificate in " +
                       where(certificate));
  }
  return pem;
}

std::string describe_certificate(const std::string& certificate_pem) {
  std::vector<Certificate> chain = parse_certificates(certificate_pem);
  if (chain.empty()) return "(no certificate)";
  return subject(chain.front().get()) + ", valid until " + utc(X509_get0_notAfter(chain.front().get()));
}

}  // namespace acomms::core
