#pragma once
// What the modem reports about packets it heard and things that went wrong
// (spec §5.6-5.8): a good frame ($CARXD), an acknowledgement ($CAACK),
// transaction messages ($CAMSG: BAD_CRC in place of a frame, PACKET_TIMEOUT)
// and errors ($CAERR: DATA_TIMEOUT, NMEA / "Bad checksum").

#include <string>

#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

// $CARXD,<SRC>,<DEST>,<ACK>,<F#>,<hex data>. Printed for every decoded
// packet, whatever its destination: the driver filters on DEST (§5.6).
struct ReceivedData {
  int source = 0;
  int destination = 0;
  bool ack = false;
  int frame = 1;
  std::string data;  // bytes; empty for a blank frame
  bool operator==(const ReceivedData&) const = default;
};
Sentence to_sentence(const ReceivedData& frame);
Result<ReceivedData> parse_received_data(const Sentence& sentence);

// $CAACK,<SRC>,<DEST>,<F#>,1. SRC acknowledged frame F# sent by DEST.
// MM1 may report third-party ACKs with DEST = us (§10 quirk 8): the driver
// checks SRC too.
struct Acknowledgement {
  int source = 0;       // the modem that acknowledged (the data's destination)
  int destination = 0;  // the modem acknowledged (the data's source)
  int frame = 1;
  bool operator==(const Acknowledgement&) const = default;
};
Sentence to_sentence(const Acknowledgement& ack);
// Field 4 (always 1) is optional: goby3 reads only three fields.
Result<Acknowledgement> parse_acknowledgement(const Sentence& sentence);

// $CAMSG,<type>,<value>: "BAD_CRC" (older firmware "Bad CRC"),
// "PACKET_TIMEOUT", "Transmit aborted", ...
struct TransactionMessage {
  std::string type;
  std::string value;  // fields 2.. joined by ','
  bool operator==(const TransactionMessage&) const = default;
  bool is_bad_crc() const { return type == "BAD_CRC" || type == "Bad CRC"; }
  bool is_packet_timeout() const { return type == "PACKET_TIMEOUT"; }
};
Sentence to_sentence(const TransactionMessage& message);
Result<TransactionMessage> parse_transaction_message(const Sentence& sentence);

// $CAERR,<hhmmss>,<module>,<number>,<message>. Error numbers are not public
// (§13), so they stay text.
struct ModemError {
  std::string time;
  std::string module;   // "DATA_TIMEOUT", "NMEA", ...
  std::string number;   // for DATA_TIMEOUT: the frame
  std::string message;  // fields 4.. joined by ','
  bool operator==(const ModemError&) const = default;
};
Sentence to_sentence(const ModemError& error);
Result<ModemError> parse_modem_error(const Sentence& sentence);

}  // namespace acomms::micromodem
