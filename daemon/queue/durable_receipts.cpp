#include "queue/durable_receipts.h"

#include <spdlog/spdlog.h>

#include <exception>
#include <string>

namespace acomms::queue {

namespace {

void not_stored(const std::string& why) {
  spdlog::error("received messages not stored ({}): no ACK sent for them, the sender will send again", why);
}

}  // namespace

AfterReceiptsDurable durable_receipts(MessageJournal& journal, PostToCore post) {
  return [&journal, post = std::move(post)](Task then) {
    try {
      // Commits complete in order: once this empty one is done, every
      // event recorded before it is on disk.
      journal.when_committed([post, then = std::move(then)](std::exception_ptr error) {
        if (!error) return post(then);
        try {
          std::rethrow_exception(error);
        } catch (const std::exception& e) {
          not_stored(e.what());
        }
      });
    } catch (const std::exception& e) {  // the writer has stopped
      not_stored(e.what());
    }
  };
}

}  // namespace acomms::queue
