#include "events_command.h"

#include <charconv>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "api_client.h"
#include "global_options.h"
#include "output.h"
#include "rpc_error.h"
#include "time_arg.h"
#include "util/seconds.h"

namespace acomms::cli {
namespace {

struct EventsOptions {
  std::string since;
  std::string until;
  std::vector<std::string> kinds;
  std::vector<std::string> types;
  int64_t message_id = 0;
  uint32_t limit = 0;
};

std::string id_text(int64_t id) { return id > 0 ? std::to_string(id) : "-"; }

// The Micro-Modem's packet types ($CACST; ReceptionFigures.packet_type).
std::string packet_type_text(int32_t type) {
  switch (type) {
    case 1: return "FSK";
    case 2: return "FSK mini";
    case 3: return "PSK";
    case 4: return "PSK mini";
    case 5: return "FDP";
    default: return "type " + std::to_string(type);
  }
}

// A received event's link figures on one line, only what the modem gave:
// "tx 2 rate 5 PSK, SNR in 12.5 dB out 9 dB, level 131 dB, MSE -14 dB, ...".
std::string link_text(const v1::LinkFigures& link) {
  std::string text = "tx " + std::to_string(link.transmission_src()) + " rate " + std::to_string(link.rate());
  const size_t unmeasured = text.size();
  if (link.has_packet_type()) text += " " + packet_type_text(link.packet_type());
  auto add = [&text](const std::string& part) { text += ", " + part; };
  if (link.has_snr_in_db() || link.has_snr_out_db()) {
    std::string snr = "SNR";
    if (link.has_snr_in_db()) snr += " in " + number_text(link.snr_in_db()) + " dB";
    if (link.has_snr_out_db()) snr += " out " + number_text(link.snr_out_db()) + " dB";
    add(snr);
  }
  if (link.has_signal_level_db()) add("level " + number_text(link.signal_level_db()) + " dB");
  if (link.has_noise_db()) add("noise " + number_text(link.noise_db()) + " dB");
  if (link.has_mse_db()) add("MSE " + number_text(link.mse_db()) + " dB");
  if (link.has_doppler_mps()) add("Doppler " + number_text(link.doppler_mps()) + " m/s");
  if (link.has_delay_spread_s()) add("delay spread " + number_text(link.delay_spread_s()) + " s");
  if (link.has_bad_frames()) add("bad frames " + std::to_string(link.bad_frames()));
  if (link.has_range_m()) add("range " + number_text(link.range_m()) + " m");
  if (link.has_predicted_snr_db()) {
    add("predicted SNR " + number_text(link.predicted_snr_db()) + " dB" +
        (link.has_predicted_tl_db() ? " (TL " + number_text(link.predicted_tl_db()) + " dB)" : ""));
  }
  if (link.has_decoded()) add(link.decoded() ? "decoded" : "lost");
  // The driver's free-text summary repeats what it measured (--json has
  // it); shown only when it is all there is.
  if (text.size() == unmeasured && !link.link_quality().empty()) add(link.link_quality());
  return text;
}

void print_events(const v1::EventsResponse& response) {
  if (response.truncated()) std::printf("(older events left out; narrow with --since or raise --limit)\n");
  std::printf("%-25s %-9s %-28s %7s %-17s %-8s %s\n", "TIME", "KIND", "TYPE", "MESSAGE", "FRAME", "SRC>DEST", "DETAIL");
  for (const v1::Event& e : response.events()) {
    std::string frame = e.frame_id() > 0 ? std::to_string(e.frame_id()) : "-";
    // A received event's detail is how it arrived: its link figures.
    std::string detail = e.detail();
    if (e.has_link()) detail += (detail.empty() ? "" : "; ") + link_text(e.link());
    std::printf("%-25s %-9s %-28s %7s %-17s %-8s %s\n", utc_text(e.time()).c_str(), e.kind().c_str(), e.type().c_str(),
                id_text(e.message_id()).c_str(), frame.c_str(), route_text(e.src(), e.dest()).c_str(), detail.c_str());
  }
}

void run_events(const GlobalOptions& global, const EventsOptions& options) {
  v1::EventsRequest request;
  const double now = util::unix_seconds_now();
  if (!options.since.empty()) request.set_since(parse_time(options.since, now));
  if (!options.until.empty()) request.set_until(parse_time(options.until, now));
  for (const std::string& kind : options.kinds) request.add_kinds(kind);
  // Packet events (one per packet heard, polls and ACKs included) outnumber
  // the messages' own stories many times over: shown only when asked for.
  if (options.kinds.empty()) {
    for (const std::string& kind : event_kinds()) {
      if (kind != "packet") request.add_kinds(kind);
    }
  }
  for (const std::string& type : options.types) request.add_types(type);
  request.set_message_id(options.message_id);
  request.set_limit(options.limit);
  ApiClient client(global);
  v1::EventsResponse response = client.call(&v1::Acomms::Stub::Events, request);
  if (global.json) {
    print_json(response);
  } else {
    print_events(response);
  }
}

}  // namespace

const std::vector<std::string>& event_kinds() {
  static const std::vector<std::string> kinds = {"queued", "sent",  "acked",    "expired", "dropped",
                                                 "retry",  "received", "packet", "delivered"};
  return kinds;
}

void add_events_command(CLI::App& app, const GlobalOptions& global) {
  static EventsOptions options;
  CLI::App* events = app.add_subcommand("events", "The event log: what happened to each message, and when");
  events->add_option("--since", options.since, "From this time (default: the beginning)")->type_name("T");
  events->add_option("--until", options.until, "Up to this time (default: now)")->type_name("T");
  std::string kinds;
  for (const std::string& kind : event_kinds()) kinds += (kinds.empty() ? "" : ", ") + kind;
  events->add_option("--kind", options.kinds, "Only these kinds: " + kinds + " (default: all but packet)")
      ->type_name("KIND")
      ->allow_extra_args(false)
      ->check(CLI::IsMember(event_kinds()));
  events->add_option("--type", options.types, "Only these message types")
      ->type_name("TYPE")
      ->allow_extra_args(false);
  events->add_option("--message", options.message_id, "Only this message's history (its id)")->type_name("ID");
  events->add_option("--limit", options.limit, "At most this many, the newest (default 1000, most 10000)")
      ->type_name("N");
  events->footer(
      "Oldest first: each message's story (queued, sent in a frame, acked, retried, expired, dropped "
      "or cancelled) and what was received, with the link figures it arrived with (who transmitted, "
      "rate, packet type, SNR, signal level, MSE, ...; \"link\" in --json). A \"packet\" event is one packet "
      "heard from another node, decoded or lost, with its figures and, when known, the model's predicted "
      "SNR and TL (what `acommsctl link calibrate` fits). T is seconds since the Unix epoch, \"now\", or relative "
      "to now: -30s, -10m, -2h, -1d.\n\n"
      "Examples:\n"
      "  acommsctl events --since -10m\n"
      "  acommsctl events --message 42\n"
      "  acommsctl events --kind dropped --kind expired --type gv.NavigationReport --since -2h\n"
      "  acommsctl events --kind packet --since -1h");
  events->callback([&global] { run_events(global, options); });
}

}  // namespace acomms::cli
