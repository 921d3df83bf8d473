// TLS on the daemon's TCP listener, against the real acommsd and acommsctl
// with certificates made here by the openssl command: one CA for the daemon
// and its clients, another CA whose clients must be refused, an expired and
// a not-yet-valid certificate. Only 127.0.0.1 is ever listened on.
//
// Proven: mutual TLS serves the right client and refuses one without a
// certificate, one from another CA, one with an expired certificate and a
// plaintext one, each with a message that says what to change; the daemon's
// own bad files stop it naming the file; SIGHUP swaps the certificate for
// new connections (and a bad file on SIGHUP keeps the old one); a config
// from before TLS fails with both fixes named; insecure_tcp serves plaintext
// with a warning.

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kAcommsd = ACOMMSD_BINARY;
const std::string kAcommsctl = ACOMMSCTL_BINARY;
const std::string kOpenssl = "/usr/bin/openssl";

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The certificates every test uses, made once. Names: <name>.pem and
// <name>.key in dir().
class Certificates {
 public:
  explicit Certificates(const fs::path& dir) : dir_(dir) {
    fs::create_directories(dir_);
    std::ofstream(dir_ / "server.ext") << "subjectAltName=IP:127.0.0.1,DNS:localhost\n";
    std::ofstream(dir_ / "client.ext") << "extendedKeyUsage=clientAuth\n";
    make_ca("ca", "acomms test CA");
    make_ca("other-ca", "some other CA");
    issue("server", "acommsd", "ca", "server.ext");
    issue("renewed-server", "acommsd renewed", "ca", "server.ext");
    issue("client", "operator", "ca", "client.ext");
    issue("other-client", "stranger", "other-ca", "client.ext");
    issue_dated("expired-client", "expired operator", "20200101000000Z", "20200102000000Z");
    issue_dated("future-server", "acommsd from the future", "20990101000000Z", "20990102000000Z");
  }
  std::string pem(const std::string& name) const { return (dir_ / (name + ".pem")).string(); }
  std::string key(const std::string& name) const { return (dir_ / (name + ".key")).string(); }
  const fs::path& dir() const { return dir_; }

 private:
  void openssl(const std::vector<std::string>& args) {
    RunResult result = run(kOpenssl, args, (dir_ / "openssl").string());
    ASSERT_EQ(result.exit_code, 0) << "openssl " << args[0] << ": " << result.err;
  }
  void new_key(const std::string& name) {
    openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out", key(name)});
  }
  void make_ca(const std::string& name, const std::string& cn) {
    new_key(name);
    openssl({"req", "-x509", "-new", "-key", key(name), "-out", pem(name), "-days", "30", "-subj",
             "/CN=" + cn});
  }
  std::string request(const std::string& name, const std::string& cn) {
    new_key(name);
    std::string csr = (dir_ / (name + ".csr")).string();
    openssl({"req", "-new", "-key", key(name), "-out", csr, "-subj", "/CN=" + cn});
    return csr;
  }
  void issue(const std::string& name, const std::string& cn, const std::string& ca, const std::string& ext) {
    std::string csr = request(name, cn);
    openssl({"x509", "-req", "-in", csr, "-CA", pem(ca), "-CAkey", key(ca), "-set_serial",
             std::to_string(++serial_), "-days", "30", "-extfile", (dir_ / ext).string(), "-out", pem(name)});
  }
  // OpenSSL 3.0's `x509` cannot set dates in the past or the future; `ca`
  // can, with a small database of its own.
  void issue_dated(const std::string& name, const std::string& cn, const std::string& start,
                   const std::string& end) {
    std::string csr = request(name, cn);
    fs::path db = dir_ / ("db-" + name);
    fs::create_directories(db);
    std::ofstream(db / "index.txt");
    std::ofstream(db / "serial") << "1" << ++serial_ << "\n";
    std::ofstream(db / "ca.cnf") << "[ca]\ndefault_ca = test\n[test]\ndatabase = " << (db / "index.txt").string()
                                 << "\nnew_certs_dir = " << db.string() << "\nserial = " << (db / "serial").string()
                                 << "\ndefault_md = sha256\npolicy = any\nx509_extensions = ext\n"
                                 << "[any]\ncommonName = supplied\n"
                                 << "[ext]\nsubjectAltName = IP:127.0.0.1\n";
    openssl({"ca", "-batch", "-config", (db / "ca.cnf").string(), "-cert", pem("ca"), "-keyfile", key("ca"),
             "-in", csr, "-out", pem(name), "-notext", "-startdate", start, "-enddate", end});
  }

  fs::path dir_;
  int serial_ = 100;
};

class TlsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    certs_ = new Certificates(fs::path("/tmp") / ("acomms-tls-" + std::to_string(::getpid())));
  }
  static void TearDownTestSuite() {
    fs::remove_all(certs_->dir());
    delete certs_;
  }

  void SetUp() override {
    dir_ = fs::path("/tmp") / ("acomms-tls-it-" + std::to_string(::getpid()) + "-" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    socket_ = (dir_ / "api.sock").string();
    port_ = free_tcp_port();
    address_ = "127.0.0.1:" + std::to_string(port_);
    // The daemon reads its certificate from a copy, so that SIGHUP tests can
    // replace it.
    fs::copy_file(certs_->pem("server"), dir_ / "server.pem");
    fs::copy_file(certs_->key("server"), dir_ / "server.key");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `grpc_extra` goes inside grpc { }.
  std::string write_config(const std::string& grpc_extra) {
    std::string path = (dir_ / "acommsd.conf").string();
    std::ofstream(path) << "data_dir: \"" << (dir_ / "data").string() << "\"\n"
                        << "grpc {\n  unix_socket: \"" << socket_ << "\"\n  tcp_listen: \"" << address_
                        << "\"\n" << grpc_extra << "}\n"
                        << "driver { name: \"sim\" modem_id: 3 }\n";
    return path;
  }
  std::string tls_block(const std::string& cert, const std::string& key, bool mutual = true) {
    return "  tls {\n    cert_file: \"" + cert + "\"\n    key_file: \"" + key + "\"\n" +
           (mutual ? "    client_ca_file: \"" + certs_->pem("ca") + "\"\n" : "") + "  }\n";
  }
  std::string mutual_tls_config() {
    return write_config(tls_block((dir_ / "server.pem").string(), (dir_ / "server.key").string()));
  }

  std::unique_ptr<ChildProcess> start_daemon(const std::string& config) {
    auto daemon = std::make_unique<ChildProcess>(kAcommsd, std::vector<std::string>{"--config", config},
                                                 (dir_ / "acommsd").string());
    EXPECT_TRUE(wait_serving(*daemon, socket_)) << daemon->stderr_text();
    return daemon;
  }

  RunResult acommsctl(std::vector<std::string> tls_args) {
    std::vector<std::string> args{"--socket", "tcp:" + address_, "--timeout", "5"};
    args.insert(args.end(), tls_args.begin(), tls_args.end());
    args.insert(args.end(), {"status", "--json"});
    return run(kAcommsctl, args, (dir_ / "ctl").string());
  }

  // A fresh connection (no subchannel shared with earlier channels) that
  // makes one call; the daemon's certificate CN, or the call's error.
  std::string call_over_tls(const std::string& cert, const std::string& key) {
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = read_text(certs_->pem("ca"));
    if (!cert.empty()) {
      ssl.pem_cert_chain = read_text(cert);
      ssl.pem_private_key = read_text(key);
    }
    return call(grpc::SslCredentials(ssl));
  }
  std::string call(const std::shared_ptr<grpc::ChannelCredentials>& credentials) {
    grpc::ChannelArguments args;
    args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
    auto stub = v1::Acomms::NewStub(grpc::CreateCustomChannel(address_, credentials, args));
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + 5s);
    v1::Status status;
    grpc::Status result = stub->GetStatus(&context, v1::GetStatusRequest(), &status);
    if (!result.ok()) return "error: " + result.error_message();
    auto cn = context.auth_context()->FindPropertyValues("x509_common_name");
    return cn.empty() ? "served (no certificate)" : "CN=" + std::string(cn.front().data(), cn.front().size());
  }

  static Certificates* certs_;
  fs::path dir_;
  std::string socket_;
  int port_ = 0;
  std::string address_;
};

Certificates* TlsTest::certs_ = nullptr;

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The daemon logs a refusal when the handshake fails, which may be just
// after the client has given up.
::testing::AssertionResult daemon_says(ChildProcess& daemon, const std::string& line) {
  if (wait_until([&] { return has(daemon.stderr_text(), line); }, 10s)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "the daemon did not log \"" << line << "\":\n" << daemon.stderr_text();
}

TEST_F(TlsTest, MutualTlsServesAClientWithACertificateFromTheClientCa) {
  auto daemon = start_daemon(mutual_tls_config());
  RunResult ok = acommsctl({"--ca", certs_->pem("ca"), "--cert", certs_->pem("client"), "--key",
                            certs_->key("client")});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(has(ok.out, "\"version\"")) << ok.out;
  EXPECT_EQ(call_over_tls(certs_->pem("client"), certs_->key("client")), "CN=acommsd");
  EXPECT_TRUE(has(daemon->stderr_text(), "mutual TLS")) << daemon->stderr_text();
}

TEST_F(TlsTest, AcommsctlTakesTheTlsFilesFromTheEnvironment) {
  auto daemon = start_daemon(mutual_tls_config());
  ChildProcess ctl(kAcommsctl, {"--socket", "tcp:" + address_, "status"}, (dir_ / "env").string(),
                   {{"ACOMMSD_CA", certs_->pem("ca")},
                    {"ACOMMSD_CERT", certs_->pem("client")},
                    {"ACOMMSD_KEY", certs_->key("client")}});
  EXPECT_EQ(ctl.wait(20s), 0) << ctl.stderr_text();
}

TEST_F(TlsTest, MutualTlsRefusesAClientWithoutACertificate) {
  auto daemon = start_daemon(mutual_tls_config());
  RunResult refused = acommsctl({"--ca", certs_->pem("ca")});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_TRUE(has(refused.err, "cannot reach acommsd at tcp:" + address_ +
                                   ": the daemon requires a client certificate (mutual TLS): pass "
                                   "--cert and --key"))
      << refused.err;
  EXPECT_TRUE(has(call_over_tls("", ""), "error: ")) << "served without a client certificate";
  EXPECT_TRUE(daemon_says(*daemon, "refused a client without a certificate (grpc.tls.client_ca_file " +
                                       certs_->pem("ca") + " requires one)"));
}

TEST_F(TlsTest, MutualTlsRefusesAClientCertificateFromAnotherCa) {
  auto daemon = start_daemon(mutual_tls_config());
  RunResult refused = acommsctl({"--ca", certs_->pem("ca"), "--cert", certs_->pem("other-client"), "--key",
                                 certs_->key("other-client")});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_TRUE(has(refused.err, "the daemon refused the client certificate --cert " +
                                   certs_->pem("other-client") +
                                   ": it is not issued by the CA in the daemon's grpc.tls.client_ca_file"))
      << refused.err;
  EXPECT_TRUE(has(call_over_tls(certs_->pem("other-client"), certs_->key("other-client")), "error: "));
  EXPECT_TRUE(daemon_says(*daemon, "refused a client certificate that does not verify against "
                                   "grpc.tls.client_ca_file " + certs_->pem("ca")));
}

TEST_F(TlsTest, AnExpiredClientCertificateIsNamedByAcommsctlAndRefusedByTheDaemon) {
  auto daemon = start_daemon(mutual_tls_config());
  RunResult refused = acommsctl({"--ca", certs_->pem("ca"), "--cert", certs_->pem("expired-client"), "--key",
                                 certs_->key("expired-client")});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_TRUE(has(refused.err, "--cert " + certs_->pem("expired-client") +
                                   ": certificate /CN=expired operator expired on 2020-01-02 00:00:00 UTC"))
      << refused.err;
  // acommsctl stops before connecting; a client that does not check is
  // refused by the daemon.
  EXPECT_TRUE(has(call_over_tls(certs_->pem("expired-client"), certs_->key("expired-client")), "error: "));
  EXPECT_TRUE(daemon_says(*daemon, "refused a client certificate that does not verify against "
                                   "grpc.tls.client_ca_file " + certs_->pem("ca") +
                                   " (issued by another CA, expired or not yet valid)"));
}

TEST_F(TlsTest, APlaintextClientIsRefused) {
  auto daemon = start_daemon(mutual_tls_config());
  RunResult refused = acommsctl({"--insecure"});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_TRUE(has(refused.err, "no plaintext answer (the daemon serves TLS unless grpc.insecure_tcp is set: "
                               "drop --insecure and pass --ca)"))
      << refused.err;
  EXPECT_TRUE(has(call(grpc::InsecureChannelCredentials()), "error: "));
  EXPECT_TRUE(daemon_says(*daemon, "refused a client that does not speak TLS"));
}

TEST_F(TlsTest, ServerOnlyTlsServesAnyClientThatTrustsTheDaemon) {
  auto daemon = start_daemon(
      write_config(tls_block((dir_ / "server.pem").string(), (dir_ / "server.key").string(), false)));
  RunResult ok = acommsctl({"--ca", certs_->pem("ca")});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(call_over_tls("", ""), "CN=acommsd");
  // A client that trusts another CA does not accept the daemon.
  RunResult distrust = acommsctl({"--ca", certs_->pem("other-ca")});
  EXPECT_EQ(distrust.exit_code, 1);
  EXPECT_TRUE(has(distrust.err, "the daemon's certificate is not trusted by --ca " + certs_->pem("other-ca") +
                                    ": it is issued by another CA"))
      << distrust.err;
  EXPECT_TRUE(daemon_says(*daemon, "a client refused this daemon's certificate, grpc.tls.cert_file " +
                                       (dir_ / "server.pem").string()));
}

TEST_F(TlsTest, TheDaemonNamesItsOwnUnusableCertificateOrKeyAndDoesNotStart) {
  struct Case {
    std::string cert, key, expected;
  };
  std::vector<Case> cases{
      {certs_->pem("future-server"), certs_->key("future-server"),
       "grpc.tls.cert_file " + certs_->pem("future-server") +
           ": certificate /CN=acommsd from the future is not valid until 2099-01-01 00:00:00 UTC"},
      {certs_->pem("expired-client"), certs_->key("expired-client"),
       "grpc.tls.cert_file " + certs_->pem("expired-client") +
           ": certificate /CN=expired operator expired on 2020-01-02 00:00:00 UTC"},
      {certs_->pem("server"), certs_->key("client"),
       "grpc.tls.key_file " + certs_->key("client") +
           ": this key does not belong to the certificate in grpc.tls.cert_file " + certs_->pem("server")},
      {certs_->key("server"), certs_->key("server"),
       "grpc.tls.cert_file " + certs_->key("server") + ": no PEM certificate in it"},
      {(dir_ / "absent.pem").string(), certs_->key("server"),
       "grpc.tls.cert_file " + (dir_ / "absent.pem").string() + ": cannot read: No such file or directory"},
  };
  for (const Case& c : cases) {
    ChildProcess daemon(kAcommsd, {"--config", write_config(tls_block(c.cert, c.key))}, (dir_ / "bad").string());
    EXPECT_EQ(daemon.wait(20s), 1);
    EXPECT_TRUE(has(daemon.stderr_text(), c.expected)) << daemon.stderr_text();
  }
}

TEST_F(TlsTest, SighupServesTheRenewedCertificateToNewConnections) {
  auto daemon = start_daemon(mutual_tls_config());
  ASSERT_EQ(call_over_tls(certs_->pem("client"), certs_->key("client")), "CN=acommsd");

  // A bad file on SIGHUP: logged with its name, the old certificate stays.
  fs::copy_file(certs_->key("client"), dir_ / "server.key", fs::copy_options::overwrite_existing);
  daemon->signal(SIGHUP);
  EXPECT_TRUE(wait_until([&] { return has(daemon->stderr_text(), "reload failed"); }, 10s));
  EXPECT_TRUE(has(daemon->stderr_text(), "still serving the previous TLS certificates: grpc.tls.key_file " +
                                             (dir_ / "server.key").string() + ": this key does not belong"))
      << daemon->stderr_text();
  EXPECT_EQ(call_over_tls(certs_->pem("client"), certs_->key("client")), "CN=acommsd");

  fs::copy_file(certs_->pem("renewed-server"), dir_ / "server.pem", fs::copy_options::overwrite_existing);
  fs::copy_file(certs_->key("renewed-server"), dir_ / "server.key", fs::copy_options::overwrite_existing);
  daemon->signal(SIGHUP);
  EXPECT_TRUE(wait_until([&] { return has(daemon->stderr_text(), "reloaded TLS certificates"); }, 10s))
      << daemon->stderr_text();
  EXPECT_EQ(call_over_tls(certs_->pem("client"), certs_->key("client")), "CN=acommsd renewed");
  EXPECT_TRUE(daemon->running());
}

TEST_F(TlsTest, AConfigFromBeforeTlsFailsNamingBothFixes) {
  std::string config = write_config("");
  ChildProcess daemon(kAcommsd, {"--config", config}, (dir_ / "old").string());
  EXPECT_EQ(daemon.wait(20s), 1);
  std::string err = daemon.stderr_text();
  EXPECT_TRUE(has(err, config + ":4:3: field 'grpc.tcp_listen'")) << err;
  EXPECT_TRUE(has(err, "add grpc { tls { cert_file: \"...\" key_file: \"...\" } }")) << err;
  EXPECT_TRUE(has(err, "or set grpc { insecure_tcp: true }")) << err;
}

TEST_F(TlsTest, InsecureTcpServesPlaintextAndWarnsAtStart) {
  auto daemon = start_daemon(write_config("  insecure_tcp: true\n"));
  EXPECT_TRUE(has(daemon->stderr_text(), "is plaintext with no authentication (grpc.insecure_tcp: true)"))
      << daemon->stderr_text();
  RunResult ok = acommsctl({"--insecure"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(call(grpc::InsecureChannelCredentials()), "served (no certificate)");
  RunResult tls = acommsctl({"--ca", certs_->pem("ca")});
  EXPECT_EQ(tls.exit_code, 1);
  EXPECT_TRUE(has(tls.err, "no TLS answer (a daemon with grpc.insecure_tcp serves plaintext: pass --insecure)"))
      << tls.err;
}

}  // namespace
}  // namespace acomms::testing
