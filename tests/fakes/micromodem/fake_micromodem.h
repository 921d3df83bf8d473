#pragma once
// A fake WHOI Micro-Modem (MM1 or MM2) that speaks the NMEA sentences of
// /work/shared/spec/micromodem-nmea.md on a byte stream, for driver tests
// without hardware. It plays the modem's side of spec §8's sequences:
// start-up ($CAREV, $CCCFG/$CCCFQ, $CCCLK), local cycles ($CCCYC →
// $CADRQ → $CCTXD → transmission), third-party polls, reception
// ($CARXP/$CACYC/$CARXD/$CAMSG/$CACST), acknowledgements sent by the
// modem itself ($CAACK at the sender), and reboots.
//
// Decisions where the spec is silent are commented where they are made
// and listed in README.md. The fake is deliberately plain: one modem, one
// exchange at a time. The extras (two-way ping, narrowband and REMUS LBL
// against the water's transponders, user mini-packets, MM2 FDP) are in
// fake_micromodem_extras.cpp.
//
// Threading: everything runs on the scheduler's thread (the fake is a
// single-threaded object like the driver it tests). from_host() and the
// output callback are called on it too.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "acoustic_packet.h"
#include "fault_injector.h"
#include "micromodem/nmea/cycle_sentences.h"
#include "micromodem/nmea/line_framer.h"
#include "micromodem/nmea/sentence.h"
#include "modem_timing.h"
#include "nvram.h"
#include "water.h"

namespace acomms::fake_micromodem {

struct FakeModemConfig {
  int address = 1;  // NVRAM SRC at first power-on
  Generation generation = Generation::kMM2;
  Position position;
  ModemTiming timing;
  double frame_error_probability = 0;  // each received frame: $CAMSG,BAD_CRC instead of $CARXD
  // Each received PSK data packet: its header does not decode (§8.6): no
  // $CACYC, no frame, a $CACST with mode 1 and PSK error 1.
  double header_error_probability = 0;
  uint32_t seed = 1;
  // MM1 firmware bug (§10 quirk 8): acknowledgements between two other
  // modems are reported as $CAACK with DEST = this modem.
  bool third_party_ack_bug = false;
};

class FakeMicroModem final : public WaterListener {
 public:
  struct Counters {
    uint64_t host_lines = 0;     // sentences accepted from the host
    uint64_t host_refused = 0;   // lines refused (bad checksum, garbage, unknown)
    uint64_t transmissions = 0;  // packets put in the water
    uint64_t receptions = 0;     // packets decoded (any destination)
    uint64_t collisions = 0;     // arrivals lost to half-duplex or overlap
  };

  FakeMicroModem(Water& water, FakeModemConfig config);
  ~FakeMicroModem() override;
  FakeMicroModem(const FakeMicroModem&) = delete;
  FakeMicroModem& operator=(const FakeMicroModem&) = delete;

  // Where the modem's output goes (the port): bytes exactly as written.
  void set_output(std::function<void(std::string_view)> output) { output_ = std::move(output); }
  // Boots: $CAREV,INIT, then the AUV (and on MM2 COPROC) revision lines.
  void power_on();
  // Bytes from the host, in any chunks.
  void from_host(std::string_view bytes);

  // Faults (spec §8.6, §10).
  FaultInjector& faults() { return faults_; }
  void reboot();                        // as after a watchdog: "$CAREV,...,INIT" again
  // Reboots halfway through the next data packet this modem transmits
  // (what reaches the water is decided when a packet starts: it arrives).
  void reboot_mid_next_transmission() { reboot_mid_transmission_ = true; }
  void write_raw(std::string_view bytes);  // straight to the port (noise, overlong lines)
  void report_error(const std::string& module, const std::string& number, const std::string& message);

  void move_to(Position position) { config_.position = position; }
  void set_frame_error_probability(double p) { config_.frame_error_probability = p; }
  Position position() const override { return config_.position; }
  void on_arrival(const AcousticPacket& packet, Duration air, double range_m) override;

  int address() const { return nvram_.integer("SRC"); }
  const Nvram& nvram() const { return nvram_; }
  const Counters& counters() const { return counters_; }
  std::string revision() const;

 private:
  struct Exchange;   // a cycle this modem transmits in (local or polled)
  struct Reception;  // a packet being received

  // fake_micromodem.cpp: output, start-up, commands.
  void emit(const micromodem::Sentence& sentence);
  void later(Duration delay, std::function<void()> task);
  void handle_host_line(const std::string& line);
  void handle_command(const micromodem::Sentence& sentence);
  void handle_config(const micromodem::Sentence& sentence);
  void handle_config_query(const micromodem::Sentence& sentence);
  void handle_clock(const micromodem::Sentence& sentence);
  void print_revision(bool boot);
  void schedule_revision();
  std::string modem_time_hhmmss() const;
  std::string modem_date_time(int decimals) const;  // yyyymmddHHMMSS.ffff
  Duration modem_time_since_epoch() const;

  // fake_micromodem_cycle.cpp: transmit side.
  void handle_cycle(const micromodem::Sentence& sentence);
  void handle_transmit_data(const micromodem::Sentence& sentence);
  void start_exchange(const micromodem::Cycle& cycle, bool polled);
  void request_frame();
  void accept_frame(const micromodem::TransmitData& frame);
  void data_timeout(uint64_t exchange_id, int frame);
  void transmit_exchange();
  void transmit(const AcousticPacket& packet, Duration air, std::function<void()> after);
  void transmit_statistics(const AcousticPacket& packet, int mode, int frames_sent, int bytes);
  void poll_timeout(uint64_t poll_id);

  // fake_micromodem_extras.cpp: ping, LBL, mini-packets, FDP.
  // True when `sentence` was one of theirs.
  bool handle_extra_command(const micromodem::Sentence& sentence);
  void handle_ping(const micromodem::Sentence& sentence);
  void handle_mini_packet(const micromodem::Sentence& sentence);
  void handle_fdp(const micromodem::Sentence& sentence);
  void handle_lbl(const micromodem::Sentence& sentence);
  void receive_extra(const AcousticPacket& packet, bool damaged);
  bool busy() const;

  // fake_micromodem_reception.cpp: receive side.
  void finish_reception();
  void receive_cycle_init(const AcousticPacket& packet);
  void receive_data(const AcousticPacket& packet, bool damaged);
  void receive_ack(const AcousticPacket& packet);
  void receive_statistics(const AcousticPacket& packet, int mode, int bad_frames, bool header_lost = false);
  void send_ack(const AcousticPacket& data, std::vector<int> frames);
  bool transmitting() const;

  Water& water_;
  FakeModemConfig config_;
  Nvram nvram_;
  FaultInjector faults_;
  micromodem::LineFramer host_framer_;
  std::function<void(std::string_view)> output_;
  std::mt19937 random_;
  Counters counters_;

  // Everything scheduled belongs to one "life" of the modem: a reboot
  // starts a new one and tasks of the old one do nothing.
  // Tasks hold a weak_ptr to it, so none outlives the modem either.
  std::shared_ptr<uint64_t> life_ = std::make_shared<uint64_t>(0);
  bool booted_ = false;
  core::Clock::time_point boot_time_{};
  std::optional<Duration> clock_offset_;  // set by $CCCLK; unset after a reboot

  std::unique_ptr<Exchange> exchange_;
  uint64_t next_exchange_id_ = 1;
  core::Clock::time_point transmitting_until_{};
  std::unique_ptr<Reception> reception_;
  uint64_t next_reception_id_ = 1;
  double reception_range_m_ = 0;  // of the packet whose $CACST is printed
  // $CCTXD lines that came with no $CADRQ outstanding (§5.3).
  std::vector<micromodem::TransmitData> buffered_frames_;
  // A third-party poll this modem sent, waiting for the polled packet.
  std::optional<std::pair<uint64_t, int>> awaited_poll_;  // (id, polled address)
  uint64_t next_poll_id_ = 1;
  // The modem a $CCMPC of ours pinged, until its reply is printed.
  std::optional<int> awaited_ping_;
  core::Clock::time_point listening_until_{};  // an LBL interrogation's Timeout
  uint64_t next_fdp_id_ = 1;
  bool reboot_mid_transmission_ = false;
};

}  // namespace acomms::fake_micromodem
