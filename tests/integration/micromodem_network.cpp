#include "micromodem_network.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>

namespace acomms::testing {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

namespace {

std::string node_name(int id) { return "node" + std::to_string(id); }

// The console's answers: every stdout line that is not a "modem ..." line.
std::vector<std::string> answers(const std::string& output) {
  std::vector<std::string> out;
  for (const std::string& line : lines_of(output)) {
    if (!line.starts_with("modem ")) out.push_back(line);
  }
  return out;
}

}  // namespace

MicroModemNetwork::MicroModemNetwork(const std::string& name, std::vector<Modem> modems, double time_scale,
                                     std::vector<std::string> fake_args)
    : dir_(fs::path("/tmp") / ("acomms-" + name + "-" + std::to_string(::getpid()))),
      modems_(std::move(modems)),
      time_scale_(time_scale) {
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  std::string fifo = (dir_ / "console").string();
  if (::mkfifo(fifo.c_str(), 0600) != 0) return;
  // Read-write, so opening does not wait for the reader; the fake opens it
  // for reading as its stdin.
  console_ = ::open(fifo.c_str(), O_RDWR | O_CLOEXEC);
  if (console_ < 0) return;
  std::vector<std::string> args = {"--transport", "tcp", "--time-scale", std::to_string(time_scale_)};
  for (const Modem& modem : modems_) {
    args.push_back("--modem");
    args.push_back(modem.spec);
  }
  args.insert(args.end(), fake_args.begin(), fake_args.end());
  fake_ = std::make_unique<ChildProcess>(FAKE_MICROMODEM_BINARY, args, (dir_ / "fake").string(),
                                         std::map<std::string, std::string>{}, fifo);
  ok_ = wait_until(
      [this] {
        for (const std::string& line : lines_of(fake_->stdout_text())) {
          int id = 0;
          char generation[8] = {}, address[64] = {};
          if (std::sscanf(line.c_str(), "modem %d %7s tcp %63s", &id, generation, address) == 3) {
            address_[id] = address;
          }
        }
        return address_.size() == modems_.size();
      },
      10s);
}

MicroModemNetwork::~MicroModemNetwork() {
  for (auto& [id, daemon] : daemons_) {
    if (daemon && daemon->running()) daemon->signal(SIGTERM);
  }
  for (auto& [id, daemon] : daemons_) {
    if (daemon && daemon->running()) daemon->wait(15s);
  }
  if (fake_) fake_->signal(SIGTERM);
  if (console_ >= 0) ::close(console_);
  fs::remove_all(dir_);
}

std::string MicroModemNetwork::fake_output() const {
  return fake_ ? fake_->stdout_text() + fake_->stderr_text() : "the fake did not start";
}

std::string MicroModemNetwork::socket(int id) const { return (dir_ / (node_name(id) + ".sock")).string(); }

std::string MicroModemNetwork::daemon_log(int id) const {
  auto found = daemons_.find(id);
  return found == daemons_.end() ? "" : found->second->stderr_text();
}

void MicroModemNetwork::write_config(int id, const std::string& mac, const std::string& micromodem,
                                     const std::string& extra) {
  std::ofstream config(dir_ / (node_name(id) + ".conf"));
  config << DaemonConfig{.data_dir = dir_ / node_name(id),
                         .unix_socket = socket(id),
                         .proto_file = ACOMMS_SOURCE_DIR "/examples/messages.proto"}.text()
         // Restarts within seconds, not the default 20: tests unplug ports.
         << "driver { name: \"micromodem\" modem_id: " << id << " restart_min_s: 0.5 restart_max_s: 2"
         << " micromodem { port: \"tcp:" << address_[id]
         << "\" time_scale: " << time_scale_ << " max_range_m: 1000 " << micromodem << " } }\n"
         << "mac { " << mac << " }\n"
         << "queue {\n"
         << "  type { type: \"example.Command\" policy { value_base: 5 }\n"
         << "         roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n"
         << "}\n"
         << extra << "\n";
}

bool MicroModemNetwork::start(int id) {
  daemons_[id] = std::make_unique<ChildProcess>(
      ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / (node_name(id) + ".conf")).string()},
      (dir_ / node_name(id)).string() + "-log");
  return wait_serving(*daemons_[id], socket(id));
}

std::string MicroModemNetwork::fault(const std::string& command) {
  std::string line = command + "\n";
  if (console_ < 0 || ::write(console_, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
    return "could not write to the fake's console";
  }
  std::string answer = "no answer from the fake's console";
  wait_until(
      [&] {
        std::vector<std::string> all = answers(fake_->stdout_text());
        if (all.size() <= answers_seen_) return false;
        answer = all[answers_seen_];
        return true;
      },
      10s);
  ++answers_seen_;
  return answer;
}

grpc::Status MicroModemNetwork::submit_command(int id, int dest, int seq, v1::SubmitResponse* response) {
  grpc::ClientContext context;
  v1::SubmitRequest request;
  request.set_type("example.Command");
  request.set_json(R"({"dest": )" + std::to_string(dest) + R"(, "kind": "GOTO", "x": 200, "y": -50, "depth": 30, "seq": )" +
                   std::to_string(seq) + "}");
  v1::SubmitResponse ignored;
  return api(socket(id))->Submit(&context, request, response ? response : &ignored);
}

int MicroModemNetwork::queued(int id) {
  grpc::ClientContext context;
  v1::ListQueuedRequest request;
  request.set_type("example.Command");
  v1::ListQueuedResponse response;
  if (!api(socket(id))->ListQueued(&context, request, &response).ok()) return -1;
  return response.messages_size();
}

v1::LinkStatusResponse MicroModemNetwork::link_status(int id) {
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + 5s);
  v1::LinkStatusResponse response;
  if (!api(socket(id))->LinkStatus(&context, v1::LinkStatusRequest(), &response).ok()) return {};
  return response;
}

RunResult MicroModemNetwork::raw_log(int id) {
  return run(ACOMMSCTL_BINARY, {"--socket", socket(id), "link", "raw", "--no-follow", "-n", "1000000"},
             (dir_ / ("raw-" + std::to_string(id))).string());
}

}  // namespace acomms::testing
