// acomms.v1.Gram through a real acommsd over its unix socket: requests per
// second and p99 latency (call to answer, gRPC included) of TransmissionLoss
// for bench_munk_query with gram.workers 1 and 2, cold (each request's
// source depth 1 µm apart: the same work, another cache key) and cached
// (the same request again). Clients keep 2 × workers calls in flight.
// gram_pool_bench measures the pool alone, in process. Figures depend on the
// machine's load; they are reported, not enforced.
//
//   build/tests/bench/gram_service_bench [--requests=N]
//   build/tests/bench/gram_service_bench --smoke     (what ctest runs)

#include <google/protobuf/text_format.h>
#include <grpcpp/grpcpp.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "acomms/v1/gram.grpc.pb.h"
#include "child_process.h"
#include "closed_loop.h"
#include "daemon_harness.h"
#include "gram/bellhop_import.h"

namespace {

namespace fs = std::filesystem;

using acomms::bench::ClosedLoopFigures;

ClosedLoopFigures drive(acomms::v1::Gram::Stub& stub, double source_depth, unsigned workers, bool cached,
                        int requests) {
  struct Call {
    grpc::ClientContext context;
    acomms::v1::TransmissionLossRequest request;
    acomms::v1::TransmissionLossReply reply;
  };
  std::once_flag first_failure;
  auto issue = [&](int index, std::function<void(bool)> done) {
    auto* call = new Call;
    call->request.mutable_header()->mutable_environment()->set_source_depth_m(
        cached ? source_depth : source_depth + 1e-6 * (index + 1));
    call->context.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    stub.async()->TransmissionLoss(&call->context, &call->request, &call->reply, [&, call, done](grpc::Status s) {
      delete call;
      if (!s.ok()) std::call_once(first_failure, [&] { std::fprintf(stderr, "%s\n", s.error_message().c_str()); });
      done(s.ok());
    });
  };
  if (cached) acomms::bench::run_closed_loop(1, 1, issue);  // warm: the one request, answered once by the model
  return acomms::bench::run_closed_loop(requests, static_cast<int>(2 * workers), issue);
}

}  // namespace

int main(int argc, char** argv) {
  int requests = 400;
  bool smoke = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--smoke") == 0) smoke = true;
    else if (std::strncmp(argv[i], "--requests=", 11) == 0) requests = std::max(10, std::atoi(argv[i] + 11));
    else {
      std::fprintf(stderr, "usage: gram_service_bench [--requests=N] [--smoke]\n");
      return 2;
    }
  }
  const auto env = acomms::gram::import_bellhop_env_file(std::string(ACOMMS_SHARED_DIR) +
                                                         "/conformance/gram/envs/bench_munk_query.env")
                       .environment;
  std::string base;
  google::protobuf::TextFormat::PrintToString(env, &base);
  const fs::path dir = fs::temp_directory_path() / ("acomms-gram-bench-" + std::to_string(::getpid()));
  int failures = 0;
  for (unsigned workers : {1u, 2u}) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string socket = (dir / "api.sock").string();
    std::ofstream(dir / "acommsd.conf") << "data_dir: \"" << (dir / "data").string() << "\"\n"
                                        << "grpc { unix_socket: \"" << socket << "\" }\n"
                                        << "gram { workers: " << workers << " queue_limit: 100 base {\n"
                                        << base << "} }\n";
    acomms::testing::ChildProcess daemon(ACOMMSD_BINARY, {"--config", (dir / "acommsd.conf").string()},
                                         (dir / "acommsd").string());
    if (!acomms::testing::wait_serving(daemon, socket)) {
      std::fprintf(stderr, "acommsd did not start: %s\n", daemon.stderr_text().c_str());
      return 1;
    }
    auto stub = acomms::v1::Gram::NewStub(grpc::CreateChannel("unix:" + socket, grpc::InsecureChannelCredentials()));
    for (bool cached : {false, true}) {
      const int n = smoke ? 10 : (cached ? requests * 10 : requests);
      const ClosedLoopFigures f = drive(*stub, env.source_depth_m(), workers, cached, n);
      std::printf("bench_munk_query via gRPC  %u worker(s)  %-6s  %6d requests  %9.1f requests/s  p50 %7.3f ms  "
                  "p99 %7.3f ms%s\n",
                  workers, cached ? "cached" : "cold", n, f.per_second, f.p50_ms, f.p99_ms, f.failed ? "  FAILED" : "");
      failures += f.failed;
    }
  }
  fs::remove_all(dir);
  return failures == 0 ? 0 : 1;
}
