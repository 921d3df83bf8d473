// The received sentences of the data path, each to the one part that owns
// it (micromodem_driver.h lists the parts). A table by sentence type, not a
// chain of comparisons: a reader finds a sentence's owner in one line, and
// adding a sentence adds one row. A sentence that does not parse is counted
// as bad input, never passed on half-read; a known sentence the data path
// does not need is ignored by name; anything else is counted as unknown.
// Driver-specific sentences (ping, LBL, mini-packets, FDP) are taken first,
// by micromodem_driver_specific.cpp.

#include <spdlog/spdlog.h>

#include <string>
#include <string_view>
#include <unordered_map>

#include "micromodem/micromodem_driver.h"
#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"
#include "micromodem/poll_frames.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using nmea::Sentence;
using v1::ModemTransmission;

template <typename T>
bool MicroModemDriver::parsed(const nmea::Result<T>& result, const Sentence& sentence) {
  if (result) return true;
  bad_input_.note("malformed " + sentence.address(), result.error().text, scheduler_.clock().now());
  return false;
}

const std::unordered_map<std::string_view, MicroModemDriver::Route>& MicroModemDriver::routes() {
  using D = MicroModemDriver;
  // Known and not needed by a data driver (clock and device queries,
  // ping/LBL/mini-packet echoes, MM2 clock reports).
  constexpr Route ignore = [](D&, const Sentence&) {};
  // Replies to a command, else a line of a dump, or a late echo.
  constexpr Route to_commands = [](D& d, const Sentence& s) { d.commands_.on_sentence(s); };
  static const std::unordered_map<std::string_view, Route> table = {
      {"REV", [](D& d, const Sentence& s) { d.on_revision(s); }},
      {"CFG", to_commands},
      {"CLK", to_commands},
      {"TMS", to_commands},
      {"CYC", [](D& d, const Sentence& s) { d.on_cycle(s); }},
      {"ERR", [](D& d, const Sentence& s) { d.on_error(s); }},
      {"DRQ",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_data_request(s); d.parsed(r, s)) d.cycle_.on_data_request(*r);
       }},
      {"TXD", [](D& d, const Sentence& s) { d.parsed(nmea::parse_transmit_data_accepted(s), s); }},
      {"TXP",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_transmit_started(s); d.parsed(r, s)) d.cycle_.on_transmit_started(*r);
       }},
      {"TXF",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_transmit_finished(s); d.parsed(r, s)) d.cycle_.on_transmit_finished(*r);
       }},
      {"XST",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_transmit_statistics(s); d.parsed(r, s)) d.cycle_.on_transmit_statistics(*r);
       }},
      {"RXP",
       [](D& d, const Sentence& s) {
         if (d.parsed(nmea::parse_receive_started(s), s)) d.reception_.on_receive_started();
       }},
      {"RXD",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_received_data(s); d.parsed(r, s)) d.reception_.on_data(*r);
       }},
      {"MSG",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_transaction_message(s); d.parsed(r, s)) {
           d.reception_.on_message(*r);
           d.cycle_.on_message(*r);
         }
       }},
      {"CST",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_receive_statistics(s); d.parsed(r, s)) d.reception_.on_statistics(*r);
         d.acks_.on_statistics();  // parsed or not: a $CACST ends the ACK mini-packet
       }},
      {"ACK",
       [](D& d, const Sentence& s) {
         if (auto r = nmea::parse_acknowledgement(s); d.parsed(r, s)) d.acks_.on_ack(*r);
       }},
      {"TMQ", ignore}, {"TMG", ignore}, {"ALQ", ignore}, {"CLQ", ignore}, {"MPC", ignore}, {"MPA", ignore},
      {"MPR", ignore}, {"MUC", ignore}, {"MUA", ignore}, {"MUR", ignore}, {"MEC", ignore}, {"MEA", ignore},
      {"MER", ignore}, {"MSC", ignore}, {"MSA", ignore}, {"MSR", ignore}, {"TDP", ignore}, {"RDP", ignore},
      {"CDR", ignore}, {"DQF", ignore}, {"DOP", ignore}, {"MFD", ignore}, {"SHF", ignore}, {"SNR", ignore},
      {"TOA", ignore}, {"RXA", ignore}, {"TXA", ignore},
  };
  return table;
}

void MicroModemDriver::dispatch(const Sentence& s) {
  if (dispatch_driver_specific(s)) return;
  if (s.talker == "CA") {
    auto route = routes().find(s.type);
    if (route != routes().end()) return route->second(*this, s);
  } else if (s.talker == "SN" || s.talker == "GP") {
    return;  // navigation and forwarded GPS: not used by this driver
  }
  bad_input_.note("unknown sentence", "$" + s.address() + " ignored", scheduler_.clock().now());
}

void MicroModemDriver::on_revision(const Sentence& s) {
  auto revision = nmea::parse_revision(s);
  if (!parsed(revision, s)) return;
  if (revision->is_boot()) return on_reboot();
  if (revision->identifier == "AUV") {
    auto generation = nmea::modem_generation(revision->revision);
    if (generation) generation_ = *generation;
    revision_ = revision->revision;
    // Before the start-up writes the FDP header setting an MM1 would refuse.
    if (refuse_fdp_on_mm1()) return;
  }
  if (startup_) startup_->on_revision(*revision);
}

void MicroModemDriver::on_cycle(const Sentence& s) {
  auto cycle = nmea::parse_cycle(s);
  if (!parsed(cycle, s)) return;
  if (cycle_.on_cycle(*cycle)) return;  // the echo of our $CCCYC
  reception_.on_cycle(*cycle);
  // ADR1 = our SRC from the water: another node polls us (§8.2).
  if (cycle->source == settings_.id && ready_ && cycle_.idle()) answer_poll(*cycle);
}

void MicroModemDriver::answer_poll(const nmea::Cycle& cycle) {
  // A frameless DATA under our own id is how driver_sequence recognises a
  // poll for us; it asks the queues and calls send(), which then starts an
  // exchange without a $CCCYC of ours (answering_poll_).
  ModemTransmission poll;
  poll.set_type(ModemTransmission::DATA);
  poll.set_src(settings_.id);
  poll.set_dest(cycle.destination);
  poll.set_rate(cycle.rate);
  poll.set_ack_requested(cycle.ack);
  poll.set_max_num_frames(polled_frames(cycle.rate, cycle.frames));  // Nframes: what the master asked for
  poll.set_time(now_seconds());
  answering_poll_ = true;
  sequence_.on_received(poll);
  answering_poll_ = false;
}

void MicroModemDriver::on_error(const Sentence& s) {
  auto error = nmea::parse_modem_error(s);
  if (!parsed(error, s)) return;
  bad_input_.note("modem error", "$CAERR " + error->module + " " + error->number + " " + error->message,
                  scheduler_.clock().now());
  if (commands_.on_error(*error)) return;
  cycle_.on_error(*error);
}


}  // namespace acomms::drivers::micromodem
