#pragma once
// The simulator's model runs on the daemon's GRAM worker pool.
//
// Problem: a node's TL grids and delay spreads must run off the core
// thread, and on the same bounded pool as every other model request, not on
// a thread per driver. Decision: a TlGridSource (tl_grid_source.h) whose
// request() submits to gram::ModelPool (no consumer key: each request is
// answered, none superseded) and posts the answer back to the core thread
// through `to_core`. The pool's answers, errors included (a full queue, an
// environment the model refuses), reach the physics as ModelAnswer::error.
// The TL is shared with the pool's cache entry, not copied.
// Thread rules: request() on the core thread only; `done` runs on the core
// thread, never inside request(). The pool outlives the source.

#include <functional>

#include "gram/model_pool.h"
#include "sim/tl_grid_source.h"

namespace acomms::drivers {

class PoolTlGridSource final : public TlGridSource {
 public:
  using Executor = std::function<void(std::function<void()> task)>;
  PoolTlGridSource(gram::ModelPool& pool, Executor to_core);
  void request(ModelRun run, Done done) override;

 private:
  gram::ModelPool& pool_;
  Executor to_core_;
};

}  // namespace acomms::drivers
