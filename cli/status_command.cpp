#include "status_command.h"

#include <cstdio>

#include "api_client.h"
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
      "status", "Show the daemon's version, uptime, data directory, driver, MAC, how many DCCL types it has and your role on its API");
  status->footer("Example:\n  acommsctl status --json");
  status->callback([&options] { run_status(options); });
}

}  // namespace acomms::cli
