// Roles on the API over real mutual TLS (service/api_roles.h): certificates
// made here by the openssl command for a viewer, an operator, an admin and a
// client with no role; the unix socket given the operator role. Each role's
// allowed calls are served, and each refused call gets PERMISSION_DENIED
// naming the role it needs; every call above viewer is refused to the
// viewer (so an RPC that forgot its check fails here); acommsctl status
// shows the caller's role.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "acomms/v1/acomms.grpc.pb.h"
#include "acomms/v1/gram.grpc.pb.h"
#include "child_process.h"
#include "daemon_harness.h"

namespace acomms::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class ApiRolesTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::path("/tmp") / ("acomms-roles-" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    std::ofstream(*dir_ / "server.ext") << "subjectAltName=IP:127.0.0.1\n";
    std::ofstream(*dir_ / "client.ext") << "extendedKeyUsage=clientAuth\n";
    openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out", key("ca")});
    openssl({"req", "-x509", "-new", "-key", key("ca"), "-out", pem("ca"), "-days", "30", "-subj", "/CN=roles CA"});
    issue("server", "acommsd", "server.ext");
    for (const char* client : {"watch", "ops", "boss", "nobody"}) issue(client, client, "client.ext");
    port_ = free_tcp_port();
    std::ofstream(*dir_ / "acommsd.conf")
        << "data_dir: \"" << (*dir_ / "data").string() << "\"\n"
        << "grpc { unix_socket: \"" << socket() << "\" tcp_listen: \"127.0.0.1:" << port_ << "\"\n"
        << "  tls { cert_file: \"" << pem("server") << "\" key_file: \"" << key("server") << "\" client_ca_file: \""
        << pem("ca") << "\" } }\n"
        << "driver { name: \"sim\" modem_id: 3 }\n"
        << "dccl { proto_files: \"" << ACOMMS_SOURCE_DIR << "/examples/messages.proto\" }\n"
        << "auth { client { common_name: \"watch\" role: \"viewer\" }\n"
        << "       client { common_name: \"ops\" role: \"operator\" }\n"
        << "       client { common_name: \"boss\" role: \"admin\" }\n"
        << "       unix_socket_role: \"operator\" }\n";
    daemon_ = new ChildProcess(ACOMMSD_BINARY, {"--config", (*dir_ / "acommsd.conf").string()},
                               (*dir_ / "acommsd").string());
    ASSERT_TRUE(wait_serving(*daemon_, socket())) << daemon_->stderr_text();
  }
  static void TearDownTestSuite() {
    delete daemon_;
    fs::remove_all(*dir_);
    delete dir_;
  }

  static void openssl(const std::vector<std::string>& args) {
    RunResult result = run("/usr/bin/openssl", args, (*dir_ / "openssl").string());
    ASSERT_EQ(result.exit_code, 0) << "openssl " << args[0] << ": " << result.err;
  }
  static void issue(const std::string& name, const std::string& cn, const std::string& ext) {
    openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out", key(name)});
    const std::string csr = (*dir_ / (name + ".csr")).string();
    openssl({"req", "-new", "-key", key(name), "-out", csr, "-subj", "/CN=" + cn});
    openssl({"x509", "-req", "-in", csr, "-CA", pem("ca"), "-CAkey", key("ca"), "-set_serial",
             std::to_string(++serial_), "-days", "30", "-extfile", (*dir_ / ext).string(), "-out", pem(name)});
  }
  static std::string pem(const std::string& name) { return (*dir_ / (name + ".pem")).string(); }
  static std::string key(const std::string& name) { return (*dir_ / (name + ".key")).string(); }
  static std::string socket() { return (*dir_ / "api.sock").string(); }

  // A channel presenting `client`'s certificate.
  static std::shared_ptr<grpc::Channel> channel(const std::string& client) {
    grpc::SslCredentialsOptions ssl;
    ssl.pem_root_certs = read_text(pem("ca"));
    ssl.pem_cert_chain = read_text(pem(client));
    ssl.pem_private_key = read_text(key(client));
    grpc::ChannelArguments args;
    args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
    return grpc::CreateCustomChannel("127.0.0.1:" + std::to_string(port_), grpc::SslCredentials(ssl), args);
  }

  // Every call above viewer, made with an empty (or harmless) request:
  // name -> the status it got.
  static std::map<std::string, grpc::Status> privileged_calls(const std::shared_ptr<grpc::Channel>& channel) {
    auto acomms = v1::Acomms::NewStub(channel);
    auto gram = v1::Gram::NewStub(channel);
    std::map<std::string, grpc::Status> got;
    auto unary = [&](const std::string& name, const std::function<grpc::Status(grpc::ClientContext*)>& call) {
      grpc::ClientContext context;
      context.set_deadline(std::chrono::system_clock::now() + 10s);
      got[name] = call(&context);
    };
    unary("Submit", [&](auto* c) { v1::SubmitResponse r; return acomms->Submit(c, v1::SubmitRequest(), &r); });
    unary("Cancel", [&](auto* c) { v1::CancelResponse r; return acomms->Cancel(c, v1::CancelRequest(), &r); });
    unary("SubmitNavigation", [&](auto* c) {
      v1::SubmitNavigationResponse r;
      auto writer = acomms->SubmitNavigation(c, &r);
      writer->WritesDone();
      return writer->Finish();
    });
    unary("LoadDefinitions",
          [&](auto* c) { v1::LoadDefinitionsResponse r; return acomms->LoadDefinitions(c, v1::LoadDefinitionsRequest(), &r); });
    unary("Flush", [&](auto* c) { v1::FlushResponse r; return acomms->Flush(c, v1::FlushRequest(), &r); });
    unary("SetCycle", [&](auto* c) { v1::SetCycleResponse r; return acomms->SetCycle(c, v1::SetCycleRequest(), &r); });
    unary("DriverSpecific",
          [&](auto* c) { v1::DriverSpecificResponse r; return acomms->DriverSpecific(c, v1::DriverSpecificRequest(), &r); });
    unary("TransmissionLoss", [&](auto* c) {
      v1::TransmissionLossReply r;
      return gram->TransmissionLoss(c, v1::TransmissionLossRequest(), &r);
    });
    unary("Arrivals", [&](auto* c) { v1::ArrivalsReply r; return gram->Arrivals(c, v1::ArrivalsRequest(), &r); });
    unary("DepthObjective", [&](auto* c) {
      v1::DepthObjectiveResponse r;
      return gram->DepthObjective(c, v1::DepthObjectiveRequest(), &r);
    });
    unary("UpdateEnvironment", [&](auto* c) {
      gram::KnownEnvironment r;
      return gram->UpdateEnvironment(c, v1::UpdateEnvironmentRequest(), &r);
    });
    return got;
  }

  static grpc::Status get_status(const std::shared_ptr<grpc::Channel>& channel, v1::Status* status) {
    grpc::ClientContext context;
    context.set_deadline(std::chrono::system_clock::now() + 10s);
    return v1::Acomms::NewStub(channel)->GetStatus(&context, v1::GetStatusRequest(), status);
  }

  static fs::path* dir_;
  static int port_;
  static int serial_;
  static ChildProcess* daemon_;
};

fs::path* ApiRolesTest::dir_ = nullptr;
int ApiRolesTest::port_ = 0;
int ApiRolesTest::serial_ = 100;
ChildProcess* ApiRolesTest::daemon_ = nullptr;

const std::set<std::string> kAdminOnly = {"LoadDefinitions", "Flush", "SetCycle", "DriverSpecific"};

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(ApiRolesTest, ViewerReadsAndIsRefusedEveryCallAboveIt) {
  auto viewer = channel("watch");
  v1::Status status;
  ASSERT_TRUE(get_status(viewer, &status).ok());
  EXPECT_EQ(status.caller_role(), "viewer");
  {
    grpc::ClientContext context;
    v1::ListQueuedResponse queued;
    EXPECT_TRUE(v1::Acomms::NewStub(viewer)->ListQueued(&context, v1::ListQueuedRequest(), &queued).ok());
  }
  for (const auto& [name, result] : privileged_calls(viewer)) {
    EXPECT_EQ(result.error_code(), grpc::StatusCode::PERMISSION_DENIED) << name << ": " << result.error_message();
    const std::string needed = kAdminOnly.count(name) ? "admin" : "operator";
    EXPECT_TRUE(has(result.error_message(), name + " needs role " + needed + " or higher; this client has role viewer "
                                                                             "(certificate CN=watch)"))
        << name << ": " << result.error_message();
  }
}

TEST_F(ApiRolesTest, OperatorActsOnTheWaterButIsRefusedAdminCalls) {
  auto operator_channel = channel("ops");
  v1::Status status;
  ASSERT_TRUE(get_status(operator_channel, &status).ok());
  EXPECT_EQ(status.caller_role(), "operator");
  for (const auto& [name, result] : privileged_calls(operator_channel)) {
    if (kAdminOnly.count(name)) {
      EXPECT_EQ(result.error_code(), grpc::StatusCode::PERMISSION_DENIED) << name;
      EXPECT_TRUE(has(result.error_message(), name + " needs role admin or higher")) << result.error_message();
    } else {
      // Past the role check: the empty request itself is what is refused.
      EXPECT_NE(result.error_code(), grpc::StatusCode::PERMISSION_DENIED) << name << ": " << result.error_message();
    }
  }
  grpc::ClientContext context;
  v1::SubmitRequest submit;
  submit.set_type("example.Command");
  submit.set_json(R"({"src": 3, "dest": 1, "time": 1700000000, "kind": "SURFACE"})");
  v1::SubmitResponse submitted;
  grpc::Status result = v1::Acomms::NewStub(operator_channel)->Submit(&context, submit, &submitted);
  EXPECT_TRUE(result.ok()) << result.error_message();
}

TEST_F(ApiRolesTest, AdminPassesEveryRoleCheck) {
  for (const auto& [name, result] : privileged_calls(channel("boss"))) {
    EXPECT_NE(result.error_code(), grpc::StatusCode::PERMISSION_DENIED) << name << ": " << result.error_message();
  }
  grpc::ClientContext context;
  v1::FlushRequest flush;
  flush.set_type("example.Command");
  v1::FlushResponse flushed;
  EXPECT_TRUE(v1::Acomms::NewStub(channel("boss"))->Flush(&context, flush, &flushed).ok());
}

TEST_F(ApiRolesTest, CertificateWithoutARoleIsRefusedEverything) {
  v1::Status status;
  grpc::Status result = get_status(channel("nobody"), &status);
  EXPECT_EQ(result.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_TRUE(has(result.error_message(), "GetStatus needs role viewer or higher; this client has no role "
                                          "(certificate CN=nobody)"))
      << result.error_message();
}

TEST_F(ApiRolesTest, UnixSocketHasItsConfiguredRole) {
  v1::Status status;
  ASSERT_TRUE(get_status(grpc::CreateChannel("unix:" + socket(), grpc::InsecureChannelCredentials()), &status).ok());
  EXPECT_EQ(status.caller_role(), "operator");
  grpc::ClientContext context;
  v1::FlushRequest flush;
  flush.set_type("example.Command");
  v1::FlushResponse flushed;
  grpc::Status result = api(socket())->Flush(&context, flush, &flushed);
  EXPECT_EQ(result.error_code(), grpc::StatusCode::PERMISSION_DENIED);
  EXPECT_TRUE(has(result.error_message(), "Flush needs role admin or higher; this client has role operator (unix "
                                          "socket)"))
      << result.error_message();
}

TEST_F(ApiRolesTest, AcommsctlStatusShowsTheCallersRole) {
  RunResult result = run(ACOMMSCTL_BINARY,
                         {"--socket", "tcp:127.0.0.1:" + std::to_string(port_), "--ca", pem("ca"), "--cert",
                          pem("watch"), "--key", key("watch"), "status"},
                         (*dir_ / "ctl").string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(has(result.out, "your role:       viewer (certificate CN=watch)")) << result.out;
}

}  // namespace
}  // namespace acomms::testing
