// Durable Submit through a real acommsd, as clients see it: submits per
// second and per-call latency (p50, p99) with 1 and 8 concurrent clients, and
// the daemon's resident memory when idle on examples/vehicle.conf.
//
// Each client has its own gRPC channel (its own connection) on the unix
// socket and keeps exactly one Submit in flight: it sends the next only once
// the last is answered, and every call is answered only once its message is
// durably in SQLite (WAL, synchronous=FULL, group commit). By default one
// event thread drives all the clients through a completion queue, as load
// generators such as wrk do, so that on a small machine the load generator
// takes as little CPU from the daemon as it can; --client-threads gives each
// client its own thread making blocking calls instead (the way most
// integrations call), which on 2 cores measures the client as much as the
// daemon. The daemon runs the sim driver with mac "none", so nothing
// is ever sent, and one DCCL type whose queue drops its oldest message
// instead of refusing (max_queue 1,000,000): no submit is refused.
//
// Goals (issue: API performance): 20,000 durable submits/s with 8 clients,
// p99 < 5 ms; idle RSS < 30 MB. Printed next to the figures, not asserted:
// this is a benchmark. It exits non-zero only when a submit fails or the
// daemon misbehaves (what the ctest smoke run checks).
//
//   build/tests/bench/submit_bench [--duration 5] [--warmup 1] [--clients 1,8]
//                                  [--idle 3] [--dir /tmp] [--json] [--no-rss] [--baseline]
//                                  [--client-threads] [--tcp plain|tls|mtls]
//   --baseline also times GetStatus the same way: the gRPC round trip alone.
//   --tcp: the clients use TCP on 127.0.0.1 instead of the unix socket:
//   plaintext (grpc.insecure_tcp), TLS, or mutual TLS (certificates made
//   with the openssl command): what TLS costs each call.

#include <absl/synchronization/mutex.h>
#include <grpcpp/grpcpp.h>
#include <signal.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "acomms/v1/acomms.grpc.pb.h"
#include "child_process.h"
#include "daemon_harness.h"
#include "count_list.h"
#include "fdatasync_probe.h"

namespace {

namespace fs = std::filesystem;
using namespace acomms;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr double kGoalSubmitsPerSecond = 20000;  // with 8 clients
constexpr int kGoalClients = 8;
constexpr double kGoalP99Ms = 5;
constexpr double kGoalIdleRssMb = 30;

struct Options {
  double duration = 5;
  double warmup = 1;
  double idle = 3;
  std::vector<int> clients = {1, 8};
  std::string base_dir = fs::temp_directory_path().string();
  std::string acommsd = ACOMMSD_BINARY;
  std::string example_config = ACOMMS_SOURCE_DIR "/examples/vehicle.conf";
  bool json = false;
  bool rss = true;
  // Also time GetStatus (no store, no core thread): what the gRPC round trip
  // alone costs, the ceiling under any Submit figure.
  bool baseline = false;
  // One thread per client, blocking calls, instead of one event thread.
  bool client_threads = false;
  // "" (unix socket), "plain", "tls" or "mtls": TCP on 127.0.0.1.
  std::string tcp;
};

// Where the clients connect, and how.
struct Endpoint {
  std::string target;
  std::shared_ptr<grpc::ChannelCredentials> credentials;
};

constexpr const char* kBenchProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package bench;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 90 max_bytes: 32 };
  required int32 seq = 1 [(dccl.field) = { min: 0 max: 65535 }];
  required double depth = 2 [(dccl.field) = { min: 0 max: 1000 precision: 1 }];
  required int32 battery = 3 [(dccl.field) = { min: 0 max: 100 }];
}
)";

struct Memory {
  long rss_kb = -1;
  long hwm_kb = -1;
};

// VmRSS and VmHWM of a process, from /proc/PID/status.
Memory memory_of(pid_t pid) {
  Memory memory;
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmRSS:", 0) == 0) memory.rss_kb = std::stol(line.substr(6));
    if (line.rfind("VmHWM:", 0) == 0) memory.hwm_kb = std::stol(line.substr(6));
  }
  return memory;
}

std::string filesystem_name(const std::string& path) {
  struct statfs info {};
  if (::statfs(path.c_str(), &info) != 0) return "?";
  switch (static_cast<unsigned long>(info.f_type)) {
    case 0xEF53: return "ext4";
    case 0x01021994: return "tmpfs";
    case 0x58465342: return "xfs";
    case 0x9123683E: return "btrfs";
    case 0x794C7630: return "overlayfs";
    default: return "fs type 0x" + [&] {
      char hex[32];
      std::snprintf(hex, sizeof(hex), "%lx", static_cast<unsigned long>(info.f_type));
      return std::string(hex);
    }();
  }
}

// SIGTERM, then the exit code (nullopt: it had to be killed, or died by a
// signal).
std::optional<int> stop(testing::ChildProcess& daemon) {
  daemon.signal(SIGTERM);
  std::optional<int> code = daemon.wait(20s);
  if (!code && daemon.running()) {
    daemon.signal(SIGKILL);
    daemon.wait(5s);
  }
  return code;
}

struct Row {
  std::string call = "Submit";
  int clients = 0;
  double seconds = 0;
  uint64_t calls = 0;
  uint64_t failed = 0;
  std::string first_error;
  double p50_ms = 0, p99_ms = 0, p999_ms = 0, max_ms = 0, mean_ms = 0;
  double rate() const { return seconds > 0 ? calls / seconds : 0; }
};

double percentile(const std::vector<float>& sorted_us, double p) {
  if (sorted_us.empty()) return 0;
  size_t rank = static_cast<size_t>(std::ceil(p * sorted_us.size()));
  return sorted_us[std::clamp<size_t>(rank, 1, sorted_us.size()) - 1] / 1e3;
}

// The calls counted and their latencies: mean and percentiles over every
// client's calls.
void summarise(const std::vector<std::vector<float>>& latencies, Row* out) {
  Row& row = *out;
  std::vector<float> all;
  for (auto& mine : latencies) all.insert(all.end(), mine.begin(), mine.end());
  std::sort(all.begin(), all.end());
  row.calls = all.size();
  row.p50_ms = percentile(all, 0.50);
  row.p99_ms = percentile(all, 0.99);
  row.p999_ms = percentile(all, 0.999);
  row.max_ms = all.empty() ? 0 : all.back() / 1e3;
  double sum = 0;
  for (float us : all) sum += us;
  row.mean_ms = all.empty() ? 0 : sum / all.size() / 1e3;
}

// A channel of its own (its own connection) for each client.
std::shared_ptr<grpc::Channel> client_channel(const Endpoint& endpoint) {
  grpc::ChannelArguments args;
  // Channels with equal arguments would otherwise share one connection.
  args.SetInt(GRPC_ARG_USE_LOCAL_SUBCHANNEL_POOL, 1);
  auto channel = grpc::CreateCustomChannel(endpoint.target, endpoint.credentials, args);
  channel->WaitForConnected(std::chrono::system_clock::now() + 10s);
  return channel;
}

// The message a client sends as its seq-th: JSON, as a script would.
std::string status_json(uint32_t seq, int client) {
  return "{\"seq\":" + std::to_string(seq % 65536) + ",\"depth\":" + std::to_string((seq * 7 + client) % 1000) +
         ".5,\"battery\":" + std::to_string(seq % 101) + "}";
}

// Where a run is: clients count only the calls they start in kMeasure.
enum Phase { kWarmup, kMeasure, kStop };

// Lets the clients warm up, then measure, then stop; returns the seconds
// measured.
double run_phases(std::atomic<int>& phase, const Options& options) {
  std::this_thread::sleep_for(std::chrono::duration<double>(options.warmup));
  auto start = Clock::now();
  phase = kMeasure;
  std::this_thread::sleep_for(std::chrono::duration<double>(options.duration));
  phase = kStop;
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// `clients` threads, each with its own channel, submitting for warm-up then
// for the measured duration. Only calls started in the measured window count.
Row run_clients_on_threads(const Options& options, const Endpoint& endpoint, int clients, bool get_status) {
  std::atomic<int> phase{kWarmup};
  std::atomic<int> connected{0};
  std::atomic<bool> go{false};
  std::mutex mutex;
  Row row;
  row.call = get_status ? "GetStatus" : "Submit";
  row.clients = clients;
  std::vector<std::vector<float>> latencies(clients);
  std::vector<std::thread> threads;
  for (int c = 0; c < clients; ++c) {
    threads.emplace_back([&, c] {
      auto stub = v1::Acomms::NewStub(client_channel(endpoint));
      std::vector<float>& mine = latencies[c];
      mine.reserve(1 << 18);
      uint64_t failed = 0;
      ++connected;
      while (!go.load()) std::this_thread::yield();
      v1::SubmitRequest request;
      request.set_type("bench.Status");
      v1::SubmitResponse response;
      v1::GetStatusRequest status_request;
      v1::Status status_response;
      for (uint32_t seq = 0;; ++seq) {
        int now_phase = phase.load(std::memory_order_relaxed);
        if (now_phase == kStop) break;
        request.set_json(status_json(seq, c));
        grpc::ClientContext context;
        context.set_deadline(std::chrono::system_clock::now() + 10s);
        auto start = Clock::now();
        grpc::Status status = get_status ? stub->GetStatus(&context, status_request, &status_response)
                                         : stub->Submit(&context, request, &response);
        auto elapsed = Clock::now() - start;
        if (!status.ok()) {
          ++failed;
          std::lock_guard lock(mutex);
          if (row.first_error.empty()) {
            row.first_error = "code " + std::to_string(status.error_code()) + ": " + status.error_message();
          }
          continue;
        }
        if (now_phase == kMeasure) {
          mine.push_back(std::chrono::duration<float, std::micro>(elapsed).count());
        }
      }
      std::lock_guard lock(mutex);
      row.failed += failed;
    });
  }
  while (connected.load() < clients) std::this_thread::sleep_for(1ms);
  go = true;
  row.seconds = run_phases(phase, options);
  for (auto& thread : threads) thread.join();
  summarise(latencies, &row);
  return row;
}

// The same clients driven by one thread: each client's next call starts
// from the completion of its last one.
Row run_clients_on_events(const Options& options, const Endpoint& endpoint, int clients, bool get_status) {
  struct Client {
    int index = 0;
    std::unique_ptr<v1::Acomms::Stub> stub;
    uint32_t seq = 0;
    std::unique_ptr<grpc::ClientContext> context;
    v1::SubmitRequest request;
    v1::SubmitResponse response;
    v1::GetStatusRequest status_request;
    v1::Status status_response;
    grpc::Status status;
    std::unique_ptr<grpc::ClientAsyncResponseReader<v1::SubmitResponse>> submit;
    std::unique_ptr<grpc::ClientAsyncResponseReader<v1::Status>> get_status;
    Clock::time_point start;
    bool measured = false;
    std::vector<float> latencies;
  };
  Row row;
  row.call = get_status ? "GetStatus" : "Submit";
  row.clients = clients;
  grpc::CompletionQueue queue;
  std::vector<Client> all(clients);
  for (int c = 0; c < clients; ++c) {
    all[c].index = c;
    all[c].stub = v1::Acomms::NewStub(client_channel(endpoint));
    all[c].request.set_type("bench.Status");
    all[c].latencies.reserve(1 << 18);
  }
  std::atomic<int> phase{kWarmup};
  auto start_call = [&](Client& client) {
    client.context = std::make_unique<grpc::ClientContext>();
    client.context->set_deadline(std::chrono::system_clock::now() + 10s);
    client.measured = phase.load(std::memory_order_relaxed) == kMeasure;
    if (get_status) {
      client.start = Clock::now();
      client.get_status = client.stub->AsyncGetStatus(client.context.get(), client.status_request, &queue);
      client.get_status->Finish(&client.status_response, &client.status, &client);
    } else {
      client.request.set_json(status_json(client.seq++, client.index));
      client.start = Clock::now();
      client.submit = client.stub->AsyncSubmit(client.context.get(), client.request, &queue);
      client.submit->Finish(&client.response, &client.status, &client);
    }
  };
  std::thread driver([&] {
    for (Client& client : all) start_call(client);
    int in_flight = clients;
    void* tag = nullptr;
    bool ok = false;
    while (in_flight > 0 && queue.Next(&tag, &ok)) {
      Client& client = *static_cast<Client*>(tag);
      auto elapsed = Clock::now() - client.start;
      if (!ok || !client.status.ok()) {
        ++row.failed;
        if (row.first_error.empty()) {
          row.first_error = ok ? "code " + std::to_string(client.status.error_code()) + ": " +
                                     client.status.error_message()
                               : "the completion queue reported a failed call";
        }
      } else if (client.measured) {
        client.latencies.push_back(std::chrono::duration<float, std::micro>(elapsed).count());
      }
      if (phase.load(std::memory_order_relaxed) == kStop) {
        --in_flight;
      } else {
        start_call(client);
      }
    }
  });
  row.seconds = run_phases(phase, options);
  driver.join();
  queue.Shutdown();
  void* tag = nullptr;
  bool ok = false;
  while (queue.Next(&tag, &ok)) {
  }
  std::vector<std::vector<float>> latencies;
  for (Client& client : all) latencies.push_back(std::move(client.latencies));
  summarise(latencies, &row);
  return row;
}

std::string met(bool ok) { return ok ? "met" : "MISSED"; }

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

struct ThroughputResult {
  std::vector<Row> rows;
  Memory after;
  bool ok = false;
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A CA, a certificate for 127.0.0.1 and a client certificate in `dir`, made
// with the openssl command; false (said on stderr) if it fails.
bool make_certificates(const fs::path& dir) {
  auto openssl = [&](std::vector<std::string> args) {
    testing::RunResult result = testing::run("/usr/bin/openssl", args, (dir / "openssl").string());
    if (result.exit_code != 0) std::fprintf(stderr, "submit_bench: openssl %s: %s", args[0].c_str(), result.err.c_str());
    return result.exit_code == 0;
  };
  auto path = [&](const std::string& name) { return (dir / name).string(); };
  write_file(dir / "server.ext", "subjectAltName=IP:127.0.0.1\n");
  bool ok = true;
  for (const char* name : {"ca", "server", "client"}) {
    ok = ok && openssl({"genpkey", "-algorithm", "EC", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-out",
                        path(std::string(name) + ".key")});
  }
  ok = ok && openssl({"req", "-x509", "-new", "-key", path("ca.key"), "-out", path("ca.pem"), "-days", "2",
                      "-subj", "/CN=bench CA"});
  for (const char* name : {"server", "client"}) {
    std::string n = name;
    ok = ok && openssl({"req", "-new", "-key", path(n + ".key"), "-out", path(n + ".csr"), "-subj", "/CN=" + n});
    ok = ok && openssl({"x509", "-req", "-in", path(n + ".csr"), "-CA", path("ca.pem"), "-CAkey", path("ca.key"),
                        "-set_serial", n == "server" ? "7" : "8", "-days", "2", "-extfile", path("server.ext"),
                        "-out", path(n + ".pem")});
  }
  return ok;
}

// The grpc { } settings for --tcp, and where the clients connect.
std::string tcp_settings(const Options& options, const fs::path& dir, Endpoint& endpoint) {
  std::string address = "127.0.0.1:" + std::to_string(testing::free_tcp_port());
  endpoint.target = address;
  if (options.tcp == "plain") {
    endpoint.credentials = grpc::InsecureChannelCredentials();
    return " tcp_listen: \"" + address + "\" insecure_tcp: true";
  }
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = read_text(dir / "ca.pem");
  std::string settings = " tcp_listen: \"" + address + "\" tls { cert_file: \"" + (dir / "server.pem").string() +
                         "\" key_file: \"" + (dir / "server.key").string() + "\"";
  if (options.tcp == "mtls") {
    ssl.pem_cert_chain = read_text(dir / "client.pem");
    ssl.pem_private_key = read_text(dir / "client.key");
    settings += " client_ca_file: \"" + (dir / "ca.pem").string() + "\"";
  }
  endpoint.credentials = grpc::SslCredentials(ssl);
  return settings + " }";
}

ThroughputResult throughput(const Options& options) {
  ThroughputResult result;
  fs::path dir = fs::path(options.base_dir) / ("acomms_submit_bench_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string socket = (dir / "api.sock").string();
  write_file(dir / "bench.proto", kBenchProto);
  Endpoint endpoint{"unix:" + socket, grpc::InsecureChannelCredentials()};
  std::string tcp;
  if (!options.tcp.empty()) {
    if (options.tcp != "plain" && !make_certificates(dir)) return result;
    tcp = tcp_settings(options, dir, endpoint);
  }
  std::ostringstream config;
  config << "data_dir: \"" << (dir / "data").string() << "\"\n"
         << "grpc { unix_socket: \"" << socket << "\"" << tcp << " }\n"
         << "driver { name: \"sim\" modem_id: 1 }\n"
         << "mac { name: \"none\" }\n"
         << "dccl { proto_files: \"" << (dir / "bench.proto").string() << "\" }\n"
         << "queue { type { type: \"bench.Status\" policy { max_queue: 1000000 on_full: DROP_OLDEST } } }\n";
  write_file(dir / "acommsd.conf", config.str());

  testing::ChildProcess daemon(options.acommsd, {"--config", (dir / "acommsd.conf").string()},
                               (dir / "acommsd").string());
  if (!testing::wait_serving(daemon, socket)) {
    std::fprintf(stderr, "submit_bench: acommsd did not start serving:\n%s", daemon.stderr_text().c_str());
    fs::remove_all(dir);
    return result;
  }
  // What the disk alone costs each Submit, so that figures from different
  // machines can be compared (see the README's Benchmarks section).
  double fdatasync_ms = -1;
  try {
    fdatasync_ms = bench::fdatasync_seconds(options.base_dir, 200, false) * 1e3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "submit_bench: cannot time fdatasync: %s\n", e.what());
  }
  if (options.json) {
    std::printf("{\"bench\":\"fdatasync\",\"dir\":\"%s\",\"in_place_ms\":%s}\n", options.base_dir.c_str(),
                fdatasync_ms < 0 ? "null" : std::to_string(fdatasync_ms).c_str());
  } else {
    std::printf("acommsd durable Submit: data dir on %s (%s), %.1f s per row after %.1f s warm-up;\n"
                "each client one connection (%s) with one call in flight, %s\n",
                options.base_dir.c_str(), filesystem_name(options.base_dir).c_str(), options.duration,
                options.warmup,
                options.tcp.empty() ? "unix socket" : ("TCP 127.0.0.1, " + options.tcp).c_str(),
                options.client_threads ? "one thread per client (blocking calls)"
                                       : "all driven by one event thread");
    if (fdatasync_ms >= 0) {
      std::printf("this disk: 4 KiB write + fdatasync in place takes %.3f ms; every Submit waits for at least one\n",
                  fdatasync_ms);
    }
    std::printf("%-9s %7s %10s %11s %8s %8s %8s %8s %8s %7s   %s\n", "call", "clients", "calls", "calls/s", "mean_ms",
                "p50_ms", "p99_ms", "p99.9_ms", "max_ms", "failed", "goals");
  }
  bool failed = false;
  std::vector<std::pair<bool, int>> runs;
  for (int clients : options.clients) runs.emplace_back(false, clients);
  if (options.baseline) {
    for (int clients : options.clients) runs.emplace_back(true, clients);
  }
  for (auto [get_status, clients] : runs) {
    Row row = options.client_threads ? run_clients_on_threads(options, endpoint, clients, get_status)
                                     : run_clients_on_events(options, endpoint, clients, get_status);
    result.rows.push_back(row);
    failed = failed || row.failed > 0 || row.calls == 0;
    if (options.json) {
      std::printf("{\"bench\":\"%s\",\"clients\":%d,\"seconds\":%.3f,\"calls\":%llu,"
                  "\"calls_per_s\":%.1f,\"mean_ms\":%.4f,\"p50_ms\":%.4f,\"p99_ms\":%.4f,"
                  "\"p999_ms\":%.4f,\"max_ms\":%.4f,\"failed\":%llu,\"client_threads\":%s}\n",
                  get_status ? "get_status" : "submit", row.clients, row.seconds,
                  static_cast<unsigned long long>(row.calls), row.rate(),
                  row.mean_ms, row.p50_ms, row.p99_ms, row.p999_ms, row.max_ms,
                  static_cast<unsigned long long>(row.failed), options.client_threads ? "true" : "false");
    } else {
      std::string goals = "p99 < " + std::to_string(static_cast<int>(kGoalP99Ms)) + " ms: " +
                          met(row.p99_ms < kGoalP99Ms);
      if (get_status) {
        goals = "(baseline: gRPC alone)";
      } else if (clients == kGoalClients) {
        goals += ", >= 20,000/s: " + met(row.rate() >= kGoalSubmitsPerSecond);
      }
      std::printf("%-9s %7d %10llu %11.0f %8.3f %8.3f %8.3f %8.3f %8.3f %7llu   %s\n", row.call.c_str(),
                  row.clients,
                  static_cast<unsigned long long>(row.calls), row.rate(), row.mean_ms, row.p50_ms,
                  row.p99_ms, row.p999_ms, row.max_ms, static_cast<unsigned long long>(row.failed),
                  goals.c_str());
    }
    if (row.failed > 0) {
      std::fprintf(stderr, "submit_bench: %llu %s calls failed with %d clients; first: %s\n",
                   static_cast<unsigned long long>(row.failed), row.call.c_str(), clients,
                   row.first_error.c_str());
    }
    std::fflush(stdout);
  }
  result.after = memory_of(daemon.pid());
  if (options.json) {
    std::printf("{\"bench\":\"rss_after_submits\",\"vm_rss_kb\":%ld,\"vm_hwm_kb\":%ld}\n", result.after.rss_kb,
                result.after.hwm_kb);
  } else {
    std::printf("acommsd after these submits: VmRSS %.1f MB, VmHWM %.1f MB\n", result.after.rss_kb / 1024.0,
                result.after.hwm_kb / 1024.0);
  }
  std::optional<int> code = stop(daemon);
  if (code != 0) {
    std::fprintf(stderr, "submit_bench: acommsd did not exit cleanly on SIGTERM (%s):\n%s",
                 code ? ("exit " + std::to_string(*code)).c_str() : "killed", daemon.stderr_text().c_str());
    failed = true;
  } else if (!options.json) {
    // The daemon's own account of how commits were shared.
    std::string log = daemon.stderr_text();
    size_t at = log.find("store writer: ");
    if (at != std::string::npos) {
      std::printf("acommsd %s\n", log.substr(at, log.find('\n', at) - at).c_str());
    }
  }
  fs::remove_all(dir);
  result.ok = !failed;
  return result;
}

// acommsd started as examples/run.sh starts the vehicle: `acommsd --config
// examples/vehicle.conf` from a directory holding examples/ (its paths, data
// dir and socket under var/ and examples/messages.proto, are relative to
// it), idle for `options.idle` seconds once serving. That directory is a
// scratch one with examples/ linked to the checkout's, so that the
// checkout's var/ is left alone.
bool idle_memory(const Options& options) {
  fs::path dir = fs::path(options.base_dir) / ("acomms_submit_bench_rss_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "var" / "vehicle");
  fs::path config = fs::absolute(options.example_config);
  fs::create_directory_symlink(config.parent_path(), dir / "examples");
  fs::path here = fs::current_path();
  // The child inherits the working directory; nothing else runs now.
  fs::current_path(dir);
  testing::ChildProcess daemon(options.acommsd, {"--config", "examples/" + config.filename().string()},
                               (dir / "acommsd").string());
  fs::current_path(here);
  std::string socket = (dir / "var" / "vehicle" / "acommsd.sock").string();
  if (!testing::wait_serving(daemon, socket)) {
    std::fprintf(stderr, "submit_bench: acommsd (%s) did not start serving:\n%s", config.c_str(),
                 daemon.stderr_text().c_str());
    fs::remove_all(dir);
    return false;
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(options.idle));
  Memory memory = memory_of(daemon.pid());
  if (options.json) {
    std::printf("{\"bench\":\"idle_rss\",\"config\":\"%s\",\"idle_s\":%.1f,\"vm_rss_kb\":%ld,\"vm_hwm_kb\":%ld}\n",
                config.c_str(), options.idle, memory.rss_kb, memory.hwm_kb);
  } else {
    std::printf("acommsd idle %.1f s on %s: VmRSS %.1f MB, VmHWM %.1f MB   goal RSS < %.0f MB: %s\n",
                options.idle, options.example_config.c_str(), memory.rss_kb / 1024.0, memory.hwm_kb / 1024.0,
                kGoalIdleRssMb, met(memory.rss_kb >= 0 && memory.rss_kb < kGoalIdleRssMb * 1024).c_str());
  }
  std::fflush(stdout);
  std::optional<int> code = stop(daemon);
  fs::remove_all(dir);
  if (code != 0) {
    std::fprintf(stderr, "submit_bench: idle acommsd did not exit cleanly on SIGTERM:\n%s",
                 daemon.stderr_text().c_str());
    return false;
  }
  return memory.rss_kb >= 0;
}

[[noreturn]] void usage() {
  std::fprintf(stderr,
               "usage: submit_bench [--duration S] [--warmup S] [--clients 1,8] [--idle S] [--dir D]\n"
               "                    [--acommsd PATH] [--example-config PATH] [--json] [--no-rss] [--baseline]\n"
               "                    [--client-threads] [--tcp plain|tls|mtls]\n");
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) {
  // As acommsd does (service/grpc_server.cpp): Debian's abseil would
  // otherwise run its debugging lock-order checks on every gRPC lock, and
  // the load generator shares the CPUs with the daemon it measures.
  absl::SetMutexDeadlockDetectionMode(absl::OnDeadlockCycle::kIgnore);
  Options options;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    std::string value;
    bool has_value = false;
    if (auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
      has_value = true;
    }
    auto next = [&]() -> std::string {
      if (has_value) return value;
      if (i + 1 >= argc) usage();
      return argv[++i];
    };
    try {
      if (arg == "--duration") options.duration = std::stod(next());
      else if (arg == "--warmup") options.warmup = std::stod(next());
      else if (arg == "--idle") options.idle = std::stod(next());
      else if (arg == "--clients") options.clients = bench::parse_count_list(next());
      else if (arg == "--dir") options.base_dir = next();
      else if (arg == "--acommsd") options.acommsd = next();
      else if (arg == "--example-config") options.example_config = next();
      else if (arg == "--json") options.json = true;
      else if (arg == "--no-rss") options.rss = false;
      else if (arg == "--baseline") options.baseline = true;
      else if (arg == "--client-threads") options.client_threads = true;
      else if (arg == "--tcp") {
        options.tcp = next();
        if (options.tcp != "plain" && options.tcp != "tls" && options.tcp != "mtls") usage();
      }
      else usage();
    } catch (const std::logic_error&) {
      usage();
    }
  }
  // A short run (the ctest smoke) keeps warm-up and idle time short too.
  if (options.duration < 1) {
    options.warmup = std::min(options.warmup, options.duration / 2);
    options.idle = std::min(options.idle, 1.0);
  }

  ThroughputResult result = throughput(options);
  bool ok = result.ok;
  if (options.rss) ok = idle_memory(options) && ok;
  return ok ? 0 : 1;
}
