#include "sim_network.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>

namespace acomms::testing {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

SimNetwork::SimNetwork(const std::string& name, double slot_seconds)
    : dir_(fs::path("/tmp") / ("acomms-" + name + "-" + std::to_string(::getpid()))), slot_seconds_(slot_seconds) {
  fs::remove_all(dir_);
  fs::create_directories(dir_);
  port_[1] = free_udp_port();
  port_[2] = free_udp_port();
}

SimNetwork::~SimNetwork() {
  if (!::testing::Test::HasFailure()) fs::remove_all(dir_);
}

std::string SimNetwork::socket(int id) const { return (dir_ / (name(id) + ".sock")).string(); }

void SimNetwork::write_config(int id, const Node& node) {
  std::ofstream config(dir_ / (name(id) + ".conf"));
  config << DaemonConfig{.data_dir = dir_ / name(id), .unix_socket = socket(id)}.text();
  if (node.example_messages) config << "dccl { proto_files: \"" << ACOMMS_SOURCE_DIR << "/examples/messages.proto\" }\n";
  config << "driver { name: \"sim\" modem_id: " << id << " sim { " << node.sim << " listen: \"127.0.0.1:" << port_[id]
         << "\" peers: \"127.0.0.1:" << port_[3 - id] << "\" } }\n"
         << "mac { name: \"fixed\" slot { src: 1 rate: 5 seconds: " << slot_seconds_
         << " } slot { src: 2 rate: 5 seconds: " << slot_seconds_ << " } max_range_m: 400 }\n"
         << node.rest;
}

std::string SimNetwork::queue_type(const std::string& type, const std::string& policy) {
  return "  type { type: \"" + type + "\" policy { " + policy + " }\n" +
         "         roles { source_field: \"src\" destination_field: \"dest\" timestamp_field: \"time\" } }\n";
}

void SimNetwork::start(int id) {
  daemons_[id] = std::make_unique<ChildProcess>(
      ACOMMSD_BINARY, std::vector<std::string>{"--config", (dir_ / (name(id) + ".conf")).string()},
      (dir_ / (name(id) + "-" + std::to_string(++starts_))).string());
  ASSERT_TRUE(wait_serving(*daemons_[id], socket(id))) << daemons_[id]->stderr_text();
}

void SimNetwork::stop() {
  for (auto& [id, daemon] : daemons_) {
    if (!daemon || !daemon->running()) continue;
    daemon->signal(SIGCONT);
    daemon->signal(SIGTERM);
    EXPECT_EQ(daemon->wait(15s), std::optional<int>(0)) << name(id) << ":\n" << daemon->stderr_text();
  }
}

}  // namespace acomms::testing
