#include "link_calibrate_command.h"

#include <cstdio>
#include <iostream>

#include "api_client.h"
#include "eval/link_calibration.h"
#include "link_calibration_plot.h"
#include "rpc_error.h"
#include "time_arg.h"
#include "util/seconds.h"

namespace acomms::cli {
namespace {

// The Events RPC's most per call (acomms.proto EventsRequest.limit).
constexpr uint32_t kMostEvents = 10000;

struct CalibrateOptions {
  std::string since;
  std::string png;
};

void run_calibrate(const GlobalOptions& global, const CalibrateOptions& options) {
  v1::EventsRequest request;
  if (!options.since.empty()) request.set_since(parse_time(options.since, util::unix_seconds_now()));
  request.add_kinds("packet");
  request.set_limit(kMostEvents);
  ApiClient client(global);
  const v1::EventsResponse response = client.call(&v1::Acomms::Stub::Events, request);
  const std::vector<v1::Event> events(response.events().begin(), response.events().end());
  std::size_t skipped = 0;
  const std::vector<eval::PacketSample> samples = eval::packet_samples(events, &skipped);
  if (response.truncated()) {
    std::printf("(only the newest %u packets: narrow with --since to fit an older period)\n", kMostEvents);
  }
  if (skipped > 0) {
    std::printf("(%zu packets left out: no model prediction, i.e. no environment, a position unknown, or a "
                "shadow)\n",
                skipped);
  }
  const std::vector<eval::LinkCalibration> links = eval::calibrate_links(samples);
  std::fputs(eval::calibration_report(links).c_str(), stdout);
  bool any = false;
  for (const eval::LinkCalibration& link : links) {
    if (!link.fitted()) continue;
    any = true;
    std::printf("\n%s", eval::physics_block(link).c_str());
  }
  if (!options.png.empty() && !samples.empty()) {
    write_link_calibration_png(options.png, samples, links);
    std::printf("\nwrote %s\n", options.png.c_str());
  }
  if (!any) {
    std::cerr << "acommsctl: too few data to calibrate: " << samples.size()
              << " packets with a model prediction in the event log"
              << (options.since.empty() ? "" : " since " + options.since) << "; each link needs at least "
              << eval::kMinMeasured << " decoded packets with a measured SNR (excess loss) or "
              << eval::kMinPackets << " packets, " << eval::kMinEachOutcome
              << " of them decoded and as many lost (reception curve)\n";
    throw CLI::RuntimeError(kExitRefused);
  }
}

}  // namespace

void add_link_calibrate_command(CLI::App& link, const GlobalOptions& global) {
  static CalibrateOptions options;
  CLI::App* calibrate =
      link.add_subcommand("calibrate", "Fit the link physics (excess loss, reception curve) to the packets heard");
  calibrate->add_option("--since", options.since, "Packets from this time (default: all the log keeps)")
      ->type_name("T");
  calibrate->add_option("--png", options.png, "Plot measured against predicted SNR, and decoding against it")
      ->type_name("FILE");
  calibrate->footer(
      "Reads this node's \"packet\" events (one per packet heard from another node, decoded or not, with "
      "the SNR the modem measured and the SNR the model predicted for the geometry: SL - TL - NL) and "
      "fits, per link of this node (LinkConfig.name), sending node and rate:\n"
      "  excess loss = -offset, the offset being the mean of measured - predicted SNR over decoded packets, "
      "with its spread (standard deviation: how single packets scatter about the model) and a 95% interval; "
      "with scatter and at least 5 lost packets, a censored fit (lost packets counted, Tobit-style) corrects "
      "that mean's bias towards the packets that decoded and gives the excess loss printed;\n"
      "  reception curve = P(decoded) against predicted SNR, logistic: its 50% point and slope (per dB) "
      "with 95% intervals.\n"
      "Prints a physics { ... } block for the simulator (driver.sim.physics: add env_file and the noise), "
      "whose snr50_db is against the corrected SNR (predicted - excess loss), as the physics applies it. "
      "Too few data (fewer than 10 decoded packets with an SNR, or 30 packets with 5 decoded and 5 lost) "
      "are refused with the reason, exit status 1.\n\n"
      "Examples:\n  acommsctl link calibrate --since -2h --png link.png\n"
      "  acommsctl link calibrate --since 1748772000");
  calibrate->callback([&global] { run_calibrate(global, options); });
}

}  // namespace acomms::cli
