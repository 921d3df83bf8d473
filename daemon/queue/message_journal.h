#pragma once
// Where queued messages outlive the process. The queues keep their working
// state in memory on the core thread; the journal holds every message that
// a Submit acknowledged until an event ends its life, plus the event log.
//
// After a crash, load() gives back exactly the messages appended and not yet
// removed; messages that were in flight (sent, awaiting an ack) come back as
// ordinary queued messages and are sent again.

#include <cstdint>
#include <exception>
#include <functional>
#include <future>
#include <string>
#include <vector>

#include "queue/queue_event.h"

namespace acomms::queue {

struct JournalMessage {
  int64_t id = 0;             // assigned by append(); the id clients see
  std::string type;           // DCCL full type name
  std::string payload;        // the protobuf message, serialized (binary)
  int32_t src = -1;           // from the source role, -1 if none
  int32_t dest = 0;           // from the destination role; 0 = broadcast
  double submitted_at = 0;    // Clock seconds since the Unix epoch
  double ttl_s = 0;           // per-message ttl; 0 = the queue's
  // An authenticated type's message as first sealed (DCCL bytes and
  // trailer), so that a restart sends it byte-identical and a receiver that
  // has it refuses the copy (migrations/0012); empty otherwise.
  std::string sealed;
};

class MessageJournal {
 public:
  virtual ~MessageJournal() = default;

  // Once an append is durable: its new id and a null error; or id 0 and
  // why it could not be stored.
  using Appended = std::function<void(int64_t id, std::exception_ptr error)>;

  // Stores `message` durably, with its "queued" event (time submitted_at)
  // in the same transaction: one commit per Submit, not two. Safe from any
  // thread; concurrent calls share commits (group commit). Does not wait:
  // `appended` runs once the commit is done, on the journal's own thread
  // (it must be short, must not wait, and must not append). Appends
  // complete in the order they were made. Throws if the journal refuses
  // the write outright (then `appended` never runs).
  virtual void append(JournalMessage message, Appended appended) = 0;

  // The same, waiting for the commit: returns the id, or throws why the
  // message was not stored.
  int64_t append(JournalMessage message) {
    std::promise<int64_t> stored;
    std::future<int64_t> id = stored.get_future();
    append(std::move(message), [&stored](int64_t new_id, std::exception_ptr error) {
      if (error) {
        stored.set_exception(error);
      } else {
        stored.set_value(new_id);
      }
    });
    return id.get();
  }

  // Logs `event`, and forgets its message when event.removes_message.
  // Asynchronous: never waits for the disk (the core thread calls it), but
  // ordered after every append() that returned before it.
  virtual void record(const QueueEvent& event) = 0;

  // Every message appended and not removed, in id order. Called at start-up,
  // before any append().
  virtual std::vector<JournalMessage> load() = 0;

  // The kReceived events logged at or after `since`, with their encoded
  // bytes, oldest first: what the duplicate filter must remember again
  // after a restart. Called at start-up.
  virtual std::vector<QueueEvent> received_since(double since) = 0;

  // The received messages of authenticated types still remembered in
  // auth_accepted, stamped at or after `sent_since` (type, encoded and
  // auth_sent_s set): what the AuthGuard must remember again after a
  // restart. Called at start-up.
  virtual std::vector<QueueEvent> authenticated_since(double sent_since) = 0;

  // The identities of routed messages delivered here (QueueEvent::routed)
  // still to be known at `now` (forget_after >= now); those past it are
  // forgotten. What the forwarder must remember again after a restart.
  // Called at start-up.
  virtual std::vector<RoutedIdentity> routed_since(double now) = 0;

  // The last received sequence number handed out (0: none yet), read at
  // start-up: the queue continues from it. Numbers are assigned by the
  // queue (QueueEvent::seq) and made durable by record().
  virtual int64_t last_received_seq() = 0;

  // Does not wait: `committed` runs once everything recorded so far is
  // committed, with a null error, or with why it was not. Runs on the
  // journal's own thread (short, no waiting), in the order of the calls.
  // A received message is published only from here, so that a subscriber
  // never sees a sequence number a crash could hand out again.
  // "Done" is not "stored": a record() whose own batch failed before this
  // request's batch does not fail it (events_not_stored() tells).
  using Committed = std::function<void(std::exception_ptr error)>;
  virtual void when_committed(Committed committed) = 0;

  // How many record()ed events failed to commit, since the journal was
  // built. Read from a `committed` callback, it counts exactly the failures
  // among the events recorded before that when_committed() (the callbacks
  // run in order, each after everything before it is done).
  virtual uint64_t events_not_stored() const = 0;

  // Returns once everything recorded so far is committed.
  virtual void flush() = 0;
};

}  // namespace acomms::queue
