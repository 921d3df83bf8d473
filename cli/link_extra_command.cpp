#include "link_extra_command.h"

#include <charconv>
#include <cstdio>
#include <string>
#include <vector>

#include "acomms/drivers/micromodem_transmission.pb.h"
#include "api_client.h"
#include "comma_list.h"
#include "global_options.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

using drivers::MicroModemTransmission;

struct ExtraOptions {
  double wait_s = 60;
  int32_t dest = 0;
  std::string value;
  std::string narrowband;  // reply frequencies, comma-separated
  std::string remus;       // beacon letters
  uint32_t channel = 1;
  uint32_t timeout_ms = 4000;
  uint32_t turnaround_ms = 50;
  uint32_t ftx_hz = 25000;
};

v1::DriverSpecificResponse call(const GlobalOptions& global, const ExtraOptions& options, int32_t dest,
                                MicroModemTransmission ask) {
  if (!(options.wait_s > 0)) throw UsageError("--wait must be a positive number of seconds");
  GlobalOptions waiting = global;
  waiting.timeout_s = options.wait_s;  // the wait for the slot is part of the call's deadline
  v1::DriverSpecificRequest request;
  v1::ModemTransmission* tx = request.mutable_transmission();
  tx->set_type(v1::ModemTransmission::DRIVER_SPECIFIC);
  tx->set_dest(dest);
  *tx->MutableExtension(drivers::micromodem_transmission) = std::move(ask);
  ApiClient client(waiting);
  return client.call(&v1::Acomms::Stub::DriverSpecific, request);
}

const MicroModemTransmission& answer_of(const v1::DriverSpecificResponse& response) {
  return response.transmission().GetExtension(drivers::micromodem_transmission);
}

void print_waited(const v1::DriverSpecificResponse& response) {
  std::printf("(waited %.1f s for this node's slot)\n", response.waited_s());
}

void run_ping(const GlobalOptions& global, const ExtraOptions& options) {
  MicroModemTransmission ask;
  ask.set_kind(MicroModemTransmission::PING);
  v1::DriverSpecificResponse response = call(global, options, options.dest, ask);
  if (global.json) return print_json(response);
  const MicroModemTransmission& answer = answer_of(response);
  std::printf("modem %d: one-way travel time %.4f s, range %.1f m ", options.dest, answer.travel_time_s(),
              answer.range_m());
  print_waited(response);
}

uint32_t parse_value(const std::string& text) {
  uint32_t value = 0;
  bool hex = text.starts_with("0x") || text.starts_with("0X");
  std::string digits = hex ? text.substr(2) : text;
  auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value, hex ? 16 : 10);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || value > 0x1FFF) {
    throw UsageError("VALUE \"" + text + "\" is not 0..8191 (13 bits; decimal, or hex as 0x1FFF)");
  }
  return value;
}

void run_mini(const GlobalOptions& global, const ExtraOptions& options) {
  MicroModemTransmission ask;
  ask.set_kind(MicroModemTransmission::MINI_PACKET);
  ask.set_mini_packet_value(parse_value(options.value));
  v1::DriverSpecificResponse response = call(global, options, options.dest, ask);
  if (global.json) return print_json(response);
  std::printf("mini-packet 0x%04X sent to %d ", ask.mini_packet_value(), options.dest);
  print_waited(response);
}

void run_lbl(const GlobalOptions& global, const ExtraOptions& options) {
  if (options.narrowband.empty() == options.remus.empty()) {
    throw UsageError("give either --narrowband FREQ,... (reply frequencies, Hz) or --remus LETTERS (beacons A..D)");
  }
  MicroModemTransmission ask;
  if (!options.narrowband.empty()) {
    ask.set_kind(MicroModemTransmission::NARROWBAND_LBL);
    auto* lbl = ask.mutable_narrowband_lbl();
    for (const std::string& item : split_commas(options.narrowband)) {
      uint32_t hz = 0;
      auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), hz);
      if (item.empty() || error != std::errc() || end != item.data() + item.size() || hz == 0) {
        throw UsageError("--narrowband: \"" + item + "\" is not a frequency in Hz");
      }
      lbl->add_reply_frequency_hz(hz);
    }
    lbl->set_timeout_ms(options.timeout_ms);
    lbl->set_turnaround_ms(options.turnaround_ms);
    lbl->set_transmit_frequency_hz(options.ftx_hz);
  } else {
    ask.set_kind(MicroModemTransmission::REMUS_LBL);
    auto* lbl = ask.mutable_remus_lbl();
    lbl->set_beacons(options.remus);
    lbl->set_channel(options.channel);
    lbl->set_timeout_ms(options.timeout_ms);
  }
  v1::DriverSpecificResponse response = call(global, options, 0, ask);
  if (global.json) return print_json(response);
  for (const drivers::LblReply& reply : answer_of(response).lbl_reply()) {
    std::string which = reply.transponder();
    if (reply.has_frequency_hz()) which += " (" + std::to_string(reply.frequency_hz()) + " Hz)";
    if (reply.answered()) {
      std::printf("%-12s one-way travel time %.4f s, range %.1f m\n", which.c_str(), reply.travel_time_s(),
                  reply.range_m());
    } else {
      std::printf("%-12s no reply\n", which.c_str());
    }
  }
  print_waited(response);
}

}  // namespace

void add_link_extra_commands(CLI::App& link, const GlobalOptions& global) {
  static ExtraOptions ping_options, mini_options, lbl_options;
  const char* wait_help = "Seconds to wait for this node's slot and the answer (the call's deadline)";
  const char* slot_rule =
      "It goes out only in this node's own slot (a node without slots: when a poll gives it the channel), "
      "so it may first wait for one; --wait bounds the whole call.";

  CLI::App* ping = link.add_subcommand("ping", "Two-way ping (Micro-Modem): travel time and range to a modem");
  ping->add_option("DEST", ping_options.dest, "Modem id to ping")->required();
  ping->add_option("--wait", ping_options.wait_s, wait_help)->capture_default_str();
  ping->footer(std::string("The modem measures the round trip and reports the one-way travel time; the range ") +
               "uses driver.micromodem.sound_speed_mps (1500). " + slot_rule + "\n\nExample:\n  acommsctl link ping 2");
  ping->callback([&global] { run_ping(global, ping_options); });

  CLI::App* lbl = link.add_subcommand("lbl", "LBL interrogation of seafloor transponders (Micro-Modem)");
  lbl->add_option("--narrowband", lbl_options.narrowband,
                  "Narrowband ($CCPNT): the reply frequencies of transponders A..D, Hz, comma-separated");
  lbl->add_option("--remus", lbl_options.remus, "REMUS digital ($CCPDT): the beacons to listen for, e.g. ABCD");
  lbl->add_option("--channel", lbl_options.channel, "REMUS interrogation channel 1..4")->capture_default_str();
  lbl->add_option("--timeout-ms", lbl_options.timeout_ms, "How long the modem listens, ms")->capture_default_str();
  lbl->add_option("--turnaround-ms", lbl_options.turnaround_ms, "Narrowband transponders' turnaround (TAT), ms")
      ->capture_default_str();
  lbl->add_option("--ftx", lbl_options.ftx_hz, "Narrowband interrogation frequency, Hz")->capture_default_str();
  lbl->add_option("--wait", lbl_options.wait_s, wait_help)->capture_default_str();
  lbl->footer(std::string("Prints the one-way travel time and range to each transponder, or that it did not "
                          "reply. ") +
              slot_rule +
              "\n\nExamples:\n  acommsctl link lbl --narrowband 26000,27000\n  acommsctl link lbl --remus AB --channel 2");
  lbl->callback([&global] { run_lbl(global, lbl_options); });

  CLI::App* mini = link.add_subcommand("mini", "Send a 13-bit user mini-packet (Micro-Modem)");
  mini->add_option("DEST", mini_options.dest, "Modem id (0: everyone)")->required();
  mini->add_option("VALUE", mini_options.value, "0..8191, decimal or 0x hex")->required();
  mini->add_option("--wait", mini_options.wait_s, wait_help)->capture_default_str();
  mini->footer(std::string("The receiving daemon's subscribers get it as acomms.drivers.MicroModemMiniPacket. ") +
               slot_rule + "\n\nExample:\n  acommsctl link mini 2 0x1ABC");
  mini->callback([&global] { run_mini(global, mini_options); });
}

}  // namespace acomms::cli
