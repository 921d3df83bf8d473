#include "link_command.h"

#include <google/protobuf/util/json_util.h>

#include <charconv>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "api_client.h"
#include "consistency_text.h"
#include "global_options.h"
#include "link_calibrate_command.h"
#include "link_extra_command.h"
#include "link_raw_command.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

constexpr const char* kSlotSyntax = "SRC[:DEST]@RATE/SECONDS, e.g. 1@1/10 or 2:1@1/10";

struct CycleOptions {
  std::vector<std::string> slots;
  std::string json;
  CLI::Option* json_option = nullptr;
};

template <typename T>
bool parse_whole(const std::string& text, T* value) {
  const char* end = text.data() + text.size();
  auto [ptr, error] = std::from_chars(text.data(), end, *value);
  return !text.empty() && error == std::errc() && ptr == end;
}

std::string slot_text(const v1::MacSlot& slot) {
  return std::to_string(slot.src()) + (slot.has_dest() ? ":" + std::to_string(slot.dest()) : "") + "@" +
         std::to_string(slot.rate()) + "/" + number_text(slot.seconds());
}

void print_status(const v1::LinkStatusResponse& link) {
  const v1::DriverStatus& driver = link.driver();
  // A node with one link in the old form ("default") prints as it always did.
  if (!link.name().empty() && link.name() != "default") {
    std::printf("link:         %s, %s%s\n", link.name().c_str(), link.enabled() ? "enabled" : "disabled",
                link.cost() > 0 ? (", cost " + number_text(link.cost())).c_str() : "");
  }
  std::printf("modem id:     %u\n", link.modem_id());
  std::printf("driver:       %s, %s (started %llu time(s), %llu failure(s))\n", driver.name().c_str(),
              driver.state().c_str(), static_cast<unsigned long long>(driver.starts()),
              static_cast<unsigned long long>(driver.failures()));
  if (!driver.summary().empty() && driver.summary() != driver.state()) std::printf("              %s\n", driver.summary().c_str());
  if (!driver.last_error().empty()) std::printf("  last error: %s\n", driver.last_error().c_str());
  if (!driver.modem().empty()) std::printf("modem:        %s\n", driver.modem().c_str());
  std::printf("mac:          %s", link.mac().empty() ? "none" : link.mac().c_str());
  if (link.cycle_size() > 0) std::printf(", cycle %s s", number_text(link.cycle_seconds()).c_str());
  if (!link.blank_rule().empty()) std::printf(", blank rule %s", link.blank_rule().c_str());
  std::printf("\n");
  for (int i = 0; i < link.cycle_size(); ++i) {
    const v1::MacSlot& slot = link.cycle(i);
    std::string dest = slot.has_dest() ? std::to_string(slot.dest()) : "any";
    std::printf("  slot %-3d    %s  (src %d -> %s, rate %d, %s s)\n", i + 1, slot_text(slot).c_str(), slot.src(),
                dest.c_str(), slot.rate(), number_text(slot.seconds()).c_str());
  }
  std::string nodes;
  for (int32_t node : link.known_nodes()) nodes += (nodes.empty() ? "" : ", ") + std::to_string(node);
  std::printf("known nodes:  %s\n", nodes.empty() ? "-" : nodes.c_str());
  const v1::LinkCounters& c = link.counters();
  std::printf("counters:     sent %llu, failed %llu, data received %llu, acks received %llu,\n"
              "              delivered %llu, duplicates dropped %llu, stale refused %llu, malformed frames %llu,\n"
              "              lost to half-duplex %llu, lost to collisions %llu\n",
              static_cast<unsigned long long>(c.transmissions_sent()),
              static_cast<unsigned long long>(c.transmissions_failed()),
              static_cast<unsigned long long>(c.data_received()), static_cast<unsigned long long>(c.acks_received()),
              static_cast<unsigned long long>(c.messages_delivered()),
              static_cast<unsigned long long>(c.duplicates_dropped()),
              static_cast<unsigned long long>(c.stale_refused()),
              static_cast<unsigned long long>(c.malformed_frames()),
              static_cast<unsigned long long>(c.lost_half_duplex()),
              static_cast<unsigned long long>(c.lost_collision()));
  // Authenticated types' refusals (config auth; zero without it).
  {
    std::printf("auth refused: auth_failed %llu, replayed %llu, stale %llu\n",
                static_cast<unsigned long long>(c.auth_failed()),
                static_cast<unsigned long long>(c.auth_replayed()),
                static_cast<unsigned long long>(c.auth_stale()));
  }
  if (!c.bad_input().empty()) {
    // Sorted by kind: a map field's order is not defined.
    std::map<std::string, uint64_t> kinds(c.bad_input().begin(), c.bad_input().end());
    std::string text;
    for (const auto& [kind, count] : kinds) text += (text.empty() ? "" : ", ") + kind + " " + std::to_string(count);
    std::printf("bad input:    %s\n", text.c_str());
  }
  // Fleet consistency on this link: its digest and the nodes heard on it.
  const double now_s = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  print_consistency("", link.consistency_digest(), link.consistency(), now_s);
}

void run_status(const GlobalOptions& global, const std::string& name) {
  ApiClient client(global);
  v1::LinkStatusRequest request;
  request.set_link(name);
  v1::LinkStatusResponse response = client.call(&v1::Acomms::Stub::LinkStatus, request);
  if (global.json) {
    print_json(response);
    return;
  }
  // A daemon from before several links fills no `links`.
  if (response.links_size() == 0) return print_status(response);
  for (int i = 0; i < response.links_size(); ++i) {
    if (i > 0) std::printf("\n");
    print_status(response.links(i));
  }
}

void run_enable(const GlobalOptions& global, const std::string& name, bool enabled) {
  ApiClient client(global);
  v1::SetLinkEnabledRequest request;
  request.set_link(name);
  request.set_enabled(enabled);
  v1::SetLinkEnabledResponse response = client.call(&v1::Acomms::Stub::SetLinkEnabled, request);
  if (global.json) {
    print_json(response);
  } else {
    std::printf("link %s %s\n", name.c_str(), response.enabled() ? "enabled" : "disabled");
  }
}

v1::SetCycleRequest cycle_from_json(const std::string& json) {
  // The array is parsed as SetCycleRequest.slot, so the names are the API's.
  v1::SetCycleRequest request;
  auto status = google::protobuf::util::JsonStringToMessage("{\"slot\":" + json + "}", &request);
  if (!status.ok()) {
    throw UsageError("--json: expected an array of slots like [{\"src\":1,\"rate\":1,\"seconds\":10}]: " +
                     std::string(status.message()));
  }
  return request;
}

void run_cycle(const GlobalOptions& global, CycleOptions options) {
  // `link cycle 1@1/10 --json` asks for JSON output; CLI11 gave --json the
  // next word, which is a slot when it is not a JSON array.
  const size_t first = options.json.find_first_not_of(" \t\n");
  if (first != std::string::npos && options.json[first] != '[') {
    options.slots.push_back(options.json);
    options.json.clear();
  }
  const bool json_in = options.json.find_first_not_of(" \t\n") != std::string::npos;
  if (json_in && !options.slots.empty()) throw UsageError("give the cycle either as SLOT arguments or as --json, not both");
  if (!json_in && options.slots.empty()) throw UsageError("no slots: give at least one " + std::string(kSlotSyntax));
  v1::SetCycleRequest request;
  if (json_in) {
    request = cycle_from_json(options.json);
  } else {
    for (const std::string& slot : options.slots) *request.add_slot() = parse_slot(slot);
  }
  ApiClient client(global);
  v1::SetCycleResponse response = client.call(&v1::Acomms::Stub::SetCycle, request);
  if (global.json || options.json_option->count() > 0) {
    print_json(response);
  } else {
    std::printf("cycle of %d slot(s), %s s, takes effect at the next cycle boundary\n", request.slot_size(),
                number_text(response.cycle_seconds()).c_str());
  }
}

}  // namespace

v1::MacSlot parse_slot(const std::string& text) {
  auto bad = [&](const std::string& why) {
    return UsageError("slot \"" + text + "\": " + why + " (a slot is " + kSlotSyntax + ")");
  };
  const size_t at = text.find('@');
  if (at == std::string::npos) throw bad("no '@' before the rate");
  const size_t slash = text.find('/', at);
  if (slash == std::string::npos) throw bad("no '/' before the seconds");
  const std::string who = text.substr(0, at);
  const size_t colon = who.find(':');
  v1::MacSlot slot;
  int32_t src = 0, dest = 0, rate = 0;
  double seconds = 0;
  if (!parse_whole(who.substr(0, colon), &src)) throw bad("SRC is not a modem id");
  slot.set_src(src);
  if (colon != std::string::npos) {
    if (!parse_whole(who.substr(colon + 1), &dest)) throw bad("DEST is not a modem id");
    slot.set_dest(dest);
  }
  if (!parse_whole(text.substr(at + 1, slash - at - 1), &rate)) throw bad("RATE is not a whole number");
  slot.set_rate(rate);
  if (!parse_whole(text.substr(slash + 1), &seconds) || !(seconds > 0)) throw bad("SECONDS is not a positive number");
  slot.set_seconds(seconds);
  return slot;
}

void add_link_command(CLI::App& app, const GlobalOptions& global) {
  static CycleOptions cycle_options;
  static std::string status_link;
  static std::string enable_link;
  static std::string disable_link;
  CLI::App* link = app.add_subcommand("link", "The node's links: modem driver health and the MAC's TDMA cycle");
  link->require_subcommand(1);
  link->footer("Example:\n  acommsctl link status");

  CLI::App* status = link->add_subcommand("status", "Modem driver state, MAC cycle, known nodes, counters, fleet consistency");
  status->add_option("NAME", status_link, "One link by name (config `link { name: ... }`); default: every link");
  status->footer(
      "Shows, for each of the node's links (or the one named), the modem driver (running, or restarting "
      "after a failure), whether the link is enabled and its cost, the MAC and its cycle of slots, the "
      "nodes it knows, and link counters (transmissions, acks, messages delivered, duplicates, malformed "
      "frames, packets lost to half-duplex and to collisions), and fleet consistency on the link: this "
      "node's digest there and, per node heard announcing one, whether it agrees and since when it has "
      "not (README \"Consistency across a fleet\").\n\n"
      "Examples:\n  acommsctl link status --json\n  acommsctl link status iridium");
  status->callback([&global] { run_status(global, status_link); });

  CLI::App* enable = link->add_subcommand("enable", "Let a link send again (its MAC and driver start)");
  enable->add_option("NAME", enable_link, "The link (config `link { name: ... }`)")->required();
  enable->footer(
      "Starts the link's driver and MAC again. A link with enable_above_depth_m is also enabled and "
      "disabled by the vehicle's depth; this command holds until the depth next crosses that threshold.\n\n"
      "Example:\n  acommsctl link enable iridium");
  enable->callback([&global] { run_enable(global, enable_link, true); });

  CLI::App* disable = link->add_subcommand("disable", "Stop a link sending (its MAC and driver stop)");
  disable->add_option("NAME", disable_link, "The link (config `link { name: ... }`)")->required();
  disable->footer(
      "Stops the link's MAC and driver: it sends and hears nothing until enabled. Messages awaiting an "
      "ACK on it may go on the node's other links at once.\n\n"
      "Example:\n  acommsctl link disable iridium");
  disable->callback([&global] { run_enable(global, disable_link, false); });

  add_link_raw_command(*link, global);
  add_link_extra_commands(*link, global);
  add_link_calibrate_command(*link, global);

  CLI::App* cycle = link->add_subcommand("cycle", "Replace the MAC's TDMA cycle of slots");
  cycle->add_option("SLOT", cycle_options.slots,
                    "Slots in order, each SRC[:DEST]@RATE/SECONDS: SRC transmits (modem id), to DEST "
                    "(default: the queues choose), at Micro-Modem RATE (0 = FSK), for SECONDS")
      ->type_name("");
  cycle_options.json_option =
      cycle->add_option("--json", cycle_options.json,
                        "The cycle as a JSON array of {src, dest, rate, seconds} instead of SLOTs "
                        "(output is JSON too); alone, just JSON output")
          ->expected(0, 1)
          ->type_name("JSON");
  cycle->footer(
      "For the polled and fixed MACs. A slot is SRC[:DEST]@RATE/SECONDS: modem SRC transmits, to DEST "
      "(default: its queues choose), at Micro-Modem RATE (0 = FSK), for SECONDS. The new cycle takes "
      "effect at the next cycle boundary and lasts until the daemon restarts. Every node of a fixed "
      "TDMA network must be given the same cycle.\n\n"
      "Examples:\n"
      "  acommsctl link cycle 1@1/10 2:1@1/10   # node 1 sends 10 s at rate 1, then node 2 to node 1\n"
      "  acommsctl link cycle --json '[{\"src\":1,\"rate\":1,\"seconds\":10},{\"src\":2,\"dest\":1,\"rate\":1,\"seconds\":10}]'");
  cycle->callback([&global] { run_cycle(global, cycle_options); });
}

}  // namespace acomms::cli
