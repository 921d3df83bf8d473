#pragma once
// What one fake Micro-Modem puts in the water: a cycle-init mini-packet, a
// data packet (its frames, each with its own ACK request) or an
// acknowledgement mini-packet. The fake modems exchange these instead of
// sound; each receiver turns one into the NMEA lines a real modem prints
// (spec §8).
//
// Between processes a packet travels as one UDP datagram (UdpWaterBus),
// as text so a person can read it in tcpdump:
//   FAKEMM1 <x> <y> <z> <air_ms> <kind> <rate> <src> <dest> <ack> <nframes>
//           [<acked frames, comma-separated, or ->] [<frame ack>:<hex> ...]
// Datagrams come from anything on the machine: decode() refuses what it
// cannot use.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace acomms::fake_micromodem {

struct Position {
  double x = 0, y = 0, z = 0;  // metres
};
double distance(const Position& a, const Position& b);

// The extras (fake_micromodem_extras.cpp): a ping and its reply (mini-
// packets), a user mini-packet (its 13 bits as one 2-byte frame) and an
// MM2 FDP packet (its bytes as one frame; frames_wanted carries the
// sender's psk.packet.mod_hdr_version, which receivers must share).
enum class PacketKind { kCycleInit, kData, kAck, kPing, kPingReply, kMiniPacket, kFdp };

struct DataFrame {
  bool ack = false;
  std::string bytes;  // may be empty: a blank frame is still carried (§5.3)
};

struct AcousticPacket {
  PacketKind kind = PacketKind::kData;
  int rate = 0;
  int source = 0;
  int destination = 0;
  bool ack = false;         // cycle-init: the cycle's ACK flag
  int frames_wanted = 0;    // cycle-init: Nframes
  std::vector<DataFrame> frames;    // data
  std::vector<int> acked_frames;    // ack: frame numbers from 1
  bool is_mini() const { return kind != PacketKind::kData && kind != PacketKind::kFdp; }
  // $CARXP type and the statistics' packet type: data packets are FSK at
  // rate 0, PSK above; mini-packets FSK unless NVRAM MOD=1, except that an
  // ACK answers a PSK packet with a PSK mini (§5.7).
  bool is_psk(bool psk_minis) const {
    if (kind == PacketKind::kData) return rate > 0;
    if (kind == PacketKind::kFdp) return true;
    return psk_minis || (kind == PacketKind::kAck && rate > 0);
  }
};

struct WaterDatagram {
  Position from;
  double air_seconds = 0;
  AcousticPacket packet;
};

std::string encode(const WaterDatagram& datagram);
std::optional<WaterDatagram> decode_datagram(std::string_view text, std::string* error);

}  // namespace acomms::fake_micromodem
