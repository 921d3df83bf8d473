// What authentication (dccl/message_auth.h) costs a message: encode and
// decode-and-verify of gv.NavigationReport plain, encrypted, authenticated
// (64-bit tag) and both, ns per message. The receive side's verify is
// measured with the decode, as the queue runs them; the replay and window
// checks (a set look-up) are not included.
//
//   build/tests/bench/auth_bench

#include <benchmark/benchmark.h>
#include <google/protobuf/text_format.h>

#include <memory>
#include <string>

#include "dccl/codec.h"
#include "dccl/message_auth.h"

namespace {

using acomms::dccl::AuthVerdict;
using acomms::dccl::Codec;
using acomms::dccl::MessageAuthenticator;

constexpr double kNow = 1'700'000'000.0;
constexpr const char* kType = "gv.NavigationReport";

struct Setup {
  Codec codec;
  std::shared_ptr<MessageAuthenticator> auth;
  std::unique_ptr<google::protobuf::Message> message;
};

std::unique_ptr<Setup> make(bool encrypted, bool authenticated) {
  auto s = std::make_unique<Setup>();
  s->codec.load(ACOMMS_SHARED_DIR "/conformance/dccl/gv.proto", {ACOMMS_PROTO_DIR});
  s->codec.set_clock([] { return kNow; });
  if (encrypted) s->codec.set_crypto("my_passphrase!");
  if (authenticated) {
    acomms::dccl::Keyring ring;
    ring.keys[1].key = std::string(16, 'k');
    ring.sign_id = 1;
    s->auth = std::make_shared<MessageAuthenticator>(64, ring, 1);
    s->codec.set_authentication(s->auth, {kType});
  }
  s->message = s->codec.new_message(kType);
  google::protobuf::TextFormat::ParseFromString("x: 450 y: 550 z: -100", s->message.get());
  return s;
}

void Encode(benchmark::State& state, bool encrypted, bool authenticated) {
  auto s = make(encrypted, authenticated);
  for (auto _ : state) benchmark::DoNotOptimize(s->codec.encode(*s->message));
  state.counters["bytes"] = static_cast<double>(s->codec.encode(*s->message).size());
}

void DecodeAndVerify(benchmark::State& state, bool encrypted, bool authenticated) {
  auto s = make(encrypted, authenticated);
  const std::string bytes = s->codec.encode(*s->message);
  for (auto _ : state) {
    size_t used = 0;
    benchmark::DoNotOptimize(s->codec.decode_as(kType, bytes, &used));
    if (s->auth && s->auth->verify(std::string_view(bytes).substr(0, used), kNow, 1, nullptr) != AuthVerdict::kOk) {
      state.SkipWithError("tag did not verify");
      break;
    }
  }
}

BENCHMARK_CAPTURE(Encode, plain, false, false);
BENCHMARK_CAPTURE(Encode, encrypted, true, false);
BENCHMARK_CAPTURE(Encode, authenticated, false, true);
BENCHMARK_CAPTURE(Encode, encrypted_authenticated, true, true);
BENCHMARK_CAPTURE(DecodeAndVerify, plain, false, false);
BENCHMARK_CAPTURE(DecodeAndVerify, encrypted, true, false);
BENCHMARK_CAPTURE(DecodeAndVerify, authenticated, false, true);
BENCHMARK_CAPTURE(DecodeAndVerify, encrypted_authenticated, true, true);

}  // namespace

BENCHMARK_MAIN();
