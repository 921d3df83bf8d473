// core::read_*: every unusable TLS file is refused with the setting, the path
// and the reason (expired when, valid from when, not PEM, another key).
// Certificates are made here with OpenSSL, at fixed dates.

#include "core/pem_files.h"

#include <gtest/gtest.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>

namespace acomms::core {
namespace {

namespace fs = std::filesystem;

struct KeyFree {
  void operator()(EVP_PKEY* key) const { EVP_PKEY_free(key); }
};
using Key = std::unique_ptr<EVP_PKEY, KeyFree>;

Key new_key() { return Key(EVP_EC_gen("P-256")); }

// A self-signed certificate for `cn`, valid from `not_before` to `not_after`
// (seconds since the epoch), in PEM.
std::string certificate(const std::string& cn, EVP_PKEY* key, time_t not_before, time_t not_after) {
  X509* cert = X509_new();
  X509_set_version(cert, 2);
  ASN1_INTEGER_set(X509_get_serialNumber(cert), 1);
  ASN1_TIME_set(X509_getm_notBefore(cert), not_before);
  ASN1_TIME_set(X509_getm_notAfter(cert), not_after);
  X509_NAME* name = X509_get_subject_name(cert);
  X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_ASC, reinterpret_cast<const unsigned char*>(cn.c_str()), -1,
                             -1, 0);
  X509_set_issuer_name(cert, name);
  X509_set_pubkey(cert, key);
  X509_sign(cert, key, EVP_sha256());
  BIO* bio = BIO_new(BIO_s_mem());
  PEM_write_bio_X509(bio, cert);
  char* data = nullptr;
  long size = BIO_get_mem_data(bio, &data);
  std::string pem(data, size);
  BIO_free(bio);
  X509_free(cert);
  return pem;
}

std::string private_key(EVP_PKEY* key) {
  BIO* bio = BIO_new(BIO_s_mem());
  PEM_write_bio_PrivateKey(bio, key, nullptr, nullptr, 0, nullptr, nullptr);
  char* data = nullptr;
  long size = BIO_get_mem_data(bio, &data);
  std::string pem(data, size);
  BIO_free(bio);
  return pem;
}

constexpr time_t k2020 = 1577836800;  // 2020-01-01 00:00:00 UTC
constexpr time_t kDay = 86400;
constexpr time_t kNow = k2020 + 100 * kDay;

class PemFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("acomms-pem-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  PemFile write(const std::string& setting, const std::string& name, const std::string& text) {
    std::ofstream((dir_ / name).string()) << text;
    return {setting, (dir_ / name).string()};
  }
  template <typename Read>
  std::string error_of(Read read) {
    try {
      read();
    } catch (const PemFileError& e) {
      return e.what();
    }
    return "(no error)";
  }
  fs::path dir_;
};

TEST_F(PemFilesTest, ACertificateValidNowAndItsKeyAreRead) {
  Key key = new_key();
  std::string cert_pem = certificate("acommsd", key.get(), k2020, k2020 + 365 * kDay);
  PemFile cert = write("--cert", "c.pem", cert_pem);
  EXPECT_EQ(read_certificate(cert, kNow), cert_pem);
  std::string key_pem = private_key(key.get());
  EXPECT_EQ(read_private_key(write("--key", "c.key", key_pem), cert_pem, cert), key_pem);
  EXPECT_EQ(describe_certificate(cert_pem), "/CN=acommsd, valid until 2020-12-31 00:00:00 UTC");
}

TEST_F(PemFilesTest, AnExpiredCertificateIsNamedWithItsEndDate) {
  Key key = new_key();
  PemFile cert = write("grpc.tls.cert_file", "old.pem", certificate("old", key.get(), k2020, k2020 + kDay));
  EXPECT_EQ(error_of([&] { read_certificate(cert, kNow); }),
            "grpc.tls.cert_file " + cert.path +
                ": certificate /CN=old expired on 2020-01-02 00:00:00 UTC (issue a new one)");
}

TEST_F(PemFilesTest, ANotYetValidCertificateIsNamedWithItsStartDate) {
  Key key = new_key();
  PemFile cert = write("--cert", "new.pem", certificate("new", key.get(), kNow + kDay, kNow + 2 * kDay));
  EXPECT_EQ(error_of([&] { read_certificate(cert, kNow); }),
            "--cert " + cert.path +
                ": certificate /CN=new is not valid until 2020-04-11 00:00:00 UTC (check this machine's "
                "clock, or reissue it)");
}

TEST_F(PemFilesTest, AnExpiredCaAmongTheTrustedOnesIsNamed) {
  Key a = new_key();
  Key b = new_key();
  PemFile cas = write("--ca", "cas.pem",
                      certificate("good CA", a.get(), k2020, kNow + kDay) +
                          certificate("stale CA", b.get(), k2020, k2020 + kDay));
  EXPECT_EQ(error_of([&] { read_ca_certificates(cas, kNow); }),
            "--ca " + cas.path + ": CA certificate /CN=stale CA expired on 2020-01-02 00:00:00 UTC (issue a new one)");
}

TEST_F(PemFilesTest, AFileWithoutACertificateOrMissingIsNamed) {
  Key key = new_key();
  PemFile not_cert = write("--cert", "key-not-cert.pem", private_key(key.get()));
  EXPECT_EQ(error_of([&] { read_certificate(not_cert, kNow); }),
            "--cert " + not_cert.path + ": no PEM certificate in it (expected \"-----BEGIN CERTIFICATE-----\")");
  PemFile missing{"grpc.tls.client_ca_file", (dir_ / "absent.pem").string()};
  EXPECT_EQ(error_of([&] { read_ca_certificates(missing, kNow); }),
            "grpc.tls.client_ca_file " + missing.path + ": cannot read: No such file or directory");
}

TEST_F(PemFilesTest, AKeyOfAnotherCertificateOrNoKeyIsNamed) {
  Key key = new_key();
  Key other = new_key();
  std::string cert_pem = certificate("acommsd", key.get(), k2020, kNow + kDay);
  PemFile cert = write("grpc.tls.cert_file", "s.pem", cert_pem);
  PemFile wrong = write("grpc.tls.key_file", "other.key", private_key(other.get()));
  EXPECT_EQ(error_of([&] { read_private_key(wrong, cert_pem, cert); }),
            "grpc.tls.key_file " + wrong.path + ": this key does not belong to the certificate in grpc.tls.cert_file " +
                cert.path);
  PemFile not_key = write("grpc.tls.key_file", "cert-not-key.pem", cert_pem);
  EXPECT_EQ(error_of([&] { read_private_key(not_key, cert_pem, cert); }),
            "grpc.tls.key_file " + not_key.path +
                ": no unencrypted PEM private key in it (expected \"-----BEGIN PRIVATE KEY-----\")");
}

}  // namespace
}  // namespace acomms::core
