// acommsctl: command-line client of acommsd.
//
// Exit codes: 0 success, 1 the command failed (daemon unreachable, call
// refused; the reason is printed on one line), 2 bad usage.

#include <CLI/CLI.hpp>

#include <iostream>

#include "completion_command.h"
#include "connection.h"
#include "dccl_command.h"
#include "defs_command.h"
#include "events_command.h"
#include "fleet_command.h"
#include "geov_command.h"
#include "nav_command.h"
#include "track_command.h"
#include "global_options.h"
#include "gram_command.h"
#include "link_command.h"
#include "queue_command.h"
#include "route_command.h"
#include "rpc_error.h"
#include "send_command.h"
#include "sim_command.h"
#include "status_command.h"
#include "sub_command.h"

namespace {

// Commands in the order a person meets them: is the daemon up, what can it
// send, send, hear, watch the queues and the link, look back; then the
// offline tools.
void add_commands(CLI::App& app, const acomms::cli::GlobalOptions& options) {
  using namespace acomms::cli;
  add_status_command(app, options);
  add_defs_command(app, options);
  add_send_command(app, options);
  add_sub_command(app, options);
  add_queue_command(app, options);
  add_link_command(app, options);
  add_route_command(app, options);
  add_events_command(app, options);
  add_nav_command(app, options);
  add_track_command(app, options);
  add_dccl_command(app, options);
  add_sim_command(app, options);
  add_gram_command(app, options);
  add_geov_command(app, options);
  add_fleet_command(app, options);
  add_completion_command(app);
}

// TLS for --socket tcp:HOST:PORT (ignored for a unix socket).
void add_tls_options(CLI::App& app, acomms::cli::GlobalOptions& options) {
  app.add_option("--ca", options.ca_file,
                 "TCP: PEM file of the CA(s) that issued the daemon's certificate (default: the "
                 "system's CAs)")
      ->envname("ACOMMSD_CA")
      ->type_name("FILE");
  app.add_option("--cert", options.cert_file,
                 "TCP: this client's PEM certificate, for a daemon with grpc.tls.client_ca_file")
      ->envname("ACOMMSD_CERT")
      ->type_name("FILE");
  app.add_option("--key", options.key_file, "TCP: the private key of --cert (PEM)")
      ->envname("ACOMMSD_KEY")
      ->type_name("FILE");
  app.add_flag("--insecure", options.insecure,
               "TCP: plaintext, no TLS (only for a daemon with grpc.insecure_tcp: true)");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "acommsctl: control and inspect acommsd, the daemon that owns this vehicle's acoustic link. "
      "Load DCCL message definitions, queue messages for the link, follow what is received, and "
      "watch the queues, the modem driver, the TDMA cycle and the event log."};
  app.require_subcommand(1);
  // Global options may also follow the subcommand: `acommsctl status --json`.
  app.fallthrough();

  acomms::cli::GlobalOptions options;
  options.endpoint = acomms::cli::default_socket();
  app.add_option("-s,--socket", options.endpoint,
                 "acommsd's unix socket, or tcp:HOST:PORT (default: $ACOMMSD_SOCKET or "
                 "/run/acommsd/acommsd.sock)")
      ->type_name("SOCKET");
  app.add_option("--timeout", options.timeout_s, "Seconds to wait for the daemon")
      ->check(CLI::PositiveNumber)
      ->type_name("SECONDS");
  app.add_flag("--json", options.json, "Machine-readable output (one JSON object)");
  add_tls_options(app, options);
  app.set_version_flag("--version", std::string("acommsctl ") + ACOMMS_VERSION);

  add_commands(app, options);
  // Set after the commands are added: CLI11 copies a parent's footer into
  // each subcommand made after it, and every command has its own examples.
  app.footer(
      "Example workflow:\n"
      "  acommsctl defs load /etc/acommsd/nav.proto && acommsctl send gv.NavigationReport x=10 y=-5 z=-20 "
      "&& acommsctl queue ls && acommsctl events --since -10m\n"
      "Run `acommsctl COMMAND --help` for a command's options and examples.\n"
      "Exit status: 0 done, 1 the daemon refused or could not be reached, 2 bad usage.");

  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command that already reported its failures
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : acomms::cli::kExitUsage;  // --help and --version exit 0
  } catch (const acomms::cli::UsageError& e) {
    std::cerr << "acommsctl: " << e.what() << "\n";
    return acomms::cli::kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << "acommsctl: " << e.what() << "\n";
    return acomms::cli::kExitRefused;
  }
  return 0;
}
