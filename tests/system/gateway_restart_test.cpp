// Gateways across an origin's restart (the network: gateway_network.h):
// the shore's notes of what awaits an end-to-end ack are kept in a real
// SQLite store (route/route_journal.h, migrations/0014), closed and opened
// again with the shore, so a receipt that comes after the restart is still
// the receipt of its message.
//
// Shown: the shore hands a command to the buoy (hop ack) while the vehicle
// is away, is restarted, and then the vehicle's end-to-end ack comes back:
// the shore logs "delivered" for that message (its id, type and
// destination) and counts it; a command that expires in the buoy's custody
// after the shore's restart is logged "expired at node 2" for its message
// and counted as expired elsewhere (expired_remote), not in `expired`.

#include "gateway_network.h"
#include "route/route_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace acomms::gateway_test {
namespace {

using namespace std::chrono_literals;

// The first event of `kind` of message `message_id` (a copy: the journal
// hands out its events by value).
std::optional<queue::QueueEvent> event_of(const queue::MemoryJournal& journal, int64_t message_id,
                                          queue::QueueEventKind kind) {
  for (const queue::QueueEvent& e : journal.events()) {
    if (e.message_id == message_id && e.kind == kind) return e;
  }
  return std::nullopt;
}

class GatewayRestart : public GatewayNetwork {
 protected:
  ~GatewayRestart() override {
    shore_.reset();
    close_shore_store();
  }
  // The shore's store: opened before the shore is built, closed after it
  // is gone (as the daemon: forwarder, route journal, writer, store).
  void open_shore_store() {
    store_ = std::make_unique<store::Store>((dir_ / "shore").string());
    writer_ = std::make_unique<store::GroupCommitWriter>(store_->db());
    route_journal_ = std::make_unique<route::RouteJournal>(*writer_);
  }
  void close_shore_store() {
    route_journal_.reset();
    writer_.reset();  // commits what is queued, then stops
    store_.reset();
  }
  void build_shore_with_store(const std::string& queues) {
    shore_ = std::make_unique<GatewayNode>(1, std::vector{status_proto(), command_proto()}, queues,
                                           R"(route { dest: 3 next_hop: 2 link: "sat" })",
                                           std::vector<LinkSpec>{{"sat", sat_, kSatCycle}}, scheduler_,
                                           shore_journal_, route_journal_.get());
  }
  // The shore stops, is away `down`, and comes back on its store.
  void restart_shore(const std::string& queues, std::chrono::seconds down) {
    shore_.reset();
    close_shore_store();
    scheduler_.run_for(down);
    open_shore_store();
    build_shore_with_store(queues);
    shore_->start();
  }

  std::unique_ptr<store::Store> store_;
  std::unique_ptr<store::GroupCommitWriter> writer_;
  std::unique_ptr<route::RouteJournal> route_journal_;
};

TEST_F(GatewayRestart, TheEndToEndAckAfterTheOriginRestartedIsReportedAsTheAckOfItsMessage) {
  open_shore_store();
  build_shore_with_store(kCommandQueues);
  build_buoy(R"(route { dest: 3 next_hop: 3 link: "acoustic" })");  // the vehicle is away for now
  shore_->start();
  buoy_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 417");
  const int64_t id = shore_->queues->find_queue("net.Command")->messages().front().record.id;
  scheduler_.run_for(100s);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  ASSERT_TRUE(event_of(shore_journal_, id, queue::QueueEventKind::kAcked));  // the hop ack

  restart_shore(kCommandQueues, 120s);
  // The new shore knows what it sent in its last life.
  std::vector<route::RoutedSend> noted = shore_->forwarder->awaiting_end_to_end().list();
  ASSERT_EQ(noted.size(), 1u);
  EXPECT_EQ(noted.front().message_id, id);
  EXPECT_TRUE(noted.front().hop_acked);

  build_vehicle();
  vehicle_->start();
  scheduler_.run_for(600s);
  ASSERT_EQ(commands_received(*vehicle_), 1u);
  EXPECT_EQ(shore_->forwarder->stats().receipts_received, 1u);
  const std::optional<queue::QueueEvent> delivered = event_of(shore_journal_, id, queue::QueueEventKind::kDelivered);
  ASSERT_TRUE(delivered);
  EXPECT_EQ(delivered->detail, "delivered to node 3 (end-to-end ack)");
  EXPECT_EQ(delivered->type, "net.Command");
  EXPECT_EQ(delivered->dest, 3);
  EXPECT_EQ(shore_->queues->stats("net.Command").delivered, 1u);
  EXPECT_TRUE(shore_->forwarder->awaiting_end_to_end().list().empty());

  // The note went from the store too: a third life has none.
  restart_shore(kCommandQueues, 10s);
  EXPECT_TRUE(shore_->forwarder->awaiting_end_to_end().list().empty());
}

TEST_F(GatewayRestart, AnExpiryReportAfterTheOriginRestartedIsCountedAsExpiredElsewhere) {
  // net.Command lives 300 s; the vehicle never comes.
  const std::string queues =
      R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } }
         type { type: "net.Command" policy { ttl_s: 300 } roles { source_field: "src" destination_field: "dest" } })";
  open_shore_store();
  build_shore_with_store(queues);
  build_buoy(R"(route { dest: 3 next_hop: 3 link: "acoustic" })");
  shore_->start();
  buoy_->start();
  shore_->submit("net.Command", "src: 1 dest: 3 code: 5");
  const int64_t id = shore_->queues->find_queue("net.Command")->messages().front().record.id;
  scheduler_.run_for(100s);
  ASSERT_EQ(buoy_->custody_held(), 1u);

  restart_shore(queues, 60s);
  scheduler_.run_for(600s);
  EXPECT_EQ(buoy_->custody_held(), 0u);
  const std::optional<queue::QueueEvent> expired = event_of(shore_journal_, id, queue::QueueEventKind::kExpired);
  ASSERT_TRUE(expired);
  EXPECT_EQ(expired->detail, "expired at node 2");
  EXPECT_EQ(expired->type, "net.Command");
  const queue::QueueStats stats = shore_->queues->stats("net.Command");
  EXPECT_EQ(stats.expired_remote, 1u);
  EXPECT_EQ(stats.expired, 0u);  // its ttl did not run out in the shore's queue
  EXPECT_EQ(stats.delivered, 0u);
}

// The shore's own expiry stays in `expired`: a command with no route
// at all expires in its queue.
TEST_F(GatewayRestart, AMessageThatExpiresInItsOwnQueueIsCountedInExpiredOnly) {
  open_shore_store();
  shore_ = std::make_unique<GatewayNode>(
      1, std::vector{status_proto(), command_proto()},
      R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } }
         type { type: "net.Command" policy { ttl_s: 100 } roles { source_field: "src" destination_field: "dest" } })",
      "", std::vector<LinkSpec>{{"sat", sat_, kSatCycle}}, scheduler_, shore_journal_, route_journal_.get());
  shore_->start();
  shore_->submit("net.Command", "src: 1 dest: 7 code: 5");
  scheduler_.run_for(200s);
  const queue::QueueStats stats = shore_->queues->stats("net.Command");
  EXPECT_EQ(stats.expired, 1u);
  EXPECT_EQ(stats.expired_remote, 0u);
}

}  // namespace
}  // namespace acomms::gateway_test
