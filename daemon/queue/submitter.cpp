#include "queue/submitter.h"

#include <atomic>
#include <exception>
#include <memory>
#include <optional>
#include <utility>

#include "core/core_thread.h"
#include "dccl/error.h"
#include "store/store_error.h"

namespace acomms::queue {
namespace {

using Error = SubmitResult::Error;

SubmitResult refused(Error error, std::string text) { return {error, 0, std::move(text)}; }

// A store failure, as the caller will read it: the store's text names the
// file; a full disk is told apart, since an operator can free space.
SubmitResult store_failure(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const store::StoreError& e) {
    if (e.disk_full()) {
      return refused(Error::kStoreFull, std::string("store: ") + e.what() +
                                            " (the disk holding the store is full: free space on it, "
                                            "then submit again)");
    }
    return refused(Error::kStoreUnavailable, std::string("store: ") + e.what());
  } catch (const std::exception& e) {
    return refused(Error::kStoreUnavailable, std::string("store: ") + e.what());
  } catch (...) {
    return refused(Error::kStoreUnavailable, "store: unknown failure");
  }
}

// Why journal_new refused a message before anything was stored.
SubmitResult refusal_of(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const UnknownTypeError& e) {
    return refused(Error::kUnknownType, e.what());
  } catch (const QueueFullError& e) {
    return refused(Error::kQueueFull, e.what());
  } catch (const TtlTooLongError& e) {
    return refused(Error::kInvalidMessage, e.what());
  } catch (const dccl::Error& e) {
    return refused(Error::kInvalidMessage, e.what());
  } catch (...) {
    // The journal refused the write outright: the store is stopping.
    return store_failure(error);
  }
}

}  // namespace

Submitter::Submitter(QueueManager& queues, PostToCore post_to_core)
    : queues_(queues), post_to_core_(std::move(post_to_core)) {}

void Submitter::submit(const google::protobuf::Message& message, double ttl_s, Done done) {
  // Shared with the journal's completion, and still ours to call when
  // journal_new throws before it hands the completion to the journal.
  auto answer = std::make_shared<Done>(std::move(done));
  // Set once the completion runs: a journal that completes inline (in
  // tests, MemoryJournal) runs it inside journal_new, and whatever it
  // throws then is not a refusal to answer a second time.
  auto completing = std::make_shared<std::atomic<bool>>(false);
  // Refused before anything was stored: answered once the lock is released,
  // so that the answer never runs while this holds up a LoadDefinitions.
  std::optional<SubmitResult> refusal;
  {
    auto stable = types_stable();
    try {
      queues_.journal_new(message, ttl_s, [this, answer, completing](QueuedMessage queued, std::exception_ptr error) {
        completing->store(true);
        // On the store writer's thread: hand on quickly, never wait.
        if (error) {
          (*answer)(store_failure(error));
          return;
        }
        auto durable = std::make_shared<QueuedMessage>(std::move(queued));
        post_to_core_([this, durable, answer] { accept(std::move(*durable), *answer); });
      });
    } catch (...) {
      if (completing->load()) throw;
      refusal = refusal_of(std::current_exception());
    }
  }
  if (refusal) (*answer)(std::move(*refusal));
}

void Submitter::accept(QueuedMessage message, const Done& done) {
  ACOMMS_ASSERT_CORE_THREAD();
  const int64_t id = message.record.id;
  const std::string type = message.record.type;
  if (!queues_.accept(std::move(message))) {
    // The queue filled while this message was being stored: it was stored,
    // and accept() dropped it again with an event.
    const Queue* queue = queues_.find_queue(type);
    done(refused(Error::kQueueFull, queue ? queue_full_text(*queue) : "queue " + type + " is full"));
    return;
  }
  done({Error::kNone, id, {}});
}

}  // namespace acomms::queue
