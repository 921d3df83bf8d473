// The exchange of a driver-specific request, once checked
// (driver_specific_request.cpp): its command, the waits bounded by the spec's
// timeouts and the caller's deadline, and the answers that end it. Every
// callback from the command queue or the scheduler names the exchange it
// belongs to (Current::id), so a late one from a finished exchange is
// ignored instead of ending the next.
#include "micromodem/driver_specific_exchange.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "core/core_thread.h"
#include "micromodem/driver_specific_request.h"
#include "micromodem/nmea/cycle_sentences.h"

namespace acomms::drivers::micromodem {

namespace nmea = ::acomms::micromodem;
using link::DriverSpecificResult;
using link::DriverSpecificStatus;
using nmea::Sentence;
using v1::ModemTransmission;
using Kind = drivers::MicroModemTransmission;

namespace {

constexpr uint8_t kFdpData = 0xFD;  // first byte of FDP data from this driver
constexpr uint8_t kFdpPadded = 0xFE;  // the same, one zero byte of padding at the end
constexpr uint8_t kFdpAck = 0xFA;   // first byte of its software acknowledgement

using std::chrono::milliseconds;
using Duration = std::chrono::system_clock::duration;

Duration seconds(double s) {
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s));
}

constexpr double kMiniAir = 0.7;     // §3.1: 0.5-0.7 s
constexpr double kTurnaround = 0.5;  // §9: ~0.5-1 s
constexpr double kSlack = 2;         // serial time and decoding (as the data cycle's margin)

}  // namespace

DriverSpecificExchange::DriverSpecificExchange(core::Scheduler& scheduler, CommandQueue& commands,
                                               Settings settings, Hooks hooks)
    : scheduler_(scheduler), commands_(commands), settings_(settings), hooks_(std::move(hooks)) {}

DriverSpecificExchange::~DriverSpecificExchange() { abort("the driver stopped"); }

Duration DriverSpecificExchange::scaled(Duration modem_time) const {
  return std::chrono::duration_cast<Duration>(modem_time / settings_.time_scale);
}

DriverSpecificResult DriverSpecificExchange::check(const ModemTransmission& request) const {
  return check_request(request, settings_, hooks_.generation ? hooks_.generation() : std::nullopt);
}

void DriverSpecificExchange::send(const ModemTransmission& request, double deadline_s, link::DriverSpecificDone done) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (current_) {
    return done(link::driver_specific_error(DriverSpecificStatus::kAborted,
                                            "busy: another driver-specific exchange is in progress", request));
  }
  DriverSpecificResult checked = check(request);
  if (checked.status != DriverSpecificStatus::kOk) return done(std::move(checked));
  // emplace(Current()), not emplace(): clang decides Current (nested, with
  // default member initializers) is not default-constructible (see reception.cpp).
  current_.emplace(Current());
  current_->request = request;
  current_->ask = request.GetExtension(drivers::micromodem_transmission);
  current_->done = std::move(done);
  current_->deadline_s = deadline_s;
  current_->id = next_id_++;
  ++counters_.sent;
  const int own = settings_.own_id;
  const int dest = request.dest();
  double max_travel = settings_.max_range_m / settings_.sound_speed;
  switch (current_->ask.kind()) {
    case Kind::PING:
      // §7.1: nothing is printed without a reply: 2 × max range / c + 3 s.
      return send_command(nmea::to_sentence(nmea::Ping{own, dest}, nmea::Talker::kHost),
                          [](const Sentence& s) { return s.is("CAMPC"); }, Phase::kAwaitReply,
                          seconds(2 * max_travel + 3));
    case Kind::NARROWBAND_LBL:
    case Kind::REMUS_LBL:
      return start_lbl();
    case Kind::MINI_PACKET:
      return send_command(nmea::to_sentence(nmea::MiniPacket{own, dest, current_->ask.mini_packet_value()},
                                            nmea::Talker::kHost),
                          [](const Sentence& s) { return s.is("CAMUC"); }, Phase::kAwaitTransmitted,
                          seconds(kMiniAir + kSlack));
    case Kind::FDP: {
      current_->fdp_sequence = next_fdp_sequence_++;
      // MM2 builds before 2.0.35490 mishandle an odd byte count (§6): pad,
      // and say so in the marker so the receiver strips it.
      bool pad = current_->ask.fdp_data().size() % 2 != 0;
      std::string data;
      data += static_cast<char>(pad ? kFdpPadded : kFdpData);
      data += static_cast<char>(current_->fdp_sequence);
      data += current_->ask.fdp_data();
      if (pad) data += '\0';
      int rate = static_cast<int>(current_->ask.fdp_rate());
      return send_command(nmea::to_sentence(nmea::FdpTransmit{dest, rate, false, data}),
                          [](const Sentence& s) { return s.is("CATDP"); }, Phase::kAwaitTransmitted,
                          seconds(nmea::fdp_packet_air_s(rate) + kSlack));
    }
    default:
      return finish(DriverSpecificStatus::kInvalidArgument, "micromodem.kind is not known");
  }
}

void DriverSpecificExchange::start_lbl() {
  bool narrowband = current_->ask.kind() == Kind::NARROWBAND_LBL;
  // REMUS transponders turn around in 50 ms (§7.3).
  int turnaround = narrowband ? static_cast<int>(current_->ask.narrowband_lbl().turnaround_ms()) : 50;
  Sentence interrogation;
  int timeout_ms = 0;
  if (narrowband) {
    const auto& lbl = current_->ask.narrowband_lbl();
    nmea::NarrowbandInterrogation x;
    x.transmit_frequency_hz = static_cast<int>(lbl.transmit_frequency_hz());
    x.transmit_ms = static_cast<int>(lbl.transmit_ms());
    x.receive_ms = static_cast<int>(lbl.receive_ms());
    x.timeout_ms = timeout_ms = static_cast<int>(lbl.timeout_ms());
    for (int i = 0; i < lbl.reply_frequency_hz_size(); ++i) x.reply_frequency_hz[i] = static_cast<int>(lbl.reply_frequency_hz(i));
    x.transmit = lbl.transmit();
    interrogation = nmea::to_sentence(x);
  } else {
    const auto& lbl = current_->ask.remus_lbl();
    nmea::RemusInterrogation x;
    x.group = static_cast<int>(lbl.group());
    x.channel = static_cast<int>(lbl.channel());
    x.sync_pps = lbl.sync_pps();
    x.pps_timeout = static_cast<int>(lbl.pps_timeout());
    x.timeout_ms = timeout_ms = static_cast<int>(lbl.timeout_ms());
    for (char c : lbl.beacons()) x.listen[kTransponderLetters.find(c)] = true;
    interrogation = nmea::to_sentence(x);
  }
  std::string echo = narrowband ? "SNPNT" : "SNPDT";
  auto interrogate = [this, interrogation, echo, timeout_ms] {
    send_command(interrogation, [echo](const Sentence& s) { return s.is(echo); }, Phase::kAwaitReply,
                 milliseconds(timeout_ms) + seconds(kSlack));
  };
  if (turnaround_ms_ == turnaround) return interrogate();
  // §8.5: TAT is written first when it changes; the modem removes it from
  // the round trip.
  nmea::ConfigParameter tat{"TAT", std::to_string(turnaround)};
  uint64_t id = current_->id;
  commands_.push({nmea::to_sentence(tat, nmea::Talker::kHost),
                  [](const Sentence& s) { return s.is("CACFG") && s.field(1) == "TAT"; },
                  [this, id, turnaround, interrogate](bool ok, const Sentence*, const std::string& why) {
                    if (!current_ || current_->id != id) return;
                    if (!ok) return finish(DriverSpecificStatus::kAborted, "the modem did not take TAT: " + why);
                    turnaround_ms_ = turnaround;
                    interrogate();
                  },
                  1});
}

void DriverSpecificExchange::send_command(const Sentence& sentence, std::function<bool(const Sentence&)> is_reply,
                                          Phase next, Duration wait_after) {
  uint64_t id = current_->id;
  current_->phase = Phase::kCommand;
  std::string address = "$" + sentence.address();
  commands_.push({sentence, std::move(is_reply),
                  [this, id, next, wait_after, address](bool ok, const Sentence* reply, const std::string& why) {
                    if (!current_ || current_->id != id) return;
                    if (!ok) return finish(DriverSpecificStatus::kAborted, "the modem did not take " + address + ": " + why);
                    if (reply != nullptr && reply->is("CATDP")) {
                      auto echo = nmea::parse_fdp_echo(*reply);
                      if (!echo || echo->error) {
                        return finish(DriverSpecificStatus::kAborted, "the modem refused the FDP packet ($CATDP " +
                                                                          std::string(reply->field(1)) + ")");
                      }
                    }
                    wait(next, wait_after, address);
                  },
                  1});
}

void DriverSpecificExchange::wait(Phase phase, Duration modem_time, std::string what) {
  current_->phase = phase;
  Duration own = scaled(modem_time);
  Duration left = seconds(current_->deadline_s - hooks_.now_s());
  bool deadline_first = left < own;
  Duration delay = std::max(Duration::zero(), std::min(own, left));
  if (current_->timer != 0) scheduler_.cancel(current_->timer);
  uint64_t id = current_->id;
  double own_s = std::chrono::duration<double>(modem_time).count();
  current_->timer = scheduler_.after(delay, [this, id, phase, deadline_first, own_s, what] {
    if (!current_ || current_->id != id) return;
    current_->timer = 0;
    const char* awaited = phase == Phase::kAwaitReply       ? "answer"
                          : phase == Phase::kAwaitTransmitted ? "$CATXF (transmission finished)"
                                                              : "FDP acknowledgement from the destination";
    if (phase == Phase::kAwaitAck) {
      // Sent, but not acknowledged (in time for the call, or at all): the
      // packet is in the water, so the call succeeded and says so
      // (fdp_acknowledged false); a deadline error would invite a resend.
      current_->ask.set_fdp_acknowledged(false);
      return succeed();
    }
    if (deadline_first) {
      return finish(DriverSpecificStatus::kDeadlineExceeded,
                    std::string("the call's deadline passed while ") + what + " waited for " + awaited);
    }
    char text[64];
    std::snprintf(text, sizeof text, "%.1f", own_s);
    finish(DriverSpecificStatus::kDeadlineExceeded,
           "no " + std::string(awaited) + " to " + what + " within " + text + " s of modem time (spec §7/§9 timeout)");
  });
}

void DriverSpecificExchange::succeed() {
  Current done = std::move(*current_);
  current_.reset();
  if (done.timer != 0) scheduler_.cancel(done.timer);
  done.request.MutableExtension(drivers::micromodem_transmission)->CopyFrom(done.ask);
  done.done({DriverSpecificStatus::kOk, "", std::move(done.request)});
}

void DriverSpecificExchange::finish(DriverSpecificStatus status, std::string error) {
  if (!current_) return;
  Current done = std::move(*current_);
  current_.reset();
  if (done.timer != 0) scheduler_.cancel(done.timer);
  ++counters_.failed;
  spdlog::warn("micromodem {}: driver-specific {} failed: {}", settings_.own_id,
               Kind::Kind_Name(done.ask.kind()), error);
  done.done(link::driver_specific_error(status, std::move(error), done.request));
}

void DriverSpecificExchange::abort(const std::string& why) { finish(DriverSpecificStatus::kAborted, why); }

bool DriverSpecificExchange::on_ping_reply(const nmea::PingReply& reply) {
  if (!current_ || current_->ask.kind() != Kind::PING || current_->phase != Phase::kAwaitReply) return false;
  // SRC is the modem that replied, DEST us (§7.1).
  if (reply.source != current_->request.dest() || reply.destination != settings_.own_id) return false;
  current_->ask.set_travel_time_s(reply.travel_time_s);
  current_->ask.set_range_m(reply.travel_time_s * settings_.sound_speed);
  succeed();
  return true;
}

bool DriverSpecificExchange::on_travel_times(const nmea::TravelTimes& times) {
  if (!current_ || current_->phase != Phase::kAwaitReply) return false;
  Kind& ask = current_->ask;
  if (ask.kind() == Kind::NARROWBAND_LBL) {
    for (int i = 0; i < ask.narrowband_lbl().reply_frequency_hz_size(); ++i) {
      drivers::LblReply* reply = ask.add_lbl_reply();
      reply->set_transponder(std::string(1, kTransponderLetters[i]));
      reply->set_frequency_hz(ask.narrowband_lbl().reply_frequency_hz(i));
      reply->set_answered(times.travel_time_s[i].has_value());
      if (times.travel_time_s[i]) {
        reply->set_travel_time_s(*times.travel_time_s[i]);
        reply->set_range_m(*times.travel_time_s[i] * settings_.sound_speed);
      }
    }
  } else if (ask.kind() == Kind::REMUS_LBL) {
    for (int i = 0; i < nmea::kTransponders; ++i) {
      if (ask.remus_lbl().beacons().find(kTransponderLetters[i]) == std::string::npos) continue;
      drivers::LblReply* reply = ask.add_lbl_reply();
      reply->set_transponder(std::string(1, kTransponderLetters[i]));
      reply->set_answered(times.travel_time_s[i].has_value());
      if (times.travel_time_s[i]) {
        reply->set_travel_time_s(*times.travel_time_s[i]);
        reply->set_range_m(*times.travel_time_s[i] * settings_.sound_speed);
      }
    }
  } else {
    return false;
  }
  succeed();
  return true;
}

bool DriverSpecificExchange::on_transmit_finished() {
  if (!current_ || current_->phase != Phase::kAwaitTransmitted) return false;
  if (current_->ask.kind() == Kind::FDP && current_->request.dest() != 0) {
    int rate = static_cast<int>(current_->ask.fdp_rate());
    double travel = settings_.max_range_m / settings_.sound_speed;
    // The ACK: turnaround, its echo, its packet (a short FDP one), travel both ways.
    wait(Phase::kAwaitAck, seconds(2 * travel + kTurnaround + nmea::fdp_packet_air_s(rate) + kSlack), "$CCTDP");
    return true;
  }
  succeed();
  return true;
}

void DriverSpecificExchange::on_mini_packet(const nmea::MiniPacket& packet) {
  if (packet.destination != settings_.own_id && packet.destination != 0) return;
  ++counters_.mini_packets_received;
  ModemTransmission rx;
  rx.set_type(ModemTransmission::DRIVER_SPECIFIC);
  rx.set_src(packet.source);
  rx.set_dest(packet.destination);
  rx.set_time(hooks_.now_s());
  drivers::MicroModemMiniPacket* mini = rx.MutableExtension(drivers::micromodem_mini_packet);
  mini->set_src(packet.source);
  mini->set_dest(packet.destination);
  mini->set_value(packet.value);
  if (hooks_.received) hooks_.received(rx);
}

void DriverSpecificExchange::on_fdp_received(const nmea::FdpReceived& packet) {
  if (packet.destination != settings_.own_id && packet.destination != 0) return;
  if (!packet.intact()) return;  // goby3 drops a packet with a bad frame; the sender's ACK wait says so
  std::string payload = packet.payload();
  if (payload.size() < kFdpHeader) return;
  auto marker = static_cast<uint8_t>(payload[0]);
  auto sequence = static_cast<uint8_t>(payload[1]);
  if (marker == kFdpAck) {
    if (current_ && current_->ask.kind() == Kind::FDP && current_->phase == Phase::kAwaitAck &&
        packet.source == current_->request.dest() && sequence == current_->fdp_sequence) {
      current_->ask.set_fdp_acknowledged(true);
      succeed();
    }
    return;
  }
  if (marker != kFdpData && marker != kFdpPadded) return;  // another host's FDP format: not ours to read
  ++counters_.fdp_received;
  ModemTransmission rx;
  rx.set_type(ModemTransmission::DRIVER_SPECIFIC);
  rx.set_src(packet.source);
  rx.set_dest(packet.destination);
  rx.set_rate(packet.rate);
  rx.set_time(hooks_.now_s());
  drivers::MicroModemFdpPacket* fdp = rx.MutableExtension(drivers::micromodem_fdp_packet);
  fdp->set_src(packet.source);
  fdp->set_dest(packet.destination);
  fdp->set_rate(static_cast<uint32_t>(packet.rate));
  std::string data = payload.substr(kFdpHeader);
  if (marker == kFdpPadded && !data.empty()) data.pop_back();
  fdp->set_data(std::move(data));
  if (packet.destination == settings_.own_id) send_fdp_ack(packet.source, packet.rate, sequence);
  if (hooks_.received) hooks_.received(rx);
}

void DriverSpecificExchange::send_fdp_ack(int destination, int rate, uint8_t sequence) {
  std::string ack;
  ack += static_cast<char>(kFdpAck);
  ack += static_cast<char>(sequence);
  ++counters_.fdp_acks_sent;
  commands_.push({nmea::to_sentence(nmea::FdpTransmit{destination, rate, false, ack}),
                  [](const Sentence& s) { return s.is("CATDP"); },
                  [this](bool ok, const Sentence*, const std::string& why) {
                    if (!ok) spdlog::warn("micromodem {}: FDP acknowledgement not sent: {}", settings_.own_id, why);
                  },
                  1});
}

}  // namespace acomms::drivers::micromodem
