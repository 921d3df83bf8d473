#pragma once
// Submit: a client's message into its queue, answered only once the message
// is durably stored.
//
// The problem: a Submit crosses three threads. Encoding is CPU work the
// caller's thread can do (the codec is read-only once types are loaded);
// the commit happens on the store writer's thread, shared with other
// Submits (group commit); the queues belong to the core thread. Each hop
// has a way to fail, and a gRPC thread must never wait for the disk.
//
// The decision: submit() is the one call that runs the sequence, and its
// answer comes back through a callback, exactly once:
//   caller's thread    checks and encodes (QueueManager::journal_new),
//                      refusing at once an unknown type, a message that
//                      does not encode, or a full REFUSE_NEW queue;
//   writer's thread    the commit completes: hands the message on to the
//                      core (or answers the store's failure);
//   core thread        QueueManager::accept queues it, and the answer is
//                      the message id (or a refusal, when the queue filled
//                      while the message was being stored).
// Nothing here waits: not the caller, not the writer, not the core.
//
// The invariant it keeps with its lock: a type looked up and encoded off
// the core thread does not change underneath. The codec's types and the
// set of queues only grow, and only under types_changing() (LoadDefinitions
// takes it before it loads and adds queues); submit() holds types_stable()
// while it encodes, and so does every other reader of the codec off the
// core thread (Encode, Decode, ListTypes, ...).

#include <google/protobuf/message.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <shared_mutex>
#include <string>

#include "queue/queue_manager.h"

namespace acomms::queue {

// How a submit ended.
struct SubmitResult {
  enum class Error {
    kNone,
    kUnknownType,       // no loaded DCCL type of that name, or one without an id
    kQueueFull,         // the type's queue is full and refuses new messages
    kInvalidMessage,    // does not encode: names the field and the bound
    kStoreUnavailable,  // not stored: the store failed or is stopping
    kStoreFull,         // not stored: the disk holding the store is full
  };
  Error error = Error::kNone;
  int64_t message_id = 0;  // the id clients see, when error is kNone
  std::string text;        // why, in words a person can act on, otherwise
  bool ok() const { return error == Error::kNone; }
};

class Submitter {
 public:
  // Runs `work` on the core thread later, without waiting (EventLoop::post).
  using PostToCore = std::function<void(std::function<void()>)>;
  // Receives a submit's result: on the caller's thread (refused before
  // storing), the store writer's thread (not stored) or the core thread
  // (queued, or refused by a queue that filled meanwhile). Must be short
  // and must not wait (nor take types_changing()).
  using Done = std::function<void(SubmitResult)>;

  // `queues` must outlive the submitter, and so must the core that
  // `post_to_core` reaches (or it must drop work posted after it stopped).
  // The submitter must outlive every submit not yet answered (the daemon
  // shuts its gRPC server down first).
  Submitter(QueueManager& queues, PostToCore post_to_core);

  // Any thread. Fills the message's unset source and time roles, encodes
  // it, stores it and queues it (see the top of this file); `done` gets the
  // result exactly once. `ttl_s` 0 means the queue's ttl.
  void submit(const google::protobuf::Message& message, double ttl_s, Done done);

  // Held shared by every reader of the codec's types or the set of queues
  // off the core thread; submit() takes it itself.
  [[nodiscard]] std::shared_lock<std::shared_mutex> types_stable() const {
    return std::shared_lock(types_);
  }
  // Held by whoever loads types and adds their queues (QueueManager::
  // add_types): no submit encodes meanwhile.
  [[nodiscard]] std::unique_lock<std::shared_mutex> types_changing() { return std::unique_lock(types_); }

 private:
  // Core thread, once the message is durable.
  void accept(QueuedMessage message, const Done& done);

  QueueManager& queues_;
  PostToCore post_to_core_;
  mutable std::shared_mutex types_;
};

}  // namespace acomms::queue
