#include "link/link_controller.h"

#include <spdlog/spdlog.h>

#include <google/protobuf/descriptor.h>

#include <algorithm>
#include <cmath>

#include "core/core_thread.h"
#include "link/link_figures.h"

namespace acomms::link {

namespace {

// What is left of the slot of `transmission` at `now` (the whole slot when
// the time is unknown).
std::chrono::nanoseconds time_left(const v1::ModemTransmission& transmission, const core::Clock* clock) {
  using std::chrono::nanoseconds;
  auto slot = nanoseconds(std::llround(transmission.slot_seconds() * 1e9));
  if (clock == nullptr || !(transmission.time() > 0)) return slot;
  auto start = nanoseconds(std::llround(transmission.time() * 1e9));
  auto elapsed = std::chrono::duration_cast<nanoseconds>(clock->now().time_since_epoch()) - start;
  // The slot start went through a double (about 0.2 us at today's epoch):
  // a request at the start must not lose a frame to that rounding.
  if (elapsed < std::chrono::microseconds(1)) return slot;
  return std::max(nanoseconds(0), slot - elapsed);
}

}  // namespace

LinkOptions LinkOptions::from_config(const v1::MacConfig& mac, const core::Clock& clock) {
  LinkOptions options;
  options.clock = &clock;
  if (mac.has_max_range_m()) options.max_range_m = mac.max_range_m();
  return options;
}

LinkController::LinkController(int32_t own_id, queue::QueueManager& queues, mac::Mac& mac, Driver& driver,
                               Deliver deliver, LinkOptions options)
    : own_id_(own_id),
      queues_(queues),
      mac_(mac),
      driver_(driver),
      deliver_(std::move(deliver)),
      options_(options),
      enabled_(options.enabled),
      gate_(options.clock, options.scheduler) {
  if (options_.choice != nullptr) options_.choice->set_enabled(options_.link_index, enabled_);
}

void LinkController::start() {
  ACOMMS_ASSERT_CORE_THREAD();
  started_ = true;
  if (enabled_) run();
}

void LinkController::stop() {
  ACOMMS_ASSERT_CORE_THREAD();
  started_ = false;
  halt();
}

bool LinkController::set_enabled(bool enabled) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (enabled == enabled_) return false;
  enabled_ = enabled;
  if (options_.choice != nullptr) options_.choice->set_enabled(options_.link_index, enabled);
  spdlog::info("link {}: {}", options_.choice != nullptr ? options_.choice->link(options_.link_index).name : "",
               enabled ? "enabled" : "disabled");
  if (!enabled) {
    halt();
    queues_.release_in_flight(options_.link_index);
  } else if (started_) {
    run();
  }
  return true;
}

void LinkController::on_driver_state(bool up) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (options_.choice != nullptr) options_.choice->set_driver_up(options_.link_index, up);
  if (!up) queues_.release_in_flight(options_.link_index);
}

void LinkController::halt() {
  if (!running_) return;
  running_ = false;
  mac_.stop();
  gate_.abort("the link stopped");
  driver_.stop();
}

void LinkController::run() {
  if (running_) return;
  running_ = true;
  DriverCallbacks callbacks;
  callbacks.on_receive = [this](const v1::ModemTransmission& t) { on_receive(t); };
  callbacks.on_data_request = [this](v1::ModemTransmission* t) { on_data_request(t); };
  callbacks.on_transmit_result = [this](const v1::ModemTransmission& t, bool ok, const std::string& error) {
    on_transmit_result(t, ok, error);
  };
  callbacks.on_raw = [this](std::string_view bytes, bool outgoing) {
    if (raw_tap_) raw_tap_(bytes, outgoing);
    if (spdlog::should_log(spdlog::level::trace)) {
      spdlog::trace("link {} {} bytes", outgoing ? ">>" : "<<", bytes.size());
    }
  };
  // A gateway's custody (queue/routing.h): the ACK of what was just
  // received goes only if every custody it took is committed (the driver
  // asks for this right after on_receive, for the same transmission).
  // Without the hook the driver acknowledges at once, custody or not: the
  // daemon always gives one.
  if (options_.after_receipt_durable) {
    callbacks.after_receipt_durable = [this](std::function<void()> then) {
      if (!ack_conditions_.empty()) {
        then = [conditions = std::exchange(ack_conditions_, {}), then = std::move(then)] {
          for (const auto& condition : conditions) {
            if (!condition->load()) {
              spdlog::debug("link: ACK withheld: custody not taken (the previous hop keeps the message)");
              return;
            }
          }
          then();
        };
      }
      options_.after_receipt_durable(std::move(then));
    };
  }
  callbacks.on_reception_failed = [this](const v1::ModemTransmission& t) { record_packet(t, false); };
  driver_.start(std::move(callbacks));
  mac_.start([this](const v1::ModemTransmission& t) {
    // The driver's data request, if any, comes within this call.
    struct OwnSlot {
      bool& flag;
      explicit OwnSlot(bool& f) : flag(f) { flag = true; }
      ~OwnSlot() { flag = false; }
    } own_slot(in_own_slot_);
    // The slot rule (driver_specific_gate.h): our own slot carries a
    // waiting extra instead of data.
    if (t.src() == own_id_ && gate_.waiting() && gate_.send_next(driver_, "this node's slot")) return;
    try {
      driver_.initiate_transmission(t);
    } catch (const DriverError& e) {
      ++stats_.transmissions_failed;
      spdlog::warn("link: slot for node {} lost: {}", t.src(), e.what());
    }
  });
}

void LinkController::request_driver_specific(const v1::ModemTransmission& request, double timeout_s,
                                             DriverSpecificDone done) {
  ACOMMS_ASSERT_CORE_THREAD();
  double deadline_s = (options_.clock == nullptr ? 0 : options_.clock->now_seconds()) + timeout_s;
  DriverSpecificResult checked = driver_.check_driver_specific(request);
  if (checked.status != DriverSpecificStatus::kOk) return done(std::move(checked));
  gate_.wait(request, deadline_s, std::move(done));
}

void LinkController::on_data_request(v1::ModemTransmission* transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  queue::DataRequest request;
  request.dest = transmission->has_dest() ? transmission->dest() : queue::kAnyDestination;
  request.max_frame_bytes = transmission->max_frame_bytes();
  request.max_num_frames = frames_for_slot(*transmission);
  request.ack_requested = transmission->ack_requested();
  request.link = options_.link_index;
  // A slot's transmission goes even when empty; a slotless driver's (a
  // satellite session) only for what the queues give.
  request.in_slot = transmission->slot_seconds() > 0;
  if (options_.choice != nullptr) {
    request.may_carry = [this](const std::string& type, int32_t dest, double priority) {
      return options_.choice->may_carry(options_.link_index, type, dest, priority, now_s());
    };
  }
  if (!in_own_slot_ && gate_.waiting()) {
    // A poll gives this slotless node the channel and an extra waits: the
    // poll is answered with one blank frame (the modem expects an answer)
    // and the extra follows it (on_transmit_result).
    extra_after_poll_answer_ = true;
    request.max_num_frames = 0;
  }
  transmission->set_max_num_frames(extra_after_poll_answer_ ? 1 : request.max_num_frames);
  transmission->clear_frame();
  // Not even one frame fits: no packet at all (not even the empty one
  // below), since one that outruns the slot is lost anyway and costs the
  // next slot's owner its reception.
  if (request.max_num_frames == 0 && !extra_after_poll_answer_) return;
  std::vector<queue::Frame> frames;
  if (request.max_num_frames > 0) frames = queues_.build_frames(request);
  std::vector<uint64_t> frame_ids;
  bool ack = false;
  for (queue::Frame& frame : frames) {
    transmission->add_frame(std::move(frame.bytes));
    frame_ids.push_back(frame.frame_id);
    ack = ack || frame.ack_requested;
  }
  // With nothing to send the slot is still used: one empty frame, to
  // broadcast, unacked. Being heard in its slot is how auto-discovery
  // neighbours learn that a node exists (a transmission without frames
  // would be a poll).
  if (frames.empty()) transmission->add_frame("");
  int32_t dest = frames.empty() ? queue::kBroadcast : frames.front().dest;
  if (request.dest == queue::kAnyDestination) transmission->set_dest(dest);
  transmission->set_ack_requested(ack);
  if (ack) awaiting_ack_[transmission->dest()] = std::move(frame_ids);
}

uint32_t LinkController::frames_for_slot(const v1::ModemTransmission& transmission) {
  uint32_t limit = transmission.max_num_frames();
  if (!(transmission.slot_seconds() > 0)) return limit;  // no slot given: nothing to budget
  SlotBudget budget;
  budget.rate = transmission.rate();
  budget.time_left = time_left(transmission, options_.clock);
  if (!in_own_slot_) {
    // Answering a poll: the slot began the poll's travel before we heard it.
    budget.time_left = std::max(std::chrono::nanoseconds(0),
                                budget.time_left - travel_time(driver_, options_.max_range_m));
  }
  budget.ack_requested = transmission.ack_requested();
  budget.max_range_m = options_.max_range_m;
  uint32_t fit = frames_that_fit(driver_, budget, limit);
  if (fit == 0 &&
      short_slots_warned_.emplace(transmission.src(), transmission.rate(), transmission.slot_seconds()).second) {
    spdlog::warn("link: a slot of node {} at rate {} ({} s) carries no data: {} (see acommsd --check-config)",
                 transmission.src(), transmission.rate(), transmission.slot_seconds(),
                 describe_shortfall(driver_, budget));
  }
  return fit;
}

void LinkController::on_receive(const v1::ModemTransmission& transmission) {
  ACOMMS_ASSERT_CORE_THREAD();
  mac_.on_receive(transmission);
  ack_conditions_.clear();  // they belong to the transmission they came with
  // Whether this link's modem ACKs decides custody on both sides of a hop:
  // an ACK heard here (the sender keeps a routed message for its custody
  // receipt), DATA heard here (the receiver answers with one).
  queues_.set_acks_in_hardware(options_.link_index, driver_.acks_in_hardware());
  if (transmission.has_figures()) {
    // Frameless packets (polls, ACKs) are mini-packets, FSK whatever rate
    // field they carry: rate 0's reception curve judges them.
    v1::ModemTransmission heard = transmission;
    if (heard.type() != v1::ModemTransmission::DATA || heard.frame_size() == 0) heard.set_rate(0);
    heard.clear_frame();
    record_packet(heard, true);
  }
  // Any packet from a node says this link reaches it (link_choice.h).
  const bool from_other = transmission.src() != own_id_ && transmission.src() != queue::kBroadcast;
  if (options_.choice != nullptr && from_other &&
      (transmission.type() == v1::ModemTransmission::DATA ||
       (transmission.type() == v1::ModemTransmission::ACK && transmission.dest() == own_id_))) {
    options_.choice->reached(options_.link_index, transmission.src(), now_s());
  }
  if (transmission.type() == v1::ModemTransmission::ACK) {
    if (transmission.dest() != own_id_) return;
    ++stats_.acks_received;
    // An ACK to us: the node hears us and we hear it (a gateway's routes).
    queues_.heard_ack(options_.link_index, transmission.src());
    auto it = awaiting_ack_.find(transmission.src());
    if (it == awaiting_ack_.end()) {
      spdlog::debug("link: ack from {} for nothing we sent it", transmission.src());
      return;
    }
    for (uint32_t index : transmission.acked_frame()) {
      if (index < it->second.size()) queues_.on_ack(it->second[index]);
    }
    awaiting_ack_.erase(it);
    return;
  }
  if (transmission.type() == v1::ModemTransmission::DRIVER_SPECIFIC) return deliver_driver_specific(transmission);
  if (transmission.type() != v1::ModemTransmission::DATA) return;
  ++stats_.data_received;
  if (transmission.has_figures()) {
    ++stats_.receptions_with_figures;
    stats_.bad_frames_received += transmission.figures().bad_frames();
  }
  // Frames are filtered message by message (destination roles), not by the
  // transmission's dest: a unicast frame may carry broadcast messages. Each
  // message's event keeps the transmission's figures, for replay.
  const std::string figures = link_figures(transmission).SerializeAsString();
  for (const std::string& frame : transmission.frame()) {
    for (queue::ReceivedMessage& message : queues_.receive(frame, transmission.src(), figures, options_.link_index,
                                                                    transmission.dest())) {
      ++stats_.messages_delivered;
      deliver_(std::move(message), transmission);
    }
  }
  ack_conditions_ = queues_.take_ack_conditions();
}

void LinkController::record_packet(const v1::ModemTransmission& transmission, bool decoded) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (transmission.src() == own_id_ || transmission.src() < 0) return;
  v1::LinkFigures figures = link_figures(transmission);
  // Every frame bad ($CACST): heard, not decoded, though the driver passed it on.
  const v1::ReceptionFigures& f = transmission.figures();
  if (f.frames() > 0 && f.bad_frames() >= f.frames()) decoded = false;
  figures.set_decoded(decoded);
  // What telemetry (to this node or broadcast) lost in this packet, as the
  // link saw it: one per bad frame (a frame usually carries one message),
  // at least one for a packet that did not decode; overheard traffic to
  // others is no part of the gap (lost_recorded).
  if (transmission.dest() == own_id_ || transmission.dest() == queue::kBroadcast) {
    const uint64_t bad = f.bad_frames();
    if (!decoded) {
      lost_recorded_[transmission.src()] += std::max<uint64_t>(bad, 1);
    } else if (bad > 0) {
      lost_recorded_[transmission.src()] += bad;
    }
  }
  figures.clear_link_quality();  // the same figures again, as text: not worth a row each
  // Which link heard it (a node with several is calibrated link by link),
  // and the model's prediction when the driver has none (a real modem).
  if (options_.choice != nullptr) figures.set_link(options_.choice->link(options_.link_index).name);
  if (options_.predict && !figures.has_predicted_snr_db()) options_.predict(transmission, figures);
  queues_.record_packet(transmission.src(), transmission.dest(), figures.SerializeAsString());
}

void LinkController::deliver_driver_specific(const v1::ModemTransmission& transmission) {
  const google::protobuf::Reflection* reflection = transmission.GetReflection();
  std::vector<const google::protobuf::FieldDescriptor*> fields;
  reflection->ListFields(transmission, &fields);
  for (const google::protobuf::FieldDescriptor* field : fields) {
    if (!field->is_extension() || field->is_repeated() ||
        field->cpp_type() != google::protobuf::FieldDescriptor::CPPTYPE_MESSAGE) {
      continue;
    }
    const google::protobuf::Message& extension = reflection->GetMessage(transmission, field);
    queue::ReceivedMessage message;
    message.type = extension.GetDescriptor()->full_name();
    message.message.reset(extension.New());
    message.message->CopyFrom(extension);
    message.src = transmission.src();
    message.dest = transmission.dest() < 0 ? queue::kBroadcast : transmission.dest();
    message.time = transmission.time();
    // seq 0: driver-specific receptions are not journaled (no DCCL queue
    // holds their type), so a resuming subscriber does not get them again.
    ++stats_.messages_delivered;
    deliver_(std::move(message), transmission);
  }
}

void LinkController::on_transmit_result(const v1::ModemTransmission& transmission, bool ok,
                                        const std::string& error) {
  if (extra_after_poll_answer_ && transmission.src() == own_id_) {
    extra_after_poll_answer_ = false;
    // Not at once: the answer is still in the water, and the extra would
    // arrive at the poller while it is hearing the answer (and lose both).
    // So after the answer has travelled the farthest range and been heard
    // (with room for an ACK), as the slot budget counts it.
    auto send = [this] { gate_.send_next(driver_, "the channel a poll gave this node"); };
    if (options_.scheduler != nullptr) {
      auto clear = std::chrono::duration_cast<std::chrono::system_clock::duration>(
          travel_time(driver_, options_.max_range_m) + driver_.ack_time(transmission.rate()));
      options_.scheduler->after(clear, send);
    } else {
      send();
    }
  }
  if (ok) {
    ++stats_.transmissions_sent;
    return;
  }
  ++stats_.transmissions_failed;
  spdlog::warn("link: transmission to {} failed: {}", transmission.dest(), error);
}

}  // namespace acomms::link
