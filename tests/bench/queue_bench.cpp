// Frame building under load: 100 DCCL types with 1,000 queued messages each,
// one 256-byte frame per build (a Micro-Modem rate-5 frame). Goal (issue:
// queues): under 100 us per frame.
//
//   build/tests/bench/queue_bench

#include <benchmark/benchmark.h>
#include <google/protobuf/text_format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <stdexcept>

#include "queue/queue_manager.h"
#include "queue/submitter.h"

namespace {

namespace fs = std::filesystem;
using namespace acomms;

constexpr int kTypes = 100;
constexpr int kPerType = 1000;
constexpr double kStart = 1'700'000'000;

// Durability is measured elsewhere (journal_bench); here it would only add
// noise, so events go nowhere.
class NullJournal final : public queue::MessageJournal {
 public:
  using queue::MessageJournal::append;
  void append(queue::JournalMessage, Appended appended) override { appended(++next_id_, nullptr); }
  void record(const queue::QueueEvent&) override {}
  std::vector<queue::JournalMessage> load() override { return {}; }
  std::vector<queue::QueueEvent> received_since(double) override { return {}; }
  std::vector<queue::QueueEvent> authenticated_since(double) override { return {}; }
  std::vector<queue::RoutedIdentity> routed_since(double) override { return {}; }
  void flush() override {}
  int64_t last_received_seq() override { return 0; }
  void when_committed(Committed committed) override { committed(nullptr); }
  uint64_t events_not_stored() const override { return 0; }

 private:
  int64_t next_id_ = 0;
};

struct Fixture {
  Fixture() {
    fs::path dir = fs::temp_directory_path() / ("acomms-queue-bench-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream proto(dir / "bench.proto");
    proto << "syntax = \"proto2\";\nimport \"dccl/option_extensions.proto\";\npackage bench;\n";
    for (int i = 1; i <= kTypes; ++i) {
      proto << "message T" << i << " {\n"
            << "  option (dccl.msg) = { codec_version: 4 id: " << i << " max_bytes: 32 };\n"
            << "  required int32 dest = 1 [(dccl.field) = { min: 0 max: 30 }];\n"
            << "  required int32 value = 2 [(dccl.field) = { min: 0 max: 100000 }];\n"
            << "  required double x = 3 [(dccl.field) = { min: -10000 max: 10000 precision: 1 }];\n}\n";
    }
    proto.close();
    codec.load((dir / "bench.proto").string(), {ACOMMS_PROTO_DIR});
    fs::remove_all(dir);

    v1::QueueConfig config;
    config.mutable_defaults()->set_max_queue(kPerType);
    // Long enough that nothing expires however many iterations run.
    config.mutable_defaults()->set_ttl_s(1e9);
    for (int i = 1; i <= kTypes; ++i) {
      auto* entry = config.add_type();
      entry->set_type("bench.T" + std::to_string(i));
      entry->mutable_policy()->set_value_base(1 + i % 5);
      entry->mutable_roles()->set_destination_field("dest");
    }
    manager = std::make_unique<queue::QueueManager>(codec, config, 1, clock, journal);
    // This thread is the core: a submit is queued when submit() returns.
    queue::Submitter submitter(*manager, [](std::function<void()> work) { work(); });
    std::string refusal;
    for (int i = 1; i <= kTypes; ++i) {
      auto message = codec.new_message("bench.T" + std::to_string(i));
      for (int n = 0; n < kPerType; ++n) {
        google::protobuf::TextFormat::ParseFromString(
            "dest: 2 value: " + std::to_string(n) + " x: " + std::to_string(n % 997), message.get());
        submitter.submit(*message, 0, [&refusal](const queue::SubmitResult& result) {
          if (!result.ok()) refusal = result.text;
        });
      }
    }
    if (!refusal.empty()) throw std::runtime_error("bench fixture: a submit was refused: " + refusal);
  }

  dccl::Codec codec;
  core::SimulatedClock clock{core::Clock::time_point(std::chrono::seconds(static_cast<int64_t>(kStart)))};
  NullJournal journal;
  std::unique_ptr<queue::QueueManager> manager;
};

void BM_BuildFrame(benchmark::State& state) {
  static Fixture fixture;
  queue::DataRequest request{queue::kAnyDestination, 256, 1, true};
  size_t messages = 0;
  for (auto _ : state) {
    // Each slot comes a second later. No ack arrives, so the next build
    // first puts the previous frame's messages back: the queues stay full.
    fixture.clock.advance(std::chrono::seconds(1));
    auto frames = fixture.manager->build_frames(request);
    messages += frames.empty() ? 0 : frames[0].message_ids.size();
    benchmark::DoNotOptimize(frames);
  }
  state.counters["messages_per_frame"] =
      benchmark::Counter(static_cast<double>(messages) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_BuildFrame)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
