// MicroModemDriver's driver-specific part (link/driver_specific.h): the
// requests go to the DriverSpecificExchange; the sentences of those
// exchanges are routed to it (echoes to the command queue), so the data
// path in micromodem_driver.cpp does not see them.

#include "core/core_thread.h"
#include "micromodem/micromodem_driver.h"
#include "micromodem/nmea/fdp_sentences.h"
#include "micromodem/nmea/mini_packet_sentences.h"
#include "micromodem/nmea/ranging_sentences.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using link::DriverSpecificStatus;
using nmea::Sentence;

link::DriverSpecificResult MicroModemDriver::check_driver_specific(const v1::ModemTransmission& request) const {
  return extras_.check(request);
}

void MicroModemDriver::send_driver_specific(const v1::ModemTransmission& request, double deadline_s,
                                            link::DriverSpecificDone done) {
  ACOMMS_ASSERT_CORE_THREAD();
  sequence_.check_running();
  auto busy = [&](const std::string& why) {
    done(link::driver_specific_error(DriverSpecificStatus::kAborted, why, request));
  };
  if (!ready_) return busy("the modem is not ready (start-up in progress)");
  // The slot is ours, but the modem may still be finishing an exchange
  // (an ACK awaited from the previous slot): one exchange at a time (§11).
  if (!cycle_.idle()) return busy("busy: the modem is in a data exchange");
  // With fdp_data, the slot's DATA goes through fdp_, not cycle_: an extra
  // sent meanwhile would take that packet's $CATXF as its own.
  if (!fdp_.idle()) return busy("busy: the modem is sending FDP data");
  extras_.send(request, deadline_s, std::move(done));
}

bool MicroModemDriver::dispatch_driver_specific(const Sentence& s) {
  const std::string address = s.address();
  auto parsed = [this, &s](const auto& result, const Sentence&) {
    if (result) return true;
    bad_input_.note("malformed " + s.address(), result.error().text, scheduler_.clock().now());
    return false;
  };
  // Echoes of the extras' commands.
  if (address == "CAMPC" || address == "CAMUC" || address == "CATDP" || address == "SNPNT" || address == "SNPDT") {
    commands_.on_sentence(s);
    return true;
  }
  if (address == "CAMPR") {
    auto r = nmea::parse_ping_reply(s);
    if (parsed(r, s)) extras_.on_ping_reply(*r);
    return true;
  }
  if (address == "SNTTA") {
    auto r = nmea::parse_travel_times(s);
    if (parsed(r, s)) extras_.on_travel_times(*r);
    return true;
  }
  if (address == "CAMUA") {
    auto r = nmea::parse_mini_packet(s);
    if (parsed(r, s)) extras_.on_mini_packet(*r);
    return true;
  }
  if (address == "CARDP") {
    auto r = nmea::parse_fdp_received(s);
    // With fdp_data, packets in its format are DATA and ACKs; others are extras.
    if (parsed(r, s) && !(settings_.fdp_data && fdp_.on_received(*r))) extras_.on_fdp_received(*r);
    return true;
  }
  if (address == "CAMPA") {
    auto r = nmea::parse_ping(s);
    parsed(r, s);  // a ping for us: the modem replies by itself (§7.1)
    return true;
  }
  // The end of an extra's transmission; else the data cycle's.
  if (address == "CATXF" && !fdp_.idle()) return fdp_.on_transmit_finished();
  if (address == "CATXF" && !extras_.idle()) return extras_.on_transmit_finished();
  return false;
}

}  // namespace acomms::drivers::micromodem
