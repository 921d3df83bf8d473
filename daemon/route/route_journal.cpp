// The durable half of routing's memories (route_journal.h).
#include "route/route_journal.h"

#include <spdlog/spdlog.h>

namespace acomms::route {
namespace {

using store::Database;
using store::Statement;

constexpr std::string_view kSaveAwaiting =
    "INSERT OR REPLACE INTO route_awaiting (seq, message_id, type, dest, next_hop, sent_at, hop_acked, "
    "forget_after) VALUES (?, ?, ?, ?, ?, ?, ?, ?)";
constexpr std::string_view kEraseAwaiting = "DELETE FROM route_awaiting WHERE seq = ?";
constexpr std::string_view kForgetAwaiting = "DELETE FROM route_awaiting WHERE forget_after < ?";
constexpr std::string_view kLoadAwaiting =
    "SELECT seq, message_id, type, dest, next_hop, sent_at, hop_acked, forget_after FROM route_awaiting "
    "ORDER BY sent_at";
constexpr std::string_view kSaveLearned =
    "INSERT OR REPLACE INTO route_learned (dest, next_hop, link, source, last_confirmed) VALUES (?, ?, ?, ?, ?)";
constexpr std::string_view kLoadLearned =
    "SELECT dest, next_hop, link, source, last_confirmed FROM route_learned ORDER BY dest";

bool valid_id(int64_t id) { return id >= 1 && id <= 65535; }

// A cached statement is reset whichever way the work ends.
struct ResetOnExit {
  Statement& statement;
  ~ResetOnExit() { statement.reset(); }
};

}  // namespace

// The writes capture the writer, not this: they may run after the journal
// is gone (the writer commits what is queued before it stops).
void RouteJournal::save_awaiting(const RoutedSend& send) {
  writer_.post([&writer = writer_, send](Database&) {
    Statement& save = writer.prepared(kSaveAwaiting);
    ResetOnExit reset{save};
    save.bind(1, int64_t{send.message_id & 0xffff})
        .bind(2, send.message_id)
        .bind(3, send.type)
        .bind(4, int64_t{send.dest})
        .bind(5, int64_t{send.next_hop})
        .bind_double(6, send.sent_at)
        .bind(7, int64_t{send.hop_acked ? 1 : 0})
        .bind_double(8, send.forget_after);
    save.step();
  });
}

void RouteJournal::erase_awaiting(uint16_t seq) {
  writer_.post([&writer = writer_, seq](Database&) {
    Statement& erase = writer.prepared(kEraseAwaiting);
    ResetOnExit reset{erase};
    erase.bind(1, int64_t{seq});
    erase.step();
  });
}

std::vector<RoutedSend> RouteJournal::load_awaiting(double now) {
  return writer_
      .submit([now](Database& db) {
        Statement forget = db.prepare(kForgetAwaiting);
        forget.bind_double(1, now);
        forget.step();
        std::vector<RoutedSend> out;
        Statement query = db.prepare(kLoadAwaiting);
        while (query.step()) {
          RoutedSend send;
          send.message_id = query.column_int64(1);
          send.type = query.column_text(2);
          send.dest = static_cast<int32_t>(query.column_int64(3));
          send.next_hop = static_cast<int32_t>(query.column_int64(4));
          send.sent_at = query.column_double(5);
          send.hop_acked = query.column_int64(6) != 0;
          send.forget_after = query.column_double(7);
          if (send.message_id <= 0 || query.column_int64(0) != (send.message_id & 0xffff) || !valid_id(send.dest)) {
            spdlog::warn("route: stored note of message {} (seq {}) does not read as one: skipped", send.message_id,
                         query.column_int64(0));
            continue;
          }
          out.push_back(std::move(send));
        }
        return out;
      })
      .get();
}

void RouteJournal::save_learned(int32_t dest, const NextHop& next, double last_confirmed) {
  writer_.post([&writer = writer_, dest, next, last_confirmed](Database&) {
    Statement& save = writer.prepared(kSaveLearned);
    ResetOnExit reset{save};
    save.bind(1, int64_t{dest})
        .bind(2, int64_t{next.node})
        .bind(3, next.link)
        .bind(4, std::string_view(to_string(next.source)))
        .bind_double(5, last_confirmed);
    save.step();
  });
}

std::vector<StoredRoute> RouteJournal::load_learned() {
  return writer_
      .submit([](Database& db) {
        std::vector<StoredRoute> out;
        Statement query = db.prepare(kLoadLearned);
        while (query.step()) {
          StoredRoute route;
          const int64_t dest = query.column_int64(0);
          const int64_t node = query.column_int64(1);
          const std::string source = query.column_text(3);
          route.next.link = query.column_text(2);
          route.last_confirmed = query.column_double(4);
          if (source == to_string(RouteSource::kLearnedDirect)) {
            route.next.source = RouteSource::kLearnedDirect;
          } else if (source == to_string(RouteSource::kLearnedRelay)) {
            route.next.source = RouteSource::kLearnedRelay;
          } else {
            spdlog::warn("route: stored route to node {} has source \"{}\": skipped", dest, source);
            continue;
          }
          if (!valid_id(dest) || !valid_id(node)) {
            spdlog::warn("route: stored route to node {} through node {}: ids out of range, skipped", dest, node);
            continue;
          }
          route.dest = static_cast<int32_t>(dest);
          route.next.node = static_cast<int32_t>(node);
          out.push_back(std::move(route));
        }
        return out;
      })
      .get();
}

}  // namespace acomms::route
