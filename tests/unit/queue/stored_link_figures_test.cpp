// Link figures in the event log (migrations/0008_link_figures.sql): the
// figures of the transmission that carried a received message go from the
// link (link::link_figures) through QueueManager::receive into a real
// SQLite store with the message's received event, and come back from the
// EventLogReader (Subscribe's replay, Events) byte for byte. Events without
// figures, and received events written by a store at migration 0007, come
// back without them, never as an error.

#include <google/protobuf/text_format.h>
#include <google/protobuf/util/message_differencer.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/link_figures.pb.h"
#include "core/clock.h"
#include "dccl/codec.h"
#include "link/link_figures.h"
#include "queue/event_log_reader.h"
#include "queue/queue_manager.h"
#include "queue/sqlite_journal.h"
#include "store/group_commit_writer.h"
#include "store/migration.h"
#include "store/sqlite.h"
#include "store/store.h"
#include "store_fixture.h"

namespace acomms::queue {
namespace {

namespace fs = std::filesystem;
namespace pb = google::protobuf;

constexpr double kStart = 1'700'000'000;
constexpr int32_t kOwnId = 1;

constexpr const char* kProto = R"(syntax = "proto2";
import "dccl/option_extensions.proto";
package lf;
message Status {
  option (dccl.msg) = { codec_version: 4 id: 2 max_bytes: 16 };
  optional int32 src = 1 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 dest = 2 [(dccl.field) = { min: 0 max: 30 }];
  optional int32 value = 3 [(dccl.field) = { min: 0 max: 1000 }];
}
)";

// A PSK packet from modem 2 as the Micro-Modem driver reports it ($CACST).
v1::ModemTransmission psk_reception() {
  v1::ModemTransmission t;
  EXPECT_TRUE(pb::TextFormat::ParseFromString(
      "src: 2 dest: 1 rate: 5 type: DATA link_quality: \"snr 12.5 dB\" "
      "figures { snr_in_db: 12.5 snr_out_db: 9.25 signal_level_db: 131 mse_db: -14.5 doppler_mps: 0.3 "
      "packet_type: 3 frames: 8 bad_frames: 1 noise_db: 70 psk_error: 2 }",
      &t));
  return t;
}

std::string figures_bytes(const v1::ModemTransmission& t) { return link::link_figures(t).SerializeAsString(); }

v1::LinkFigures parsed(const std::optional<std::string>& bytes) {
  v1::LinkFigures figures;
  EXPECT_TRUE(bytes.has_value());
  EXPECT_TRUE(figures.ParseFromString(bytes.value_or("")));
  return figures;
}

class StoredLinkFiguresTest : public acomms::testing::StoreFixture {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "lf.proto") << kProto;
    codec_.load((dir_ / "lf.proto").string());
  }
  void TearDown() override {
    close();
  }

  std::string data_dir() const { return (dir_ / "data").string(); }

  void open() {
    open_store(data_dir());
    v1::QueueConfig config;
    EXPECT_TRUE(pb::TextFormat::ParseFromString(
        "type { type: \"lf.Status\" roles { source_field: \"src\" destination_field: \"dest\" } }", &config));
    manager_ = std::make_unique<QueueManager>(codec_, config, kOwnId, clock_, *journal_);
    manager_->restore();
    reader_ = std::make_unique<EventLogReader>(store_->db().path());
  }
  void close() {
    reader_.reset();
    manager_.reset();
    close_store();
  }

  std::string status(int value) {
    auto m = codec_.new_message("lf.Status");
    EXPECT_TRUE(pb::TextFormat::ParseFromString("src: 2 dest: 1 value: " + std::to_string(value), m.get()));
    return codec_.encode(*m);
  }

  std::vector<StoredReceived> replay() {
    journal_->flush();
    return reader_->received_after(0, {}, std::nullopt, 100);
  }

  dccl::Codec codec_;
  core::SimulatedClock clock_{core::Clock::time_point(std::chrono::seconds(static_cast<int64_t>(kStart)))};
  std::unique_ptr<QueueManager> manager_;
  std::unique_ptr<EventLogReader> reader_;
};

TEST_F(StoredLinkFiguresTest, EachMessageOfAReceptionIsReplayedWithTheFiguresItArrivedWith) {
  open();
  const v1::ModemTransmission t = psk_reception();
  ASSERT_EQ(manager_->receive(status(7) + status(8), t.src(), figures_bytes(t)).size(), 2u);

  std::vector<StoredReceived> page = replay();
  ASSERT_EQ(page.size(), 2u);
  for (const StoredReceived& stored : page) {
    v1::LinkFigures figures = parsed(stored.link_figures);
    EXPECT_TRUE(pb::util::MessageDifferencer::Equals(figures, link::link_figures(t))) << figures.DebugString();
    EXPECT_EQ(figures.transmission_src(), 2);
    EXPECT_EQ(figures.rate(), 5);
    EXPECT_EQ(figures.packet_type(), 3);  // PSK
    EXPECT_DOUBLE_EQ(figures.snr_in_db(), 12.5);
    EXPECT_DOUBLE_EQ(figures.snr_out_db(), 9.25);
    EXPECT_DOUBLE_EQ(figures.signal_level_db(), 131);
    EXPECT_DOUBLE_EQ(figures.mse_db(), -14.5);
    EXPECT_EQ(figures.bad_frames(), 1u);
    EXPECT_FALSE(figures.has_delay_spread_s()) << "the modem gave none";
  }
  EXPECT_EQ(page[1].seq, page[0].seq + 1);
}

TEST_F(StoredLinkFiguresTest, TheFiguresSurviveARestartAndEventsShowThemOnReceivedEventsOnly) {
  open();
  const v1::ModemTransmission t = psk_reception();
  ASSERT_EQ(manager_->receive(status(7), t.src(), figures_bytes(t)).size(), 1u);
  journal_->flush();
  close();
  open();

  ASSERT_EQ(replay().size(), 1u);
  EventQuery all;
  EventPage page = reader_->query(all);
  ASSERT_EQ(page.events.size(), 1u);
  EXPECT_EQ(page.events[0].event.kind, QueueEventKind::kReceived);
  EXPECT_EQ(parsed(page.events[0].event.link_figures).snr_in_db(), 12.5);
  // An event of another kind carries none.
  QueueEvent sent;
  sent.kind = QueueEventKind::kSent;
  sent.time = kStart + 1;
  sent.type = "lf.Status";
  sent.message_id = 3;
  journal_->record(sent);
  journal_->flush();
  page = reader_->query(all);
  ASSERT_EQ(page.events.size(), 2u);
  EXPECT_EQ(page.events[1].event.kind, QueueEventKind::kSent);
  EXPECT_FALSE(page.events[1].event.link_figures.has_value());
}

TEST_F(StoredLinkFiguresTest, APacketEventKeepsItsPredictionAndOutcomeAndIsNeverReplayedAsAMessage) {
  open();
  v1::ModemTransmission t = psk_reception();
  t.mutable_figures()->set_predicted_tl_db(61.5);
  t.mutable_figures()->set_predicted_snr_db(20.5);
  v1::LinkFigures figures = link::link_figures(t);
  figures.set_decoded(false);
  manager_->record_packet(2, 1, figures.SerializeAsString());
  journal_->flush();
  close();
  open();

  EXPECT_TRUE(replay().empty()) << "a packet is not a message: nothing to hand a subscriber";
  EventQuery packets;
  packets.kinds = {"packet"};
  EventPage page = reader_->query(packets);
  ASSERT_EQ(page.events.size(), 1u);
  const QueueEvent& e = page.events[0].event;
  EXPECT_EQ(e.kind, QueueEventKind::kPacket);
  EXPECT_EQ(e.src, 2);
  EXPECT_EQ(e.dest, 1);
  EXPECT_EQ(e.type, "");
  EXPECT_DOUBLE_EQ(e.time, kStart);
  const v1::LinkFigures stored = parsed(e.link_figures);
  EXPECT_DOUBLE_EQ(stored.predicted_tl_db(), 61.5);
  EXPECT_DOUBLE_EQ(stored.predicted_snr_db(), 20.5);
  EXPECT_DOUBLE_EQ(stored.snr_in_db(), 12.5);
  ASSERT_TRUE(stored.has_decoded());
  EXPECT_FALSE(stored.decoded());
}

TEST_F(StoredLinkFiguresTest, NoFiguresIsStoredAsNoneAndAllDefaultFiguresAsFigures) {
  open();
  ASSERT_EQ(manager_->receive(status(1), 2).size(), 1u);
  // A transmission from "modem 0" at rate 0 with nothing measured: every
  // field at its default, zero bytes, yet figures the link did give.
  v1::ModemTransmission bare;
  bare.set_src(0);
  ASSERT_EQ(figures_bytes(bare), "");
  ASSERT_EQ(manager_->receive(status(2), 0, figures_bytes(bare)).size(), 1u);

  std::vector<StoredReceived> page = replay();
  ASSERT_EQ(page.size(), 2u);
  EXPECT_FALSE(page[0].link_figures.has_value());
  ASSERT_TRUE(page[1].link_figures.has_value()) << "a zero-length blob read back as NULL";
  EXPECT_EQ(*page[1].link_figures, "");
}

// A store written by a daemon at migration 0007, with received events of its
// own, opened by this build: 0008 is applied, the old events replay (with
// their bytes, without figures), and new ones keep theirs.
TEST_F(StoredLinkFiguresTest, ReceivedEventsOfAStoreAtMigration0007ReplayWithoutFigures) {
  fs::create_directories(data_dir());
  {
    store::Database db((fs::path(data_dir()) / store::kStoreFileName).string());
    std::vector<store::Migration> up_to_7;
    for (const store::Migration& m : store::known_migrations()) {
      if (m.version <= 7) up_to_7.push_back(m);
    }
    ASSERT_EQ(up_to_7.size(), 7u);
    store::migrate(db, up_to_7);
    ASSERT_EQ(store::schema_version(db), 7);
    const std::string old = status(5);
    store::Statement insert = db.prepare(
        "INSERT INTO event_log (time, kind, type, src, dest, detail, encoded, seq) "
        "VALUES (?, 'received', 'lf.Status', 2, 1, '', ?, 1)");
    insert.bind_double(1, kStart - 10).bind_blob(2, old);
    insert.step();
    db.exec("INSERT INTO event_log (time, kind, type, message_id, detail) VALUES (" + std::to_string(kStart - 5) +
            ", 'queued', 'lf.Status', 4, '')");
    db.exec("UPDATE event_sequence SET last = 1 WHERE name = 'received'");
  }

  open();
  EXPECT_EQ(store_->migration().from_version, 7);
  // Migrated up to the newest (0008 and whatever followed it).
  EXPECT_EQ(store_->schema_version(), store::known_migrations().back().version);
  EXPECT_EQ(manager_->last_received_seq(), 1);
  const v1::ModemTransmission t = psk_reception();
  ASSERT_EQ(manager_->receive(status(6), t.src(), figures_bytes(t)).size(), 1u);

  std::vector<StoredReceived> page = replay();
  ASSERT_EQ(page.size(), 2u);
  EXPECT_EQ(page[0].seq, 1);
  EXPECT_EQ(page[0].encoded, status(5));
  EXPECT_FALSE(page[0].link_figures.has_value());
  EXPECT_EQ(page[1].seq, 2);
  EXPECT_EQ(parsed(page[1].link_figures).snr_out_db(), 9.25);

  EventPage events = reader_->query(EventQuery{});
  ASSERT_EQ(events.events.size(), 3u);
  for (size_t i = 0; i < 2; ++i) EXPECT_FALSE(events.events[i].event.link_figures.has_value()) << i;
  EXPECT_TRUE(events.events[2].event.link_figures.has_value());
}

}  // namespace
}  // namespace acomms::queue
