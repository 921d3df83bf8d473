#include "status_command.h"

#include <chrono>
#include <cstdio>

#include "api_client.h"
#include "consistency_text.h"
#include "global_options.h"
#include "output.h"

namespace acomms::cli {
namespace {

void print_human(const v1::Status& status) {
  std::printf("acommsd %s\n", status.version().c_str());
  std::printf("  uptime:          %.1f s\n", status.uptime_s());
  std::printf("  data dir:        %s\n", status.data_dir().c_str());
  std::printf("  schema version:  %lld\n", static_cast<long long>(status.schema_version()));
  std::printf("  driver:          %s (modem id %u)\n", status.driver().c_str(), status.modem_id());
  std::printf("  mac:             %s\n", status.mac().c_str());
  std::printf("  dccl types:      %d\n", status.dccl_types());
  // The role this client has on the API (config auth): what it may call.
  std::printf("  your role:       %s (%s)\n", status.caller_role().empty() ? "none" : status.caller_role().c_str(),
              status.caller().c_str());
  // Fleet consistency (config consistency): this node's digest, and every
  // node heard announcing one, agreeing or not.
  const double now_s = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  print_consistency("  ", status.consistency_digest(), status.consistency(), now_s);
  if (!status.consistency_digest().empty()) {
    std::printf("  unexpected digests heard: %llu, malformed announces: %llu\n",
                static_cast<unsigned long long>(status.unexpected_digests()),
                static_cast<unsigned long long>(status.malformed_announces()));
  }
}

void run_status(const GlobalOptions& options) {
  ApiClient client(options);
  v1::Status status = client.call(&v1::Acomms::Stub::GetStatus, v1::GetStatusRequest());
  if (options.json) {
    print_json(status);
  } else {
    print_human(status);
  }
}

}  // namespace

void add_status_command(CLI::App& app, const GlobalOptions& options) {
  CLI::App* status = app.add_subcommand(
      "status", "Show the daemon's version, uptime, data directory, driver, MAC, how many DCCL types it has, your role on its API, "
      "and fleet consistency: its digest and whether each node heard announcing one agrees");
  status->footer(
      "Consistency: \"node 2 9f3c01aa on default: DISAGREES ... since T\" means node 2's message definitions or MAC "
      "cycle differ from this node's (or from consistency.expected_digest) since T (README \"Consistency across a "
      "fleet\").\n"
      "Example:\n  acommsctl status --json");
  status->callback([&options] { run_status(options); });
}

}  // namespace acomms::cli
