#pragma once
// Whether a driver-specific request (ping, LBL, mini-packet, FDP) is one
// this modem can send, decided before anything is sent: a bad request is
// refused at once with a status and a message naming the field, instead of
// reaching the modem and failing there (or, worse, being sent wrong).
// Used by DriverSpecificExchange (driver_specific_exchange.h) for
// check_driver_specific and again before each send.
//
// Threads: pure functions (any thread).

#include <optional>
#include <string_view>

#include "acomms/drivers/micromodem_transmission.pb.h"
#include "link/driver_specific.h"
#include "micromodem/driver_specific_exchange.h"
#include "micromodem/nmea/config_sentences.h"

namespace acomms::drivers::micromodem {

// The driver's own header on FDP data (a marker byte, then a sequence
// number): a request's fdp_data may fill the rate's data section less this.
inline constexpr int kFdpHeader = 2;
// LBL transponders, by letter, in the order of the modem's travel times.
inline constexpr std::string_view kTransponderLetters = "ABCD";

// kOk with the request, or why not. `settings`: this modem's id, whether
// FDP is configured, the modems known to be MM1; `generation`: this
// modem's, when known (FDP needs an MM2).
link::DriverSpecificResult check_request(const v1::ModemTransmission& request,
                                         const DriverSpecificExchange::Settings& settings,
                                         std::optional<::acomms::micromodem::ModemGeneration> generation);

}  // namespace acomms::drivers::micromodem
