#pragma once
// Turns the modem's receive reports into one DATA transmission per packet.
//
// The problem: a packet reaches the host as several sentences (spec §5.6,
// §8): `$CARXP` when it is detected, `$CACYC` from a cycle-init or a PSK
// header, one `$CARXD` per good frame or `$CAMSG,BAD_CRC` in its place, and
// last `$CACST`. Rate 0 gives two `$CACST` (cycle-init, then data) and a
// PSK poller sees a second `$CACYC` (§10 quirk 7).
// The decision: a record opens on `$CARXP` (or the first sentence of a
// packet without one), collects frames in frame order, and closes on
// `$CACST`; a record with at least one non-empty good frame is delivered,
// others (cycle-inits, ACK mini-packets, timeouts) only close. A new
// `$CARXP` closes an unfinished record (CST=0 or a lost `$CACST`) the same
// way. DATA for every destination is delivered (driver.h: the queues
// filter); empty frames are skipped (blank frames, §5.3) and bad frames
// counted. `time` is the host's clock at delivery (the modem's clock may be
// unset, §10 quirk 14); the statistics travel along as link figures.
//
// Packets sent and not received (issue 32), as the spec shows them (§8.6),
// are told through set_on_failed, each at most once:
// - detected and damaged: no good frame and a $CACST with mode 1 (every
//   frame `$CAMSG,BAD_CRC`, or a PSK header that did not decode: mode 1
//   with no frame at all), told with the $CACST's figures;
// - announced and never came: a $CACST with mode 2 (after
//   `$CAMSG,PACKET_TIMEOUT`), told without figures (mode 2's mean nothing).
// Whose packet it was comes, in this order, from the packet's own $CACYC
// (a PSK header), from the cycle-init mini-packet heard just before it
// (a rate-0 packet has no header, §5.1: its $CACYC comes with the
// cycle-init's own $CACST, one record earlier), or from our poll awaiting
// its answer. A damaged packet with none of these is counted
// (unattributed) and not told: the $CACST's source and destination
// (fields 15, 16) are firm for good packets, but the spec does not say
// what a modem writes there for one it could not decode, so they are not
// trusted. Also unsettled by the spec: whether a third modem that only
// overheard a cycle-init prints PACKET_TIMEOUT when the data never comes
// (when it does, it is told; when it does not, the announcement is
// forgotten at the next packet, a damaged mini-packet included, or after
// kAnnouncementLife_s).
//
// Core thread only.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/modem_transmission.pb.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/receive_sentences.h"
#include "micromodem/nmea/statistics_sentences.h"

namespace acomms::drivers::micromodem {

// "snr_in_db=12.5 snr_out_db=9.1 ..." from a $CACST, for link_quality.
std::string describe_link_quality(const ::acomms::micromodem::ReceiveStatistics& statistics);
// The $CACST fields as ReceptionFigures (PSK-only fields only for PSK packets).
v1::ReceptionFigures figures_of(const ::acomms::micromodem::ReceiveStatistics& statistics);

class Reception {
 public:
  struct Counters {
    uint64_t packets = 0;         // records closed by $CACST
    uint64_t data_delivered = 0;  // DATA transmissions delivered
    uint64_t frames = 0;          // good non-empty frames delivered
    uint64_t bad_frames = 0;      // $CAMSG,BAD_CRC
    uint64_t packet_timeouts = 0; // $CAMSG,PACKET_TIMEOUT
    uint64_t lost_told = 0;       // packets told lost (on_failed): bad frames, or awaited and never came
    uint64_t unattributed = 0;    // damaged packets whose sender nothing named: not told
  };
  using Deliver = std::function<void(v1::ModemTransmission)>;

  // A cycle-init is taken to announce a packet for kAnnouncementLife_s:
  // the data follows it within the modem's cycle timeout (CTO, 10 s by
  // default, §9), and rate 0's air time.
  static constexpr double kAnnouncementLife_s = 30;

  // `own_id`: this modem's SRC (a cycle-init naming it as ADR1 is a poll
  // of us: we send, nothing is awaited).
  Reception(int32_t own_id, std::function<double()> now_seconds, Deliver deliver);

  void on_receive_started();                                          // $CARXP
  void on_cycle(const ::acomms::micromodem::Cycle& cycle);            // $CACYC from the water
  void on_data(const ::acomms::micromodem::ReceivedData& frame);      // $CARXD
  void on_message(const ::acomms::micromodem::TransactionMessage& m); // $CAMSG
  void on_statistics(const ::acomms::micromodem::ReceiveStatistics& statistics);  // $CACST
  // Drops the record in progress (a reboot).
  void reset() {
    record_.reset();
    expected_.reset();
    announced_.reset();
  }
  // A packet detected and damaged (above), its sender known: told here
  // (no frames; rate, src, dest from its cycle; the $CACST figures), so the
  // event log counts a packet heard and lost
  // (link::DriverCallbacks::on_reception_failed). Unset: dropped.
  void set_on_failed(Deliver on_failed) { on_failed_ = std::move(on_failed); }
  // Our poll of `src` went out (a third-party $CCCYC): its packet is
  // awaited at `rate`. If the modem reports that it never came
  // ($CAMSG,PACKET_TIMEOUT and a $CACST with mode 2, spec §8.6), that is a
  // packet sent and not received, told through on_failed (no figures: mode
  // 2's are meaningless). A cycle-init heard from the water whose packet
  // never came counts the same, from the cycle's source. Each mode-2
  // $CACST tells at most one loss, and a packet told lost for its bad
  // frames (mode 1) is not told again: no packet counts twice.
  void expect(int32_t src, int32_t dest, int32_t rate) { expected_ = Expected{src, dest, rate}; }

  const Counters& counters() const { return counters_; }

 private:
  struct Record {
    std::optional<::acomms::micromodem::Cycle> cycle;
    std::optional<::acomms::micromodem::ReceivedData> first_frame;
    std::vector<std::string> frames;  // good, non-empty, in frame order
    bool ack_requested = false;
    int bad_frames = 0;  // $CAMSG,BAD_CRC in this packet
  };
  Record& open();
  void close(const ::acomms::micromodem::ReceiveStatistics* statistics);
  struct Expected {
    int32_t src = -1, dest = -1, rate = 0;
  };
  void tell_lost(const Expected& from, const ::acomms::micromodem::ReceiveStatistics* figures);
  // Whose the packet closing now was, when it has no $CACYC of its own:
  // the cycle-init just heard, else our poll; for a timeout (mode 2) our
  // poll first.
  std::optional<Expected> announcer(bool timeout);
  // A closed record that was a cycle-init mini-packet from the water (not
  // a poll of us): the next packet is its sender's.
  void note_cycle_init(const Record& record, const ::acomms::micromodem::ReceiveStatistics& statistics);

  int32_t own_id_;
  std::function<double()> now_seconds_;
  Deliver deliver_;
  Deliver on_failed_;
  std::optional<Expected> expected_;  // our poll's answer, awaited
  struct Announced {
    Expected packet;
    double heard_s = 0;
  };
  std::optional<Announced> announced_;  // a cycle-init's packet, awaited
  std::optional<Record> record_;
  Counters counters_;
};

}  // namespace acomms::drivers::micromodem
