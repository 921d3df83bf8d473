// libFuzzer target: one line from a Micro-Modem's serial port (or a host's,
// at the fake modem) through parse_sentence() and every typed parser. Bad
// input must be refused with a reason, never crash or throw; what is
// accepted must survive serialize() and parse again unchanged, so what the
// driver logs or re-sends is what it read.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/fdp_sentences.h"
#include "micromodem/nmea/mini_packet_sentences.h"
#include "micromodem/nmea/ranging_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"
#include "micromodem/nmea/time_sentences.h"

namespace {

using namespace acomms::micromodem;

// Typed value → Sentence → line → Sentence → typed value: must be equal.
template <typename T, typename Parse, typename Write>
void typed_round_trip(const Sentence& sentence, Parse parse, Write write) {
  Result<T> typed = parse(sentence);
  if (!typed) {
    if (typed.error().text.empty()) __builtin_trap();
    return;
  }
  Result<Sentence> again = parse_sentence(serialize(write(*typed)));
  if (!again) __builtin_trap();
  Result<T> retyped = parse(*again);
  if (!retyped || !(*retyped == *typed)) __builtin_trap();
}

void check_typed(const Sentence& s) {
  Talker talker = s.talker == "CC" ? Talker::kHost : Talker::kModem;
  auto with_talker = [talker](const auto& v) { return to_sentence(v, talker); };
  auto plain = [](const auto& v) { return to_sentence(v); };
  typed_round_trip<ConfigParameter>(s, parse_config_parameter, with_talker);
  typed_round_trip<ConfigQuery>(s, parse_config_query, plain);
  typed_round_trip<ClockTime>(s, parse_clock_time, with_talker);
  typed_round_trip<Revision>(s, parse_revision, plain);
  typed_round_trip<TimeSet>(s, parse_time_set, plain);
  typed_round_trip<TimeSetReply>(s, parse_time_set_reply, plain);
  typed_round_trip<Cycle>(s, parse_cycle, with_talker);
  typed_round_trip<DataRequest>(s, parse_data_request, plain);
  typed_round_trip<TransmitData>(s, parse_transmit_data, plain);
  typed_round_trip<TransmitDataAccepted>(s, parse_transmit_data_accepted, plain);
  typed_round_trip<TransmitStarted>(s, parse_transmit_started, plain);
  typed_round_trip<TransmitFinished>(s, parse_transmit_finished, plain);
  typed_round_trip<ReceiveStarted>(s, parse_receive_started, plain);
  typed_round_trip<ReceivedData>(s, parse_received_data, plain);
  typed_round_trip<Acknowledgement>(s, parse_acknowledgement, plain);
  typed_round_trip<TransactionMessage>(s, parse_transaction_message, plain);
  typed_round_trip<ModemError>(s, parse_modem_error, plain);
  typed_round_trip<ReceiveStatistics>(s, parse_receive_statistics, plain);
  typed_round_trip<TransmitStatistics>(s, parse_transmit_statistics, plain);
  // Ping, LBL, mini-packets, FDP (the driver's extras).
  const char* ping_type = s.type == "MPA" ? "MPA" : "MPC";
  typed_round_trip<Ping>(s, parse_ping, [&](const Ping& v) { return to_sentence(v, talker, ping_type); });
  typed_round_trip<PingReply>(s, parse_ping_reply, plain);
  typed_round_trip<NarrowbandInterrogation>(s, parse_narrowband_interrogation, plain);
  typed_round_trip<RemusInterrogation>(s, parse_remus_interrogation, plain);
  typed_round_trip<TravelTimes>(s, parse_travel_times, plain);
  const char* mini_type = s.type == "MUA" ? "MUA" : "MUC";
  typed_round_trip<MiniPacket>(s, parse_mini_packet, [&](const MiniPacket& v) { return to_sentence(v, talker, mini_type); });
  typed_round_trip<FdpTransmit>(s, parse_fdp_transmit, plain);
  typed_round_trip<FdpEcho>(s, parse_fdp_echo, [](const FdpEcho& v) { return to_sentence(v, 0, 0); });
  typed_round_trip<FdpReceived>(s, parse_fdp_received, plain);
  if (Result<FdpReceived> fdp = parse_fdp_received(s)) {
    // The payload is the frames' bytes, in order, whatever their CRCs.
    size_t bytes = 0;
    for (const auto& f : fdp->mini_frames) bytes += f.data.size();
    for (const auto& f : fdp->data_frames) bytes += f.data.size();
    if (fdp->payload().size() != bytes) __builtin_trap();
  }
  if (s.is("CAREV")) {
    Result<ModemGeneration> generation = modem_generation(s.field(3));
    if (!generation && generation.error().text.empty()) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view line(reinterpret_cast<const char*>(data), size);
  for (ChecksumRule rule : {ChecksumRule::kRequired, ChecksumRule::kOptional}) {
    Result<Sentence> sentence = parse_sentence(line, rule);
    if (!sentence) {
      if (sentence.error().text.empty()) __builtin_trap();  // every refusal says why
      continue;
    }
    // The canonical form parses back to the same sentence, checksum verified.
    std::string canonical = serialize(*sentence);
    Result<Sentence> again = parse_sentence(canonical);
    if (!again || again->checksum != ChecksumState::kVerified) __builtin_trap();
    Sentence expected = *sentence;
    expected.checksum = ChecksumState::kVerified;
    if (!(*again == expected) || serialize(*again) != canonical) __builtin_trap();
    check_typed(*sentence);
  }
  return 0;
}
