#pragma once
// The queues of one node: one per DCCL type, the priority contest between
// them, frame building, acks, expiry, and the receive side.
//
// Threads: the core thread only, but for a client's message, which comes
// in through Submitter::submit (submitter.h): it runs this class's private
// journal_new (any thread) and accept (core thread) in order.
//
// On each transmission the queues contest every place in a frame: the
// highest priority P = value_base * (t - t_last_sent) / ttl wins (the rules
// in full open frame_building.cpp).
//
// One class, one file per idea: queue_manager.cpp makes the queues, brings
// them back at start-up and holds the steps of a submit, expiry, Cancel and
// Flush; frame_building.cpp the contest, build_frames and on_ack;
// frame_receiving.cpp receive (unstitch, decode). What is received is
// passed on at most once: the rule, and the windows it needs, are the
// ReceiveFilter's (receive_filter.h); a Submit whose ttl_s is longer than
// its type's window is refused here.

#include <google/protobuf/message.h>

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "core/clock.h"
#include "dccl/codec.h"
#include "queue/auth_guard.h"
#include "queue/frame.h"
#include "queue/message_journal.h"
#include "queue/piggyback.h"
#include "queue/queue.h"
#include "queue/queue_stats.h"
#include "queue/receive_filter.h"
#include "queue/received_message.h"
#include "queue/roles.h"
#include "queue/routing.h"

namespace acomms::queue {

// Submit failed because the type is not a loaded DCCL type.
class UnknownTypeError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Submit failed because the type's queue is full and refuses new messages.
class QueueFullError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Submit failed because its ttl_s is longer than the type's duplicate
// window: a resend after the window would be delivered again.
class TtlTooLongError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// "queue T is full (max_queue N) and refuses new messages".
std::string queue_full_text(const Queue& queue);

class QueueManager {
 public:
  // One queue per type loaded in `codec`. Throws std::invalid_argument when
  // the config names a type that is not loaded, a role field that does not
  // exist, or an unusable policy value. `codec`, `clock` and `journal` must
  // outlive the manager.
  QueueManager(const dccl::Codec& codec, const v1::QueueConfig& config, int32_t own_id,
               const core::Clock& clock, MessageJournal& journal);

  // Makes a queue for every loaded type that has none yet (after the codec
  // loaded more definitions). Returns their names. Must not run
  // concurrently with journal_new: the caller holds
  // Submitter::types_changing().
  std::vector<std::string> add_types();

  // Makes `type` authenticated (its codec seals and carries the trailer:
  // dccl::Codec::set_authentication) with window `window_s`: received
  // messages of it must verify and be fresh and new (auth_guard.h), and a
  // Submit whose ttl_s is longer than the window is refused. Call before
  // restore(). Throws std::invalid_argument naming the type when it has no
  // queue, is not authenticated by the codec, the window is not > 0, or
  // the queue's ttl_s is longer than the window.
  void authenticate(const std::string& type, double window_s);

  // Start-up: brings back what the journal holds (after a crash, messages
  // that were in flight come back eligible). A stored message whose type is
  // no longer loaded, or that no longer encodes, is dropped with an event.
  // The duplicate filter gets back what was received within its window.
  // A message of an authenticated type goes out with the seal it was first
  // given (JournalMessage::sealed), byte-identical to any copy sent before
  // the restart.
  void restore();

  // Builds up to request.max_num_frames frames for a transmission. Messages
  // still awaiting an ack from an earlier transmission become eligible
  // again first, and expired ones are dropped.
  std::vector<Frame> build_frames(const DataRequest& request);

  // The receiver acknowledged `frame_id`: its messages are done.
  void on_ack(uint64_t frame_id);

  // Messages awaiting an ACK on link `link` (DataRequest::link) are back in
  // the contest now, for any link: that link was disabled or its driver
  // failed, so its next transmission may be far off.
  void release_in_flight(int link);

  // Splits a received frame into messages and returns those for this node
  // (destination role = own id or broadcast; all when promiscuous).
  // Undecodable bytes end the frame: what came before is kept, the rest is
  // counted and logged as malformed. `link_figures` (a serialized
  // acomms.v1.LinkFigures of the transmission that carried the frame) is
  // logged with each message's received event, so a replay can give it
  // back; nullopt: the link gave none.
  // `link` (the index of the link that heard it, DataRequest::link) and
  // `transmission_dest` (whom the transmission was for) are for routing
  // (queue/routing.h) only.
  std::vector<ReceivedMessage> receive(std::string_view frame, int32_t transmission_src,
                                       std::optional<std::string_view> link_figures = std::nullopt, int link = 0,
                                       int32_t transmission_dest = kAnyDestination);

  // Gateways (queue/routing.h, README "Gateways"): routing decides how
  // chosen messages go out and what received envelopes become. Set once,
  // before restore(); null (the default): no routing, frames unchanged.
  // `routing` must outlive the manager. Defined in routed_queues.cpp, as
  // are the custody calls below.
  void set_routing(Routing* routing) { routing_ = routing; }
  // A node's own bytes in frames' spare space (queue/piggyback.h): asked
  // for after the last frame's contest, handed what starts with its id on
  // receive. Null (the default): frames unchanged. Must outlive the
  // manager; set before the links start.
  void set_piggyback(Piggyback* piggyback) { piggyback_ = piggyback; }
  // Custody, any thread: stores `record` (type: a custody queue's name,
  // Routing::custody_policy; payload: the envelope's bytes) with its
  // "queued" event; `appended` runs once it is durable (or failed), on the
  // journal's thread, as for a Submit.
  void journal_custody(JournalMessage record, MessageJournal::Appended appended);
  // Core thread: puts a journaled custody message (encoded = payload) in its
  // queue, made on demand. False when no custody queue has that name or the
  // queue is full and refuses it (dropped, with an event).
  bool accept_custody(QueuedMessage message);
  // Core thread: the ACK conditions received envelopes set since the last
  // call (EnvelopeOutcome::ack_only_if): the link's ACK of the transmission
  // just received goes only if all are still true once its receipts are
  // durable.
  std::vector<std::shared_ptr<std::atomic<bool>>> take_ack_conditions();
  // Core thread, routing's side of a reception (routed_queues.cpp): an ACK
  // from `src` on `link`; whether the driver of `link` ACKs in hardware.
  void heard_ack(int link, int32_t src);
  void set_acks_in_hardware(int link, bool in_hardware);
  // Core thread: receive() of an envelope's payload, whose received event
  // keeps the routed identity (origin, seq) until `forget_after` so a copy
  // is known after a restart (MessageJournal::routed_since).
  std::vector<ReceivedMessage> receive_routed(std::string_view payload, int32_t origin, uint16_t seq,
                                              double forget_after, std::optional<std::string_view> link_figures,
                                              int link);
  // The identities of routed messages delivered here that are still to be
  // known (MessageJournal::routed_since now): the forwarder's at start.
  std::vector<RoutedIdentity> routed_delivered() { return journal_.routed_since(clock_.now_seconds()); }
  // Core thread: logs and journals what routing learned of `message` (of
  // queue `type`) after it left the queue (an end-to-end ack: kDelivered; an
  // expiry report: kExpired, counted in QueueStats::expired_remote, not
  // expired). False when no queue has that name.
  bool report_routed(const std::string& type, QueueEventKind kind, const JournalMessage& message,
                     const std::string& detail);

  // Core thread, custody receipts (route/custody_receipt.h): message `id`
  // of queue `type`, held after its modem's ACK (Routing::keeps_after_ack),
  // passed custody to its next hop: removed, with its acked event (`detail`,
  // then routing's acked_detail). False when it is no longer queued.
  bool custody_passed(const std::string& type, int64_t id, const std::string& detail);

  // Logs a "packet" event (QueueEventKind::kPacket): one packet heard from
  // `src`, with its serialized acomms.v1.LinkFigures. Core thread only.
  void record_packet(int32_t src, int32_t dest, std::string link_figures);

  // Drops messages past their ttl now (also done on every build_frames).
  void expire();

  // Removes a queued message (Cancel). False if there is no such message.
  bool cancel(int64_t id, const std::string& reason);

  // Removes every message of `type` (Flush), each with a dropped event
  // giving `reason`. Returns how many. Throws UnknownTypeError.
  size_t flush(const std::string& type, const std::string& reason);

  const Queue* find_queue(const std::string& type) const;
  std::vector<const Queue*> queues() const;
  QueueStats stats(const std::string& type) const;
  uint64_t malformed_frames() const { return malformed_frames_; }
  // Received messages of authenticated types refused, per reason.
  const AuthRefusals& auth_refusals() const { return auth_guard_.refusals(); }
  // Received messages recognised as retransmissions and not passed on.
  uint64_t duplicates() const { return receive_filter_.duplicates(); }
  // Received messages refused as stale: stamped longer ago than their
  // type's window (plus the clock skew allowed).
  uint64_t stale_refused() const { return receive_filter_.stale_refused(); }
  // The type's duplicate window W in seconds (0: off); Submit refuses a
  // ttl_s above it. Throws UnknownTypeError.
  double duplicate_window(const std::string& type) const;
  // The longest any type's duplicate filter looks back (seconds; 0: none
  // does): received events this recent are read back at start, so the
  // event log must keep them. Core thread only (queues come and go).
  double duplicate_window_s() const;
  // The received sequence number given to the last message received (0:
  // none yet); continues across restarts from the journal.
  int64_t last_received_seq() const { return last_received_seq_; }
  // Hands out the next received sequence number for something received
  // that is not a queue message: telemetry's reconstructed Positions, which
  // Subscribe replays by `after` like every received message. The taker
  // makes the number durable (event_sequence, migration 0005) in the commit
  // that stores what it numbers. Core thread only (numbers follow the order
  // things are passed on).
  int64_t take_received_seq();

 private:
  // The steps of a submit, run in order on their threads by
  // Submitter::submit, the one way a client's message comes in.
  friend class Submitter;

  // Any thread. Fills unset source/timestamp roles and encodes (strict mode
  // per the codec): throws UnknownTypeError, QueueFullError (a full
  // REFUSE_NEW queue, counted as refused), or dccl::Error naming the field
  // and bound (or the required fields still missing once the roles are
  // filled); nothing is stored then. Otherwise hands the message to the
  // journal without waiting for the commit: `journaled` gets it with its id
  // once it is durable, or the error that kept it from the disk, on the
  // journal's thread; it must be short and never wait (hand the message to
  // the core thread from there). Completions come in the order of the calls.
  using Journaled = std::function<void(QueuedMessage, std::exception_ptr)>;
  void journal_new(const google::protobuf::Message& message, double ttl_s, Journaled journaled) const;

  // Core thread. Puts a journaled message in its queue. Returns false when
  // the queue is full and refuses new messages (the message is then
  // dropped, with an event). A full queue that drops its oldest message
  // returns true.
  bool accept(QueuedMessage message);

  struct TypeState {
    std::unique_ptr<Queue> queue;
    MessageRoles roles;
    QueueStats stats;  // core thread
    // Counted by journal_new, on any thread.
    mutable std::atomic<uint64_t> refused{0};
    // W (0: off), as the ReceiveFilter gave it when the queue was made;
    // prepare_new reads it on any thread to bound a Submit's ttl.
    double window_s = 0;
    // The authenticated window (0: not authenticated), set before any
    // Submit; bounds a Submit's ttl as window_s does.
    double auth_window_s = 0;
    // A custody queue (routed_queues.cpp): envelopes held for other nodes.
    bool custody = false;
  };

  // The tag, stamp and replay checks of one received message of an
  // authenticated type (its DCCL bytes and trailer): its stamp, or nullopt
  // when refused (counted and logged by the guard).
  // A custody queue's state by name, made when routing names a policy for
  // it; null otherwise (routed_queues.cpp).
  TypeState* custody_state(const std::string& type);
  // Routing's form of `queue`'s next message for `request` (kPlain without
  // routing).
  RoutedForm routed_form(const Queue& queue, const QueuedMessage& next, const DataRequest& request, double now);

  std::optional<dccl::AuthStamp> admit_authenticated(const std::string& type, std::string_view message,
                                                     int32_t transmission_src, double now);

  // restore(): the bytes `record` was first sealed with, when they can go
  // out again as they were (so a receiver that has them refuses the copy
  // instead of delivering it twice); nullptr when `resealed` must go.
  const std::string* first_seal(const JournalMessage& record, const std::string& resealed, double now) const;

  // journal_new's checks and encoding: the message as it will be queued,
  // not yet journaled (id 0).
  QueuedMessage prepare_new(const google::protobuf::Message& message, double ttl_s) const;

  struct Contender;
  std::vector<Contender> contenders(double now);
  TypeState* contest(std::vector<Contender>& field, double now, size_t room, int32_t dest,
                     const DataRequest& request);
  // The piggyback after the last contest (frame_building.cpp).
  void add_piggyback(const DataRequest& request, int32_t dest, double now, std::vector<Frame>* frames);
  // One change of a message's fate, as emit() takes it; callers name the
  // fields they set (designated initializers), the rest keep these values.
  struct Change {
    QueueEventKind kind;
    const JournalMessage& message;
    uint64_t frame_id = 0;              // kSent, kAcked, kRetry: the frame
    std::string_view detail = {};       // why, for the log and the event
    bool removes_message = false;       // QueueEvent::removes_message
    bool already_journaled = false;     // the journal has the event: count and log only
    std::string_view encoded = {};      // kReceived: the message's bytes
    std::optional<std::string_view> link_figures = std::nullopt;  // kReceived: its transmission's
    std::optional<uint32_t> auth_sent_s = std::nullopt;           // kReceived, authenticated: its stamp
    int32_t auth_sender = -1;                                      // with auth_sent_s: the transmission's src
    bool remote = false;  // reported from afar (report_routed): kExpired counts in expired_remote
  };
  // Counts, logs and journals `change` to a message of `state`'s type, at `now`.
  void emit(TypeState& state, double now, const Change& change);

  const dccl::Codec& codec_;
  v1::QueueConfig config_;
  int32_t own_id_;
  bool promiscuous_;
  const core::Clock& clock_;
  MessageJournal& journal_;
  // Ordered by DCCL id: the contest's last tie-break, and a stable order for tools.
  std::map<int, TypeState> by_id_;
  std::unordered_map<std::string, TypeState*> by_name_;
  // Frames awaiting an ack: frame id -> the link that sent it and the
  // types with messages in it.
  struct InFlightFrame {
    int link = 0;
    std::vector<TypeState*> types;
  };
  std::unordered_map<uint64_t, InFlightFrame> in_flight_;
  uint64_t next_frame_id_;
  // Each type's priority when the build_frames running now began: what
  // the link's cost is held against (DataRequest::may_carry).
  std::unordered_map<const TypeState*, double> standing_;
  uint64_t malformed_frames_ = 0;
  ReceiveFilter receive_filter_;  // core thread
  AuthGuard auth_guard_;          // core thread (its windows are fixed before any Submit)
  int64_t last_received_seq_ = 0;
  // Gateways (routed_queues.cpp): null without routing.
  Routing* routing_ = nullptr;
  Piggyback* piggyback_ = nullptr;
  // Custody queues sort after every DCCL id (last in a priority tie).
  int next_custody_key_ = 1 << 20;
  // The form of the message the last contest() chose (build_frames sends it).
  RoutedForm winner_form_;
  int64_t winner_id_ = 0;  // ... and which of its queue's messages it is
  std::vector<std::shared_ptr<std::atomic<bool>>> ack_conditions_;
  // Set while receive_routed() runs: the identity its received event keeps.
  std::optional<RoutedIdentity> receiving_routed_;
};

}  // namespace acomms::queue
