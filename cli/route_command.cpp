// `acommsctl route ls`: the ListRoutes RPC as a table (or JSON).
#include "route_command.h"

#include <cstdio>
#include <string>

#include "api_client.h"
#include "global_options.h"
#include "output.h"
#include "util/seconds.h"

namespace acomms::cli {
namespace {

std::string destinations(const v1::Route& route) {
  return route.dest_min() == route.dest_max() ? std::to_string(route.dest_min())
                                          : std::to_string(route.dest_min()) + "-" + std::to_string(route.dest_max());
}

void run_ls(const GlobalOptions& global) {
  ApiClient client(global);
  v1::ListRoutesResponse response = client.call(&v1::Acomms::Stub::ListRoutes, v1::ListRoutesRequest());
  if (global.json) {
    print_json(response);
    return;
  }
  const double now = util::unix_seconds_now();
  std::printf("%-12s %-8s %-12s %-8s %s\n", "DEST", "NEXT HOP", "LINK", "SOURCE", "LAST CONFIRMED");
  for (const v1::Route& route : response.routes()) {
    std::string confirmed = "never since start";
    if (route.last_confirmed() > 0) {
      confirmed = std::to_string(static_cast<long long>(now - route.last_confirmed())) + " s ago";
    }
    if (route.stale()) confirmed += " (stale: not used)";
    std::printf("%-12s %-8d %-12s %-8s %s\n", destinations(route).c_str(), route.next_hop(), route.link().c_str(),
                route.source().c_str(), confirmed.c_str());
  }
  std::printf(
      "custody: %llu held, %llu taken, %llu refused (full), %llu copies; delivered here %llu (%llu duplicates); "
      "dropped: %llu at the hop limit, %llu expired, %llu malformed\n",
      static_cast<unsigned long long>(response.custody_held()), static_cast<unsigned long long>(response.custody_taken()),
      static_cast<unsigned long long>(response.custody_refused()),
      static_cast<unsigned long long>(response.custody_copies()), static_cast<unsigned long long>(response.delivered()),
      static_cast<unsigned long long>(response.duplicates()),
      static_cast<unsigned long long>(response.hop_limit_dropped()),
      static_cast<unsigned long long>(response.expired_dropped()),
      static_cast<unsigned long long>(response.malformed()));
}

}  // namespace

void add_route_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* route = app.add_subcommand("route", "A gateway's routes to nodes it does not hear directly");
  route->require_subcommand(1);
  route->footer("Example:\n  acommsctl route ls");
  CLI::App* ls = route->add_subcommand("ls", "Routes (static and learned), where each came from, custody counters");
  ls->footer(
      "Lists the node's routes: static ones (config `routing { route { ... } }`) in config order, then "
      "those learned from traffic: `heard` (the node was heard on the link) and `relayed` (its messages came "
      "through the next hop), with when each was last confirmed; a learned route older than "
      "routing.learned_max_age_s is stale and not used. Learned routes are kept in the store: after a restart "
      "they are listed again with their last confirmation (the time down counts in their age). Then what the "
      "node holds for others and what it dropped. Fails on a node without `routing`.\n\n"
      "Examples:\n  acommsctl route ls\n  acommsctl route ls --json");
  ls->callback([&global] { run_ls(global); });
}

}  // namespace acomms::cli
