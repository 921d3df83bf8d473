// What computes a model run: the built-in ray/beam model, or an external
// program (BELLHOP) behind the same face.
//
// Problem: the worker pool must not care which model answers, and an
// external program's failure must reach the client as the program said it,
// while a bad environment is the client's mistake. Decision: an engine
// throws std::invalid_argument for an environment it refuses (naming the
// field), ModelCancelled when its token fired, and EngineError for its own
// failure (text verbatim). Engines are called from several worker threads
// at once: implementations are thread-safe.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/arrivals.h"
#include "gram/cancel_token.h"
#include "gram/transmission_loss.h"

namespace acomms::gram {

// The engine itself failed (not the environment): its message is passed
// on to the client verbatim.
class EngineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ModelEngine {
 public:
  virtual ~ModelEngine() = default;
  virtual std::string name() const = 0;
  virtual TransmissionLoss transmission_loss(const Environment& env, const CancelToken& cancel) = 0;
};

// compute_transmission_loss on the calling thread only: the pool's
// parallelism is across requests (gram.workers), not inside one.
std::unique_ptr<ModelEngine> make_builtin_engine();

}  // namespace acomms::gram
