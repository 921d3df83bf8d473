// acommsd: the acoustic communications daemon.
//
// Exit codes: 0 clean stop (or a successful --check-config, warnings and
// all: a slot too short for one frame is only warned about), 1 a config or
// start-up error (the message says which file and what is wrong), 2 bad
// command-line usage.

#include <CLI/CLI.hpp>
#include <signal.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <iostream>

#include "core/config_error.h"
#include "core/config_loader.h"
#include "core/fleet.h"
#include "core/node_links.h"
#include "core/logging.h"
#include "node/codec_setup.h"
#include "node/consistency_digest.h"
#include "node/daemon.h"
#include "link/slot_check.h"
#include "telemetry/node_settings.h"
#include "service/tls_certificates.h"

namespace {

constexpr int kExitStartupError = 1;
constexpr int kExitUsage = 2;

// Blocks the signals acommsd acts on in this thread before any other
// starts, so every thread inherits the mask and the signals wait for
// sigwait() in main: shutdown (SIGINT, SIGTERM) and reloading the TLS
// certificates (SIGHUP, systemd's ExecReload) then run as ordinary code, not
// in a signal handler.
sigset_t block_handled_signals() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  return signals;
}

// Serves until SIGINT or SIGTERM; each SIGHUP re-reads the certificates and
// the auth keyring.
int wait_for_stop(acomms::node::Daemon& daemon, const sigset_t& signals) {
  int signal_number = 0;
  while (sigwait(&signals, &signal_number) == 0 && signal_number == SIGHUP) {
    spdlog::info("received SIGHUP, reloading TLS certificates and the auth keyring");
    daemon.reload_tls();
    daemon.reload_keyring();
  }
  return signal_number;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"acommsd: acoustic communications daemon (DCCL, priority queues, TDMA)"};
  std::string config_path;
  std::string data_dir;
  std::string socket;
  std::string check_path;
  std::string fleet_path;
  std::string node_name;
  bool print_example = false;
  bool print_digest = false;
  CLI::Option* config_option = app.add_option("-c,--config", config_path, "Config file (protobuf text format)");
  CLI::Option* fleet_option =
      app.add_option("--fleet", fleet_path, "Fleet file (README \"Fleet configuration\"); run the node --node of it")
          ->excludes(config_option);
  app.add_option("--node", node_name, "The fleet's node to run (see `acommsctl fleet ls FLEET`)")->needs(fleet_option);
  fleet_option->needs("--node");
  app.add_option("--data-dir", data_dir, "Directory for the store (overrides the config)");
  app.add_option("--socket", socket, "Unix socket for the API (overrides the config)");
  app.add_flag("--example-config", print_example, "Print a complete, commented config and exit");
  app.add_option("--check-config", check_path, "Validate a config file and exit");
  app.add_flag("--print-digest", print_digest,
               "Print the config's consistency digest (its DCCL definitions and MAC cycle; one line per link when "
               "there are several: NAME DIGEST) and exit, e.g. acommsd --config vehicle.conf --print-digest");
  app.set_version_flag("--version", std::string("acommsd ") + ACOMMS_VERSION);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitUsage;  // --help and --version exit 0
  }

  if (print_example) {
    std::cout << acomms::core::example_config();
    return 0;
  }
  if (!check_path.empty()) {
    try {
      acomms::v1::Config checked = acomms::core::load_config_file(check_path);
      // The telemetry section's bounds, as the start would check them.
      (void)acomms::telemetry::node_settings(checked.telemetry(), acomms::core::node_id(checked));
      // Slots too short for one frame are a warning: the config still works.
      for (const std::string& warning :
           acomms::link::short_slot_warnings(checked, acomms::link::DriverRegistry::linked())) {
        std::cerr << "acommsd: warning: " << check_path << ": " << warning << "\n";
      }
      std::cout << check_path << ": ok\n";
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "acommsd: " << e.what() << "\n";
      return kExitStartupError;
    }
  }

  acomms::v1::Config config;
  try {
    if (!fleet_path.empty()) {
      config = acomms::core::load_fleet_node_config(fleet_path, node_name);
    } else {
      config = config_path.empty() ? acomms::core::parse_config("", "(defaults)")
                                   : acomms::core::load_config_file(config_path);
    }
    if (!data_dir.empty()) config.set_data_dir(data_dir);
    if (!socket.empty()) config.mutable_grpc()->set_unix_socket(socket);
    acomms::core::check_effective_config(config);
  } catch (const std::exception& e) {
    std::cerr << "acommsd: " << e.what() << "\n";
    return kExitStartupError;
  }

  if (print_digest) {
    // The config's own definitions (not those a running node may have been
    // given with LoadDefinitions: acommsctl status shows a node's digest).
    // Only the digest on stdout (it is pasted into a fleet file); what the
    // codec logs goes to stderr.
    spdlog::set_default_logger(spdlog::stderr_color_mt("acommsd"));
    try {
      std::unique_ptr<acomms::dccl::Codec> codec = acomms::node::make_codec(config.dccl());
      auto digests = acomms::node::config_digests(config, *codec);
      for (const auto& [link, digest] : digests) {
        std::cout << (digests.size() == 1 ? "" : link + " ") << acomms::node::digest_hex(digest) << "\n";
      }
      return 0;
    } catch (const std::exception& e) {
      std::cerr << "acommsd: " << e.what() << "\n";
      return kExitStartupError;
    }
  }

  acomms::core::configure_logging(config.log_level());
  sigset_t handled_signals = block_handled_signals();
  try {
    // The TLS files are checked before anything starts, so that a bad
    // certificate stops the daemon as cleanly as a bad config.
    if (config.grpc().has_tls()) acomms::service::TlsCertificates check(config.grpc().tls());
    acomms::node::Daemon daemon(config);
    int signal_number = wait_for_stop(daemon, handled_signals);
    spdlog::info("received {}, stopping", signal_number == SIGTERM ? "SIGTERM" : "SIGINT");
    daemon.stop();
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    return kExitStartupError;
  }
  return 0;
}
