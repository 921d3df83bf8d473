#include "queue/durable_receipts.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <memory>
#include <string>

#include "store/store_error.h"

namespace acomms::queue {

namespace {

void not_stored(const std::string& why) {
  spdlog::error("received messages not stored ({}): no ACK sent for them, the sender will send again", why);
}

}  // namespace

WhenStored when_stored(MessageJournal& journal) {
  // Failures the chain's previous call already answered for. Touched only
  // in the commit callbacks, which run one at a time, in order.
  auto answered = std::make_shared<uint64_t>(journal.events_not_stored());
  return [&journal, answered](MessageJournal::Committed committed) {
    // Commits complete in order: once this empty request is done, every
    // event recorded before it is done too, stored or failed. A failure in
    // its own batch fails this request; one in an earlier batch only shows
    // in the journal's count.
    journal.when_committed([&journal, answered, committed = std::move(committed)](std::exception_ptr error) {
      const uint64_t failed = journal.events_not_stored();
      const uint64_t newly_failed = failed - *answered;
      *answered = failed;
      if (!error && newly_failed > 0) {
        error = std::make_exception_ptr(
            store::StoreError(std::to_string(newly_failed) + " event(s) recorded before it failed to commit"));
      }
      committed(error);
    });
  };
}

AfterReceiptsDurable durable_receipts(MessageJournal& journal, PostToCore post) {
  return [stored = when_stored(journal), post = std::move(post)](Task then) {
    try {
      stored([post, then = std::move(then)](std::exception_ptr error) {
        if (!error) return post(then);
        try {
          std::rethrow_exception(error);
        } catch (const std::exception& e) {
          not_stored(e.what());
        } catch (...) {
          not_stored("unknown failure");
        }
      });
    } catch (const std::exception& e) {  // the writer has stopped
      not_stored(e.what());
    }
  };
}

}  // namespace acomms::queue
