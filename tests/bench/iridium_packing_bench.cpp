// MO packing efficiency on the Iridium link: payload bytes per byte paid.
//
// RockBLOCK bills one credit per started 50 bytes of an MO (spec §6.4), so
// a 20-byte DCCL message sent alone pays for 50. The Iridium driver asks
// the queues for one frame of up to 340 bytes (driver.iridium.max_mo_bytes)
// and the queues pack several DCCL messages into it (queue/frame_building).
// This prints, for a vehicle surfacing with a backlog of N messages (the
// example network's Status and CTD, real DCCL encodings, built by the real
// QueueManager): MOs (sessions), credits, bytes paid, and payload per byte
// paid, for one message per MO against packing to 340 and to 100 bytes.
//
//   build/tests/bench/iridium_packing_bench           (figures)
//   build/tests/bench/iridium_packing_bench --smoke   (what ctest runs)

#include <google/protobuf/text_format.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "queue/memory_journal.h"
#include "queue/queue_manager.h"
#include "queue/submitter.h"

namespace {

using namespace acomms;

constexpr size_t kCreditBytes = 50;  // RockBLOCK: one credit per started 50 bytes
constexpr int kVehicle = 2;
constexpr int kShore = 1;

size_t credits(size_t mo_bytes) { return (mo_bytes + kCreditBytes - 1) / kCreditBytes; }

struct Cost {
  size_t mos = 0;
  size_t payload = 0;
  size_t credits = 0;
  double per_byte_paid() const { return payload == 0 ? 0 : double(payload) / double(credits * kCreditBytes); }
};

// A node's queues holding a backlog of `n` messages for the shore: two
// Statuses for every CTD cast, with varied values.
struct Backlog {
  explicit Backlog(int n) {
    codec.load(ACOMMS_SOURCE_DIR "/examples/messages.proto", {ACOMMS_PROTO_DIR});
    v1::QueueConfig config;
    config.mutable_defaults()->set_max_queue(1000);
    config.mutable_defaults()->set_ttl_s(86400);
    for (const char* type : {"example.Status", "example.CTD"}) {
      auto* entry = config.add_type();
      entry->set_type(type);
      entry->mutable_roles()->set_source_field("src");
      entry->mutable_roles()->set_destination_field("dest");
      entry->mutable_roles()->set_timestamp_field("time");
    }
    manager = std::make_unique<queue::QueueManager>(codec, config, kVehicle, clock, journal);
    queue::Submitter submitter(*manager, [](std::function<void()> work) { work(); });
    std::string refusal;
    for (int i = 0; i < n; ++i) {
      const bool ctd = i % 3 == 2;
      auto message = codec.new_message(ctd ? "example.CTD" : "example.Status");
      const std::string common = "src: 2 dest: 1 time: " + std::to_string(1'700'000'000 + 60 * i) + " ";
      const std::string fields =
          ctd ? "conductivity: " + std::to_string(3.1 + 0.01 * i) + " temperature: " + std::to_string(11.5 - 0.1 * i) +
                    " depth: " + std::to_string(5 + i % 40) + " salinity: 34.7"
              : "x: " + std::to_string(120 + 7 * i) + " y: " + std::to_string(-40 - 3 * i) +
                    " depth: 0 heading: " + std::to_string(i * 37 % 360) + " speed: 1.5 battery: " +
                    std::to_string(90 - i % 50) + " mode: SURFACING seq: " + std::to_string(i);
      if (!google::protobuf::TextFormat::ParseFromString(common + fields, message.get())) {
        throw std::runtime_error("bench: bad message text");
      }
      encoded.push_back(codec.encode(*message));
      submitter.submit(*message, 0, [&refusal](const queue::SubmitResult& result) {
        if (!result.ok()) refusal = result.text;
      });
    }
    if (!refusal.empty()) throw std::runtime_error("bench: a submit was refused: " + refusal);
  }

  // What the driver's data requests take out, one MO each, at `max_mo_bytes`.
  Cost drain(uint32_t max_mo_bytes) {
    Cost cost;
    while (true) {
      auto frames = manager->build_frames({kShore, max_mo_bytes, 1, true});
      if (frames.empty()) break;
      ++cost.mos;
      cost.payload += frames[0].bytes.size();
      cost.credits += credits(frames[0].bytes.size());
      manager->on_ack(frames[0].frame_id);  // the session's success
    }
    return cost;
  }

  dccl::Codec codec;
  core::SimulatedClock clock{core::Clock::time_point(std::chrono::seconds(1'700'010'000))};
  queue::MemoryJournal journal;
  std::unique_ptr<queue::QueueManager> manager;
  std::vector<std::string> encoded;
};

Cost one_per_mo(const std::vector<std::string>& encoded) {
  Cost cost;
  for (const std::string& message : encoded) {
    ++cost.mos;
    cost.payload += message.size();
    cost.credits += credits(message.size());
  }
  return cost;
}

void row(int n, const char* how, const Cost& cost) {
  std::printf("%5d  %-22s %5zu %8zu %8zu %10zu   %.3f\n", n, how, cost.mos, cost.payload, cost.credits,
              cost.credits * kCreditBytes, cost.per_byte_paid());
}

}  // namespace

int main(int argc, char** argv) {
  const bool smoke = argc > 1 && std::strcmp(argv[1], "--smoke") == 0;
  std::vector<int> backlogs = smoke ? std::vector<int>{10} : std::vector<int>{1, 3, 10, 30, 100};
  std::printf("RockBLOCK credit = %zu bytes (spec §6.4). Payload per byte paid, higher is better.\n", kCreditBytes);
  std::printf("%5s  %-22s %5s %8s %8s %10s   %s\n", "msgs", "MO building", "MOs", "payload", "credits", "bytes paid",
              "payload/paid");
  for (int n : backlogs) {
    Cost alone = one_per_mo(Backlog(n).encoded);
    Cost packed = Backlog(n).drain(340);
    Cost packed_100 = Backlog(n).drain(100);
    row(n, "one message per MO", alone);
    row(n, "packed, max_mo_bytes 340", packed);
    row(n, "packed, max_mo_bytes 100", packed_100);
    if (packed.payload != alone.payload || packed_100.payload != alone.payload) {
      std::fprintf(stderr, "packing lost or duplicated bytes: %zu / %zu vs %zu\n", packed.payload, packed_100.payload,
                   alone.payload);
      return 1;
    }
    if (packed.credits > alone.credits) {
      std::fprintf(stderr, "packing cost more credits than one message per MO\n");
      return 1;
    }
  }
  return 0;
}
