// Checking a driver-specific request at once, before the modem hears of
// it: every bound the modem or the spec sets (§6-§7), each refusal naming
// the field and its range. INVALID_ARGUMENT for the request itself;
// FAILED_PRECONDITION for what this modem or network cannot do (FDP on an
// MM1, FDP not configured, FDP towards an MM1); UNIMPLEMENTED for another
// driver's request.
#include "micromodem/driver_specific_request.h"

#include <algorithm>
#include <string>

#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/fdp_sentences.h"
#include "micromodem/nmea/mini_packet_sentences.h"
#include "micromodem/nmea/ranging_sentences.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using link::DriverSpecificResult;
using link::DriverSpecificStatus;
using v1::ModemTransmission;
using Kind = drivers::MicroModemTransmission;

namespace {

constexpr uint32_t kMaxLblTimeoutMs = 60'000;

DriverSpecificResult invalid(const ModemTransmission& r, std::string why) {
  return link::driver_specific_error(DriverSpecificStatus::kInvalidArgument, std::move(why), r);
}

bool is_address(int64_t id) { return id >= 0 && id <= nmea::kMaxAddress; }

}  // namespace

DriverSpecificResult check_request(const ModemTransmission& r, const DriverSpecificExchange::Settings& settings,
                                   std::optional<nmea::ModemGeneration> generation) {
  if (!r.HasExtension(drivers::micromodem_transmission)) {
    return link::driver_specific_error(
        DriverSpecificStatus::kUnimplemented,
        "does not support the driver-specific request " + link::describe_driver_specific(r) +
            " (it takes acomms.drivers.micromodem_transmission: ping, LBL, mini-packet, FDP)",
        r);
  }
  const Kind& ask = r.GetExtension(drivers::micromodem_transmission);
  int64_t own = settings.own_id;
  auto needs_dest = [&](bool broadcast_ok) -> std::string {
    if (!is_address(r.dest()) || r.dest() == own || (!broadcast_ok && r.dest() == 0)) {
      return "transmission.dest " + std::to_string(r.dest()) + " must be another modem's address (" +
             (broadcast_ok ? "0 = everyone, " : "") + "1..127, not this modem's " + std::to_string(own) + ")";
    }
    return "";
  };
  switch (ask.kind()) {
    case Kind::PING:
      if (auto why = needs_dest(false); !why.empty()) return invalid(r, why);
      break;
    case Kind::NARROWBAND_LBL: {
      const auto& lbl = ask.narrowband_lbl();
      if (lbl.reply_frequency_hz_size() < 1 || lbl.reply_frequency_hz_size() > nmea::kTransponders) {
        return invalid(r, "micromodem.narrowband_lbl.reply_frequency_hz has " +
                              std::to_string(lbl.reply_frequency_hz_size()) + " entries: give 1..4 (transponders A..D)");
      }
      for (uint32_t hz : lbl.reply_frequency_hz()) {
        if (hz == 0 || hz > 1'000'000) return invalid(r, "micromodem.narrowband_lbl.reply_frequency_hz " + std::to_string(hz) + " is outside 1..1000000 Hz");
      }
      if (lbl.transmit_frequency_hz() == 0 || lbl.transmit_frequency_hz() > 1'000'000) {
        return invalid(r, "micromodem.narrowband_lbl.transmit_frequency_hz is outside 1..1000000 Hz");
      }
      if (lbl.timeout_ms() == 0 || lbl.timeout_ms() > kMaxLblTimeoutMs) {
        return invalid(r, "micromodem.narrowband_lbl.timeout_ms " + std::to_string(lbl.timeout_ms()) + " is outside 1..60000");
      }
      if (lbl.transmit_ms() > 1000 || lbl.receive_ms() > 1000 || lbl.turnaround_ms() > 10'000) {
        return invalid(r, "micromodem.narrowband_lbl: transmit_ms and receive_ms are at most 1000, turnaround_ms 10000");
      }
      break;
    }
    case Kind::REMUS_LBL: {
      const auto& lbl = ask.remus_lbl();
      if (lbl.group() != 1) return invalid(r, "micromodem.remus_lbl.group must be 1 (the only group)");
      if (lbl.channel() < 1 || lbl.channel() > 4) return invalid(r, "micromodem.remus_lbl.channel " + std::to_string(lbl.channel()) + " is outside 1..4");
      if (lbl.beacons().empty() || lbl.beacons().size() > 4 ||
          lbl.beacons().find_first_not_of(kTransponderLetters) != std::string::npos) {
        return invalid(r, "micromodem.remus_lbl.beacons \"" + lbl.beacons() + "\" must be letters among ABCD");
      }
      if (lbl.timeout_ms() == 0 || lbl.timeout_ms() > kMaxLblTimeoutMs) {
        return invalid(r, "micromodem.remus_lbl.timeout_ms " + std::to_string(lbl.timeout_ms()) + " is outside 1..60000");
      }
      if (lbl.pps_timeout() > 1'000'000) return invalid(r, "micromodem.remus_lbl.pps_timeout is outside 0..1000000");
      break;
    }
    case Kind::MINI_PACKET:
      if (auto why = needs_dest(true); !why.empty()) return invalid(r, why);
      if (!ask.has_mini_packet_value() || ask.mini_packet_value() > nmea::kMaxMiniPacketValue) {
        return invalid(r, "micromodem.mini_packet_value " +
                              (ask.has_mini_packet_value() ? std::to_string(ask.mini_packet_value()) : "(unset)") +
                              " is outside 0..8191 (13 bits)");
      }
      break;
    case Kind::FDP: {
      if (generation && *generation == nmea::ModemGeneration::kMM1) {
        return link::driver_specific_error(DriverSpecificStatus::kFailedPrecondition,
                                           "cannot send FDP: this modem is a Micro-Modem 1, and the flexible data "
                                           "protocol ($CCTDP) needs a Micro-Modem 2",
                                           r);
      }
      if (!generation) {
        return link::driver_specific_error(DriverSpecificStatus::kFailedPrecondition,
                                           "cannot send FDP yet: the modem's revision (MM1 or MM2) is not known", r);
      }
      if (!settings.fdp_configured) {
        return link::driver_specific_error(
            DriverSpecificStatus::kFailedPrecondition,
            "FDP is not configured: add cfg: \"psk.packet.mod_hdr_version,1\" to driver.micromodem (on every modem "
            "of the network: FDP and legacy PSK packets cannot decode each other)",
            r);
      }
      if (auto why = needs_dest(true); !why.empty()) return invalid(r, why);
      const auto& mm1 = settings.mm1_modems;
      if (std::find(mm1.begin(), mm1.end(), r.dest()) != mm1.end()) {
        return link::driver_specific_error(DriverSpecificStatus::kFailedPrecondition,
                                           "cannot send FDP to modem " + std::to_string(r.dest()) +
                                               ": it is a Micro-Modem 1 (driver.micromodem.mm1_modems), which "
                                               "cannot decode the flexible data protocol",
                                           r);
      }
      int limit = nmea::fdp_max_data_bytes(static_cast<int>(ask.fdp_rate()));
      if (limit == 0) return invalid(r, "micromodem.fdp_rate " + std::to_string(ask.fdp_rate()) + " is not an FDP rate (1, 3 or 5)");
      if (ask.fdp_data().empty() || static_cast<int>(ask.fdp_data().size()) > limit - kFdpHeader) {
        return invalid(r, "micromodem.fdp_data has " + std::to_string(ask.fdp_data().size()) +
                              " bytes: FDP rate " + std::to_string(ask.fdp_rate()) + " carries 1.." +
                              std::to_string(limit - kFdpHeader) + " (its " + std::to_string(limit) +
                              "-byte data section less the driver's 2-byte header)");
      }
      break;
    }
    default:
      return invalid(r, "micromodem.kind is required: PING, NARROWBAND_LBL, REMUS_LBL, MINI_PACKET or FDP");
  }
  return {DriverSpecificStatus::kOk, "", r};
}

}  // namespace acomms::drivers::micromodem
