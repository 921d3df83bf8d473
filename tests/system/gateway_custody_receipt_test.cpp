// Gateways: custody on a satellite link whose modem ACKs in hardware
// (route/custody_receipt.h). The shore (1) and the buoy (2) share "sat",
// whose modems ACK whatever the buoy does with a frame (modem_ack_driver.h);
// the buoy and the vehicle (3) share "acoustic" (software ACKs). The
// vehicle starts late: until then the buoy has no route to it and holds
// what it took, so its custody (routing.max_custody) stays full.

#include "gateway_network.h"
#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/store.h"

namespace acomms::gateway_test {
namespace {

using namespace std::chrono_literals;

// The shore's real store (SQLite, migrated, group commits), its appends
// waited for on the caller's thread: the simulated network runs on one.
class SqliteStore final : public queue::MessageJournal {
 public:
  explicit SqliteStore(const std::filesystem::path& dir) : store_(dir.string()), writer_(store_.db()), inner_(writer_) {}
  using MessageJournal::append;
  void append(queue::JournalMessage message, Appended appended) override {
    int64_t id = 0;
    std::exception_ptr error;
    try {
      id = inner_.append(std::move(message));
    } catch (...) {
      error = std::current_exception();
    }
    appended(id, error);
  }
  void record(const queue::QueueEvent& event) override { inner_.record(event); }
  std::vector<queue::JournalMessage> load() override { return inner_.load(); }
  std::vector<queue::QueueEvent> received_since(double since) override { return inner_.received_since(since); }
  std::vector<queue::QueueEvent> authenticated_since(double since) override {
    return inner_.authenticated_since(since);
  }
  std::vector<queue::RoutedIdentity> routed_since(double now) override { return inner_.routed_since(now); }
  int64_t last_received_seq() override { return inner_.last_received_seq(); }
  void when_committed(Committed committed) override {
    inner_.flush();
    committed(nullptr);
  }
  uint64_t events_not_stored() const override { return inner_.events_not_stored(); }
  void flush() override { inner_.flush(); }

 private:
  store::Store store_;
  store::GroupCommitWriter writer_;
  queue::SqliteJournal inner_;
};

// The shore's commands live two hours: long enough for a back-off or two.
constexpr const char* kLongCommandQueues =
    R"(type { type: "net.Status" roles { source_field: "src" destination_field: "dest" } }
       type { type: "net.Command" policy { ttl_s: 7200 } roles { source_field: "src" destination_field: "dest" } })";

class CustodyReceipts : public GatewayNetwork {
 protected:
  void build_shore_modem_acks() { build_shore_modem_acks(shore_journal_); }
  void build_shore_modem_acks(queue::MessageJournal& journal) {
    shore_ = std::make_unique<GatewayNode>(
        1, std::vector{status_proto(), command_proto()}, kLongCommandQueues,
        R"(route { dest: 3 next_hop: 2 link: "sat" })",
        std::vector<LinkSpec>{{"sat", sat_, kSatCycle, 0, /*modem_acks=*/true}}, scheduler_, journal);
  }
  void build_buoy_modem_acks(const std::string& routing) {
    buoy_ = std::make_unique<GatewayNode>(
        2, std::vector{status_proto()}, kQueues, routing,
        std::vector<LinkSpec>{{"sat", sat_, kSatCycle, 0, true}, {"acoustic", acoustic_, kAcousticCycle}},
        scheduler_, buoy_journal_);
  }
  size_t shore_commands_queued() const { return shore_->queues->find_queue("net.Command")->size(); }
  // Commands received by the vehicle with `code`.
  size_t vehicle_got(int code) {
    size_t n = 0;
    for (const auto& r : vehicle_->received) {
      if (r.type != "net.Command") continue;
      for (const auto& m : vehicle_->codec.decode(r.encoded)) {
        n += m->GetReflection()->GetInt32(*m, m->GetDescriptor()->FindFieldByName("code")) == code;
      }
    }
    return n;
  }
  // Runs `seconds`, checking every slot that the buoy never holds more
  // than `bound`.
  void run_within_bound(int seconds, size_t bound) {
    for (int t = 0; t < seconds; t += 10) {
      scheduler_.run_for(10s);
      ASSERT_LE(buoy_->custody_held(), bound) << "after " << t << " s";
    }
  }
  static bool carries_bytes(const v1::ModemTransmission& t) {
    for (const std::string& frame : t.frame()) {
      if (!frame.empty()) return true;
    }
    return false;
  }
};

TEST_F(CustodyReceipts, FullCustodyBehindAModemAckLinkLeavesTheMessageWithTheShoreAndDeliversItOnceLater) {
  build_shore_modem_acks();
  build_buoy_modem_acks("max_custody: 1");
  build_vehicle();
  shore_->start();
  buoy_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 1");
  scheduler_.run_for(120s);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  EXPECT_EQ(shore_commands_queued(), 0u) << "custody of the first was taken: the shore forgot it";

  shore_->submit("net.Command", "src: 1 dest: 3 code: 2");
  run_within_bound(120, 1);
  EXPECT_EQ(buoy_->custody_held(), 1u) << "not stored over routing.max_custody";
  EXPECT_GE(buoy_->forwarder->stats().custody_refused, 1u);
  EXPECT_EQ(shore_commands_queued(), 1u) << "the modem ACKed it, but the shore keeps it";
  ASSERT_EQ(shore_->forwarder->held_for_receipt().size(), 1u);
  EXPECT_TRUE(shore_->forwarder->held_for_receipt().begin()->second.refused);

  // Offered again after its back-off, refused again, never lost.
  run_within_bound(2000, 1);
  EXPECT_GE(shore_->forwarder->stats().custody_reoffered, 1u);
  EXPECT_GE(buoy_->forwarder->stats().custody_refused, 2u);
  EXPECT_EQ(shore_commands_queued(), 1u);

  // The vehicle comes: custody drains, the second is taken and delivered.
  vehicle_->start();
  run_within_bound(4000, 1);
  EXPECT_EQ(vehicle_got(1), 1u);
  EXPECT_EQ(vehicle_got(2), 1u);
  EXPECT_EQ(shore_commands_queued(), 0u);
  EXPECT_TRUE(shore_->forwarder->held_for_receipt().empty());
}

TEST_F(CustodyReceipts, ALostCustodyReceiptLeadsToAReofferAnsweredTakenWithoutASecondCopy) {
  build_shore_modem_acks();
  build_buoy_modem_acks("");
  build_vehicle();
  // The buoy's first frame to the shore with anything in it (the receipt).
  shore_->links[0]->modem->drop = [this](const v1::ModemTransmission& t) {
    return t.src() == 2 && carries_bytes(t) && shore_->links[0]->modem->dropped == 0;
  };
  shore_->start();
  buoy_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 5");
  scheduler_.run_for(120s);
  ASSERT_EQ(shore_->links[0]->modem->dropped, 1);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  EXPECT_EQ(buoy_->forwarder->stats().custody_receipts_sent, 1u);
  EXPECT_EQ(shore_commands_queued(), 1u) << "no receipt yet: kept past the modem's ACK";

  scheduler_.run_for(std::chrono::seconds(static_cast<int64_t>(route::Forwarder::receipt_wait_s(1)) + 120));
  EXPECT_EQ(shore_->forwarder->stats().custody_reoffered, 1u);
  EXPECT_EQ(buoy_->forwarder->stats().custody_copies, 1u) << "the copy was known";
  EXPECT_EQ(buoy_->forwarder->stats().custody_receipts_sent, 2u);
  EXPECT_EQ(shore_commands_queued(), 0u) << "the second receipt ended it";
  EXPECT_EQ(buoy_->custody_held(), 1u);
  EXPECT_EQ(buoy_journal_.load().size(), 1u) << "stored once";

  vehicle_->start();
  scheduler_.run_for(900s);
  EXPECT_EQ(vehicle_got(5), 1u);
  EXPECT_EQ(buoy_->custody_held(), 0u);
}

TEST_F(CustodyReceipts, AShoreRestartedWhileAwaitingACustodyReceiptOffersTheMessageAgain) {
  auto store = std::make_unique<SqliteStore>(dir_ / "shore");
  build_shore_modem_acks(*store);
  build_buoy_modem_acks("");
  build_vehicle();
  shore_->links[0]->modem->drop = [](const v1::ModemTransmission& t) { return t.src() == 2 && carries_bytes(t); };
  shore_->start();
  buoy_->start();
  scheduler_.run_for(60s);
  shore_->submit("net.Command", "src: 1 dest: 3 code: 9");
  scheduler_.run_for(120s);
  ASSERT_EQ(buoy_->custody_held(), 1u);
  ASSERT_EQ(shore_->forwarder->held_for_receipt().size(), 1u);

  // Killed while it waits, its store closed and opened again.
  shore_.reset();
  store.reset();
  store = std::make_unique<SqliteStore>(dir_ / "shore");
  build_shore_modem_acks(*store);
  EXPECT_EQ(shore_commands_queued(), 1u) << "the store kept it";
  shore_->start();
  scheduler_.run_for(120s);  // far less than the receipt wait: offered at once
  EXPECT_EQ(shore_commands_queued(), 0u) << "offered again, and the buoy's receipt ended it";
  EXPECT_EQ(buoy_->forwarder->stats().custody_copies, 1u);
  EXPECT_EQ(buoy_journal_.load().size(), 1u) << "stored once at the buoy";
  store->flush();
  EXPECT_TRUE(store->load().empty()) << "the receipt's acked event removed it from the shore's store";

  vehicle_->start();
  scheduler_.run_for(900s);
  EXPECT_EQ(vehicle_got(9), 1u);
  shore_.reset();  // before its store
}

}  // namespace
}  // namespace acomms::gateway_test
