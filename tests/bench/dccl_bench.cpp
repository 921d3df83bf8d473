// DCCL encode/decode speed, ns per message, for every type in the
// conformance schema (one representative message per type: the first vector
// line of that type). Goal (issue: DCCL codec): gv.NavigationReport under
// 800 ns to encode and 1100 ns to decode on a 2-core CI-class machine, ten
// times faster than the reference library.
//
//   build/tests/bench/dccl_bench --benchmark_filter=NavigationReport

#include <benchmark/benchmark.h>
#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "dccl/codec.h"

namespace {

using acomms::dccl::Codec;

struct Sample {
  std::unique_ptr<google::protobuf::Message> message;
  std::string bytes;
};

Codec& codec() {
  static Codec* instance = [] {
    auto* c = new Codec;
    c->load(ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto", {ACOMMS_PROTO_DIR});
    c->set_clock([] { return 1'700'000'000.0; });
    return c;
  }();
  return *instance;
}

// type name -> first message of that type in vectors.txt
std::map<std::string, Sample> load_samples() {
  std::map<std::string, Sample> samples;
  std::ifstream vectors(ACOMMS_SHARED_DIR "/conformance/dccl/vectors.txt");
  for (std::string line; std::getline(vectors, line);) {
    if (line.empty() || line[0] != '|') continue;
    size_t close = line.find('|', 1);
    std::string type = line.substr(1, close - 1);
    if (samples.count(type)) continue;
    std::string text = line.substr(close + 1, line.rfind(" => ") - close - 1);
    Sample sample;
    sample.message = codec().new_message(type);
    if (!google::protobuf::TextFormat::ParseFromString(text, sample.message.get())) continue;
    sample.bytes = codec().encode(*sample.message);
    samples.emplace(type, std::move(sample));
  }
  return samples;
}

}  // namespace

int main(int argc, char** argv) {
  static std::map<std::string, Sample> samples = load_samples();
  for (auto& [type, sample] : samples) {
    const Sample* s = &sample;
    benchmark::RegisterBenchmark(("encode/" + type).c_str(), [s](benchmark::State& state) {
      for (auto _ : state) benchmark::DoNotOptimize(codec().encode(*s->message));
    });
    // omit_id types carry no id to dispatch on: the receiver names the type.
    const bool omit_id = codec().find_type(type)->omit_id;
    benchmark::RegisterBenchmark(("decode/" + type).c_str(), [s, omit_id, type](benchmark::State& state) {
      for (auto _ : state) {
        if (omit_id) {
          benchmark::DoNotOptimize(codec().decode_as(type, s->bytes));
        } else {
          benchmark::DoNotOptimize(codec().decode(s->bytes));
        }
      }
    });
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
