#include "micromodem/nmea/cycle_sentences.h"

#include "micromodem/nmea/field_reader.h"
#include "micromodem/nmea/hex.h"

namespace acomms::micromodem {
namespace {

std::string number(int64_t value) { return std::to_string(value); }
std::string flag(bool value) { return value ? "1" : "0"; }

}  // namespace

Sentence to_sentence(const Cycle& cycle, Talker talker) {
  return Sentence{talker == Talker::kHost ? "CC" : "CA", "CYC",
                  {number(cycle.command), number(cycle.source), number(cycle.destination),
                   number(cycle.rate), flag(cycle.ack), number(cycle.frames)}};
}

Result<Cycle> parse_cycle(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCCYC", "CACYC"});
  reader.require(6);
  Cycle cycle;
  cycle.command = static_cast<int>(reader.integer(1, "CMD", 0, 1));
  cycle.source = static_cast<int>(reader.integer(2, "ADR1", 0, kMaxAddress));
  cycle.destination = static_cast<int>(reader.integer(3, "ADR2", 0, kMaxAddress));
  cycle.rate = static_cast<int>(reader.integer(4, "Packet Type", 0, kMaxRate));
  cycle.ack = reader.flag(5, "ACK");
  cycle.frames = static_cast<int>(reader.integer(6, "Nframes", 0, kMaxFrames));
  return reader.finish(cycle);
}

Sentence to_sentence(const DataRequest& request) {
  return Sentence{"CA", "DRQ",
                  {request.time, number(request.source), number(request.destination),
                   flag(request.ack), number(request.max_bytes), number(request.frame)}};
}

Result<DataRequest> parse_data_request(const Sentence& sentence) {
  FieldReader reader(sentence, {"CADRQ"});
  reader.require(6);
  DataRequest request;
  request.time = reader.text(1);
  request.source = static_cast<int>(reader.integer(2, "SRC", 0, kMaxAddress));
  request.destination = static_cast<int>(reader.integer(3, "DEST", 0, kMaxAddress));
  request.ack = reader.flag(4, "ACK");
  request.max_bytes = static_cast<int>(reader.integer(5, "N", 0, kMaxFrameBytes));
  request.frame = static_cast<int>(reader.integer(6, "F#", 1, kMaxFrames));
  return reader.finish(request);
}

Sentence to_sentence(const TransmitData& frame) {
  return Sentence{"CC", "TXD",
                  {number(frame.source), number(frame.destination), flag(frame.ack),
                   hex_encode(frame.data)}};
}

Result<TransmitData> parse_transmit_data(const Sentence& sentence) {
  FieldReader reader(sentence, {"CCTXD"});
  reader.require(4);
  TransmitData frame;
  frame.source = static_cast<int>(reader.integer(1, "SRC", 0, kMaxAddress));
  frame.destination = static_cast<int>(reader.integer(2, "DEST", 0, kMaxAddress));
  frame.ack = reader.flag(3, "ACK");
  frame.data = reader.hex(4, "data");
  return reader.finish(frame);
}

Sentence to_sentence(const TransmitDataAccepted& accepted) {
  return Sentence{"CA", "TXD",
                  {number(accepted.source), number(accepted.destination), flag(accepted.ack),
                   number(accepted.bytes)}};
}

Result<TransmitDataAccepted> parse_transmit_data_accepted(const Sentence& sentence) {
  FieldReader reader(sentence, {"CATXD"});
  reader.require(4);
  TransmitDataAccepted accepted;
  accepted.source = static_cast<int>(reader.integer(1, "SRC", 0, kMaxAddress));
  accepted.destination = static_cast<int>(reader.integer(2, "DEST", 0, kMaxAddress));
  accepted.ack = reader.flag(3, "ACK");
  accepted.bytes = static_cast<int>(reader.integer(4, "nbytes", 0, kMaxFrameBytes));
  return reader.finish(accepted);
}

Sentence to_sentence(const TransmitStarted& started) {
  return Sentence{"CA", "TXP", {number(started.bytes)}};
}

Sentence to_sentence(const TransmitFinished& finished) {
  return Sentence{"CA", "TXF", {number(finished.bytes)}};
}

// FDP packets report their size here too (up to 2 KiB data + 96 B mini).
constexpr int64_t kMaxPacketBytes = 4096;

Result<TransmitStarted> parse_transmit_started(const Sentence& sentence) {
  FieldReader reader(sentence, {"CATXP"});
  reader.require(1);
  TransmitStarted started{static_cast<int>(reader.integer(1, "nbytes", 0, kMaxPacketBytes))};
  return reader.finish(started);
}

Result<TransmitFinished> parse_transmit_finished(const Sentence& sentence) {
  FieldReader reader(sentence, {"CATXF"});
  reader.require(1);
  TransmitFinished finished{static_cast<int>(reader.integer(1, "nbytes", 0, kMaxPacketBytes))};
  return reader.finish(finished);
}

Sentence to_sentence(const ReceiveStarted& started) {
  return Sentence{"CA", "RXP", {number(started.type)}};
}

Result<ReceiveStarted> parse_receive_started(const Sentence& sentence) {
  FieldReader reader(sentence, {"CARXP"});
  reader.require(1);
  ReceiveStarted started{static_cast<int>(reader.integer(1, "type", 0, 1))};
  return reader.finish(started);
}

}  // namespace acomms::micromodem
