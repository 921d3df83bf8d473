// acommsctl: command-line client of acommsd.
//
// Exit codes: 0 success, 1 the command failed (daemon unreachable, call
// refused; the reason is printed on one line), 2 bad usage.

#include <CLI/CLI.hpp>

#include <iostream>

#include "connection.h"
#include "global_options.h"
#include "dccl_command.h"
#include "sim_command.h"
#include "status_command.h"

int main(int argc, char** argv) {
  CLI::App app{"acommsctl: control and inspect acommsd"};
  app.require_subcommand(1);
  // Global options may also follow the subcommand: `acommsctl status --json`.
  app.fallthrough();

  acomms::cli::GlobalOptions options;
  options.endpoint = acomms::cli::default_socket();
  app.add_option("-s,--socket", options.endpoint,
                 "acommsd's unix socket, or tcp:HOST:PORT (default: $ACOMMSD_SOCKET or "
                 "/run/acommsd/acommsd.sock)");
  app.add_option("--timeout", options.timeout_s, "Seconds to wait for the daemon")
      ->check(CLI::PositiveNumber);
  app.add_flag("--json", options.json, "Machine-readable output (one JSON object)");
  app.set_version_flag("--version", std::string("acommsctl ") + ACOMMS_VERSION);

  acomms::cli::add_status_command(app, options);
  acomms::cli::add_dccl_command(app, options);
  acomms::cli::add_sim_command(app, options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command that already reported its failures
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;  // --help and --version exit 0
  } catch (const std::exception& e) {
    std::cerr << "acommsctl: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
