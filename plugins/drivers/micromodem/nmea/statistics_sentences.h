#pragma once
// Per-packet statistics (spec §5.5, §5.6): $CACST after every reception
// (the driver's "packet complete" signal, and its link quality) and $CAXST
// after every transmission (the transmit result).
//
// Layouts depend on the firmware (§10 quirk 15):
//   $CACST v0 (old MM1): no version field, 29 fields; v6 (MM1 >= 0.93.0.52):
//   30 fields; v7/v8 (MM2): 34 fields, the last four about FDP.
//   $CAXST v0: no version field (field 1 is the date); v6 (MM1): 16 fields;
//   v7 (MM2): 17, the last the carrier actually used.
// Parsing goes by position with bounds checks; a short sentence is not
// fatal (fields past its end keep their defaults, and field_count says how
// many were there), but a field that is present and not a number is.

#include <cstddef>
#include <string>

#include "micromodem/nmea/result.h"
#include "micromodem/nmea/sentence.h"

namespace acomms::micromodem {

// Packet types in both statistics (G-PROTO PacketType).
enum PacketTypeCode {
  kPacketUnknown = -1,
  kPacketFsk = 1,
  kPacketFskMini = 2,
  kPacketPsk = 3,
  kPacketPskMini = 4,
  kPacketFdp = 5,
};

// $CACST. Field numbers in the comments are those of the versioned layout.
struct ReceiveStatistics {
  int version = 6;             // 1: 0 (no field), 6 (MM1), 7 or 8 (MM2)
  int mode = 0;                // 2: 0 good, 1 bad CRC, 2 packet timeout
  std::string time_of_arrival; // 3: yyyymmddHHMMSS.ffff (v0: hhmmss.ffff), modem clock
  int clock_status = 0;        // 4
  int mf_peak = 0;             // 5
  int mf_power = 0;            // 6: dB
  int mf_ratio = 0;            // 7
  int spl = 0;                 // 8: dB re 1 uPa, the signal level
  int analog_gain = 0;         // 9
  int shift_previous = 0, shift_current = 0, shift_detect = 0, shift_baseband = 0;  // 10-13
  int rate = 0;                // 14
  int source = 0;              // 15
  int destination = 0;         // 16
  int psk_error = 0;           // 17
  int packet_type = kPacketUnknown;  // 18
  int frames = 0;              // 19
  int bad_frames = 0;          // 20
  double rss = 0;              // 21: dB
  double snr_in = 0;           // 22: dB
  double snr_out = 0;          // 23: dB, after the equalizer
  double snr_symbol = 0;       // 24: dB
  double mse = 0;              // 25: dB
  int dqf = 0;                 // 26: FSK data quality 0..255
  double doppler = 0;          // 27: m/s
  double noise = 0;            // 28: dB
  int carrier = 0;             // 29: Hz
  int bandwidth = 0;           // 30: Hz
  // 31-34, MM2 (v7/v8) only: written when version >= 7; -1 = not applicable.
  int sequence = -1, data_rate = -1, data_frames = -1, bad_data_frames = -1;
  size_t field_count = 0;      // fields the parsed line had (not compared)

  bool operator==(const ReceiveStatistics& other) const;
};
Sentence to_sentence(const ReceiveStatistics& statistics);
Result<ReceiveStatistics> parse_receive_statistics(const Sentence& sentence);

// $CAXST.
struct TransmitStatistics {
  int version = 6;         // 1: 0 (no field), 6 (MM1), 7 (MM2)
  std::string date;        // 2: yyyymmdd
  std::string time;        // 3: hhmmss.ffff
  int clock_status = 0;    // 4
  int mode = 0;            // 5: 0 sent, 1 FETs hot, 2 EXTSYNC timeout, 3 inhibited, 4 data timeout
  int probe_length = 0;    // 6
  int bandwidth = 0;       // 7
  int carrier = 0;         // 8
  int rate = 0;            // 9
  int source = 0;          // 10
  int destination = 0;     // 11
  bool ack = false;        // 12
  int frames_expected = 0; // 13
  int frames_sent = 0;     // 14
  int packet_type = kPacketUnknown;  // 15
  int bytes = 0;           // 16
  int carrier_used = 0;    // 17, v7 only
  size_t field_count = 0;  // fields the parsed line had (not compared)

  bool operator==(const TransmitStatistics& other) const;
};
Sentence to_sentence(const TransmitStatistics& statistics);
Result<TransmitStatistics> parse_transmit_statistics(const Sentence& sentence);

}  // namespace acomms::micromodem
