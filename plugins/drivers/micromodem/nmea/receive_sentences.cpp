#include "micromodem/nmea/receive_sentences.h"

#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/field_reader.h"
#include "micromodem/nmea/hex.h"

namespace acomms::micromodem {

Sentence to_sentence(const ReceivedData& frame) {
  return Sentence{"CA", "RXD",
                  {std::to_string(frame.source), std::to_string(frame.destination),
                   frame.ack ? "1" : "0", std::to_string(frame.frame), hex_encode(frame.data)}};
}

Result<ReceivedData> parse_received_data(const Sentence& sentence) {
  FieldReader reader(sentence, {"CARXD"});
  reader.require(5);
  ReceivedData frame;
  frame.source = static_cast<int>(reader.integer(1, "SRC", 0, kMaxAddress));
  frame.destination = static_cast<int>(reader.integer(2, "DEST", 0, kMaxAddress));
  frame.ack = reader.flag(3, "ACK");
  frame.frame = static_cast<int>(reader.integer(4, "F#", 1, kMaxFrames));
  frame.data = reader.hex(5, "data");
  return reader.finish(frame);
}

Sentence to_sentence(const Acknowledgement& ack) {
  return Sentence{"CA", "ACK",
                  {std::to_string(ack.source), std::to_string(ack.destination),
                   std::to_string(ack.frame), "1"}};
}

Result<Acknowledgement> parse_acknowledgement(const Sentence& sentence) {
  FieldReader reader(sentence, {"CAACK"});
  reader.require(3);
  Acknowledgement ack;
  ack.source = static_cast<int>(reader.integer(1, "SRC", 0, kMaxAddress));
  ack.destination = static_cast<int>(reader.integer(2, "DEST", 0, kMaxAddress));
  ack.frame = static_cast<int>(reader.integer(3, "F#", 1, kMaxFrames));
  return reader.finish(ack);
}

Sentence to_sentence(const TransactionMessage& message) {
  Sentence sentence{"CA", "MSG", {message.type}};
  append_fields(sentence, message.value);
  return sentence;
}

Result<TransactionMessage> parse_transaction_message(const Sentence& sentence) {
  FieldReader reader(sentence, {"CAMSG"});
  reader.require(1);
  return reader.finish(TransactionMessage{reader.text(1), reader.rest(2)});
}

Sentence to_sentence(const ModemError& error) {
  Sentence sentence{"CA", "ERR", {error.time, error.module, error.number}};
  append_fields(sentence, error.message);
  return sentence;
}

Result<ModemError> parse_modem_error(const Sentence& sentence) {
  FieldReader reader(sentence, {"CAERR"});
  reader.require(2);
  return reader.finish(ModemError{reader.text(1), reader.text(2), reader.text(3), reader.rest(4)});
}

}  // namespace acomms::micromodem
