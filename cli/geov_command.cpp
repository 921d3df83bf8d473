#include "geov_command.h"

#include <pthread.h>
#include <signal.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>
#include <vector>

#include "geov/daemon_feed.h"
#include "geov/fleet.h"
#include "geov/http_server.h"
#include "geov/map_site.h"
#include "geov/tl_section.h"
#include "global_options.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

struct ServeOptions {
  std::string listen = "127.0.0.1:8080";
  std::vector<std::string> daemons;
  std::string token_file;
  bool insecure_http = false;
  std::string tile_url;
  std::string mbtiles;
  std::string attribution;
  int max_connections = 64;
  double kml_refresh_s = 5;
  double poll_s = 1;
  double max_period_h = 24;
};

std::string read_token(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw UsageError("--token-file " + path + ": cannot read it");
  std::string token;
  std::getline(file, token);
  while (!token.empty() && (token.back() == '\r' || token.back() == ' ')) token.pop_back();
  if (token.size() < 16) throw UsageError("--token-file " + path + ": the token must be 16 characters or more");
  for (char c : token) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') {
      throw UsageError("--token-file " + path + ": the token may hold only letters, digits, '-', '_' and '.'");
    }
  }
  return token;
}

void run_serve(const GlobalOptions& global, const ServeOptions& options) {
  // SIGINT and SIGTERM are taken by one thread (below), so every thread
  // started from here on, gRPC's included, leaves them to it.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  geov::SiteOptions site_options;
  if (!options.token_file.empty()) site_options.token = read_token(options.token_file);
  site_options.tile_url = options.tile_url;
  site_options.attribution = options.attribution;
  site_options.kml_refresh_s = options.kml_refresh_s;
  site_options.max_period_s = options.max_period_h * 3600;
  if (!options.mbtiles.empty()) site_options.mbtiles = std::make_shared<geov::MbTiles>(options.mbtiles);

  geov::Fleet fleet;
  const std::vector<std::string> daemons = options.daemons.empty() ? std::vector{global.endpoint} : options.daemons;
  // The environment comes from the first daemon: the buoy's, by the
  // convention of --daemon's help.
  GlobalOptions buoy = global;
  buoy.endpoint = daemons.front();
  auto sections = std::make_shared<geov::TlSection>(buoy, fleet);
  site_options.section = [sections](const telemetry::Position& vehicle) { return sections->picture(vehicle); };
  geov::MapSite site(fleet, site_options);
  geov::HttpServer server({.listen = options.listen, .max_connections = options.max_connections},
                          [&site](const geov::HttpRequest& request, geov::HttpResponder& responder) {
                            site.handle(request, responder);
                          });
  if (!server.loopback() && site_options.token.empty() && !options.insecure_http) {
    throw UsageError("--listen " + options.listen +
                     " is reachable from other machines: give --token-file (viewers open /?token=...), or "
                     "--insecure-http to serve the fleet to anyone who can reach the port");
  }

  std::vector<std::unique_ptr<geov::DaemonFeed>> feeds;
  for (const std::string& endpoint : daemons) {
    GlobalOptions daemon = global;
    daemon.endpoint = endpoint;
    feeds.push_back(std::make_unique<geov::DaemonFeed>(daemon, fleet, options.poll_s));
    feeds.back()->connect_now();
  }
  for (auto& feed : feeds) feed->start();
  std::thread stopper([&] {
    int signal = 0;
    sigwait(&signals, &signal);
    std::fprintf(stderr, "acommsctl geov: stopping (signal %d)\n", signal);
    fleet.close();
    server.stop();
  });
  std::string host = options.listen.substr(0, options.listen.rfind(':'));
  std::fprintf(stderr, "acommsctl geov: serving http://%s:%d/ from %zu daemon(s)\n", host.c_str(), server.port(),
               daemons.size());
  server.run();
  stopper.join();
  for (auto& feed : feeds) feed->stop();
  std::fprintf(stderr, "acommsctl geov: stopped; %d viewers at most at once, %llu refused busy, %llu bad requests\n",
               server.peak_connections(), static_cast<unsigned long long>(server.refused_busy()),
               static_cast<unsigned long long>(server.bad_requests()));
}

}  // namespace

void add_geov_command(CLI::App& app, const GlobalOptions& global) {
  static ServeOptions options;
  CLI::App* geov = app.add_subcommand("geov", "The fleet on a map, in a browser and in Google Earth");
  geov->require_subcommand(1);
  geov->footer("Example:\n  acommsctl geov serve --listen 127.0.0.1:9090 --kml-refresh 10");
  CLI::App* serve = geov->add_subcommand(
      "serve",
      "Serve the map page (built in: it needs no internet) with every vehicle's position, heading, depth, fix "
      "age, track, link figures and queued messages, updated live; the transmission loss from the buoy towards a "
      "vehicle; playback of a period; KML for Google Earth");
  serve->add_option("--listen", options.listen, "HOST:PORT to serve HTTP on (port 0: any free port)")
      ->capture_default_str();
  serve->add_option("--daemon", options.daemons,
                    "A daemon to follow: unix socket or tcp:HOST:PORT, with --ca/--cert/--key/--insecure as for "
                    "every command; repeat for several (default: --socket). The first is the buoy's: the page's "
                    "transmission-loss section runs on its environment (acommsctl gram env)")
      ->type_name("SOCKET");
  serve->add_option("--token-file", options.token_file,
                    "A file whose first line is the token viewers must give (/?token=T, or Authorization: Bearer "
                    "T); required when --listen is not loopback")
      ->type_name("FILE");
  serve->add_flag("--insecure-http", options.insecure_http,
                  "Serve a non-loopback --listen without a token (anyone who reaches the port sees the fleet)");
  serve->add_option("--tiles", options.tile_url,
                    "A tile URL template for the page to draw under the tracks, e.g. http://tiles.ship/{z}/{x}/{y}.png "
                    "(default: a metric grid around the datum, with range rings)")
      ->type_name("URL");
  serve->add_option("--mbtiles", options.mbtiles, "Serve tiles from this local MBTiles file instead")
      ->type_name("FILE");
  serve->add_option("--attribution", options.attribution, "Credit line for the tiles");
  serve->add_option("--max-connections", options.max_connections,
                    "Open HTTP connections at most (each viewer holds one for its live stream)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  serve->add_option("--kml-refresh", options.kml_refresh_s, "Seconds between Google Earth's NetworkLink refreshes")
      ->check(CLI::Range(1.0, 3600.0))
      ->capture_default_str();
  serve->add_option("--max-period", options.max_period_h,
                    "Hours of positions one playback or history request may hold at most")
      ->check(CLI::Range(0.01, 8760.0))
      ->capture_default_str();
  serve->add_option("--poll", options.poll_s, "Seconds between polls of each daemon (tracks back-filled, queues)")
      ->check(CLI::Range(0.1, 60.0))
      ->capture_default_str();
  serve->footer(
      "Open http://HOST:PORT/ in a browser: click a vehicle for the transmission loss from the buoy towards it "
      "(/api/section?src=N); play back a period from a start to an end at a chosen speed. Google Earth: add "
      "/kml/network.kml (a NetworkLink that refreshes), or save /kml/history.kml?from=-1h for the last hour with "
      "time stamps. Stop with Ctrl-C.\n\n"
      "Examples:\n"
      "  acommsctl geov serve\n"
      "  acommsctl geov serve --daemon /run/acommsd/acommsd.sock --daemon tcp:buoy:50051 --ca ca.pem\n"
      "  acommsctl geov serve --listen 0.0.0.0:8080 --token-file /etc/acommsd/map-token --mbtiles chart.mbtiles");
  serve->callback([&global] { run_serve(global, options); });
}

}  // namespace acomms::cli
