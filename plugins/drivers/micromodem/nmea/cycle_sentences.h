#pragma once
// The data exchange (spec §5.1-5.6): cycle initialisation ($CCCYC/$CACYC),
// the modem's request for each frame ($CADRQ), the host's frame ($CCTXD)
// and its acceptance ($CATXD), the start and end of any transmission
// ($CATXP/$CATXF) and the start of a reception ($CARXP).
//
// Addresses are 0..127 (0 = broadcast); frames are numbered from 1 on the
// wire (acommsd counts from 0: the driver subtracts 1); rates are 0..6.

#include <string>

#include "micromodem/nmea/config_sentences.h"
#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

inline constexpr int kMaxAddress = 127;
inline constexpr int kMaxRate = 6;
inline constexpr int kMaxFrames = 8;         // rate 5: 8 frames of 256 bytes
inline constexpr int kMaxFrameBytes = 2048;  // generous: the largest frame is 256 bytes

// $CCCYC / $CACYC,<CMD>,<ADR1>,<ADR2>,<Packet Type>,<ACK>,<Nframes>
struct Cycle {
  int command = 0;      // deprecated: send 0 (older code sends 1)
  int source = 0;       // ADR1: our SRC for a local cycle, another modem's to poll it
  int destination = 0;  // ADR2
  int rate = 0;         // Packet Type
  bool ack = false;
  int frames = 1;
  bool operator==(const Cycle&) const = default;
};
Sentence to_sentence(const Cycle& cycle, Talker talker);
Result<Cycle> parse_cycle(const Sentence& sentence);

// $CADRQ,<hhmmss>,<SRC>,<DEST>,<ACK>,<N>,<F#>: supply frame F# (≤ N bytes).
struct DataRequest {
  std::string time;  // modem time of day, hhmmss
  int source = 0;
  int destination = 0;
  bool ack = false;
  int max_bytes = 0;
  int frame = 1;
  bool operator==(const DataRequest&) const = default;
};
Sentence to_sentence(const DataRequest& request);
Result<DataRequest> parse_data_request(const Sentence& sentence);

// $CCTXD,<SRC>,<DEST>,<ACK>,<hex data>. Empty data = no more frames.
struct TransmitData {
  int source = 0;
  int destination = 0;
  bool ack = false;
  std::string data;  // bytes (hex on the wire)
  bool operator==(const TransmitData&) const = default;
};
Sentence to_sentence(const TransmitData& frame);
Result<TransmitData> parse_transmit_data(const Sentence& sentence);

// $CATXD,<SRC>,<DEST>,<ACK>,<nbytes>: the modem accepted a $CCTXD.
struct TransmitDataAccepted {
  int source = 0;
  int destination = 0;
  bool ack = false;
  int bytes = 0;
  bool operator==(const TransmitDataAccepted&) const = default;
};
Sentence to_sentence(const TransmitDataAccepted& accepted);
Result<TransmitDataAccepted> parse_transmit_data_accepted(const Sentence& sentence);

// $CATXP,<nbytes> (transmission starts) and $CATXF,<nbytes> (it ended).
// nbytes is 2 for every mini-packet (§5.4).
struct TransmitStarted {
  int bytes = 0;
  bool operator==(const TransmitStarted&) const = default;
};
struct TransmitFinished {
  int bytes = 0;
  bool operator==(const TransmitFinished&) const = default;
};
Sentence to_sentence(const TransmitStarted& started);
Sentence to_sentence(const TransmitFinished& finished);
Result<TransmitStarted> parse_transmit_started(const Sentence& sentence);
Result<TransmitFinished> parse_transmit_finished(const Sentence& sentence);

// $CARXP,<type>: a packet was detected. 0 FSK, 1 PSK.
struct ReceiveStarted {
  int type = 0;
  bool operator==(const ReceiveStarted&) const = default;
};
Sentence to_sentence(const ReceiveStarted& started);
Result<ReceiveStarted> parse_receive_started(const Sentence& sentence);

}  // namespace acomms::micromodem
