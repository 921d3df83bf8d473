#pragma once
// MM2 flexible data protocol (spec §6, §3.2): one command carries the data
// ($CCTDP), the modem echoes it ($CATDP, error flag first) and a receiver
// prints $CARDP with its frames as ';'-separated triplets
// <crc ok 0/1>;<nbytes>;<hex data>. Data frames are hex (recv.base64data=0,
// what acommsd sets); hex in either case is accepted (§10 quirk 19).

#include <string>
#include <vector>

#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

// The FDP rates and their sizes (§3.2): the data section's most bytes.
int fdp_max_data_bytes(int rate);  // 0 for a rate that is not 1, 3 or 5
inline constexpr int kFdpMiniFrameBytes = 96;
// Air time of an FDP packet at `rate` (§3.2): the mini section plus a full
// data section (an upper bound: FDP air time follows the bytes sent), s.
double fdp_packet_air_s(int rate);

// $CCTDP,<dest>,<rate>,<ack>,<reserved 0>,<hex data>.
struct FdpTransmit {
  int destination = 0;
  int rate = 1;
  bool ack = false;
  std::string data;
  bool operator==(const FdpTransmit&) const = default;
};
Sentence to_sentence(const FdpTransmit& packet);
Result<FdpTransmit> parse_fdp_transmit(const Sentence& sentence);

// $CATDP,<err flag>,<unique id>,<dest>,<rate>,<ack>,<reserved>,<mini-frames>,<data-frames>:
// the echo; err flag != 0 = refused. Only the first five fields are read.
struct FdpEcho {
  bool error = false;
  std::string id;
  int destination = 0;
  int rate = 1;
  bool operator==(const FdpEcho&) const = default;
};
Sentence to_sentence(const FdpEcho& echo, int mini_frames, int data_frames);
Result<FdpEcho> parse_fdp_echo(const Sentence& sentence);

// One frame of a received FDP packet.
struct FdpFrame {
  bool crc_ok = true;
  std::string data;
  bool operator==(const FdpFrame&) const = default;
};

// $CARDP,<src>,<dest>,<rate>,<ack>,<reserved>,<mini-frames>,<data-frames>.
struct FdpReceived {
  int source = 0;
  int destination = 0;
  int rate = 1;
  bool ack = false;
  std::vector<FdpFrame> mini_frames;
  std::vector<FdpFrame> data_frames;
  bool operator==(const FdpReceived&) const = default;
  // Every frame passed its CRC (goby3 drops a packet with a bad one).
  bool intact() const;
  // Mini-frames then data frames, concatenated.
  std::string payload() const;
};
Sentence to_sentence(const FdpReceived& packet);
Result<FdpReceived> parse_fdp_received(const Sentence& sentence);

}  // namespace acomms::micromodem
