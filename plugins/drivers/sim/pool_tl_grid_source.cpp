#include "sim/pool_tl_grid_source.h"

#include "core/core_thread.h"

namespace acomms::drivers {

PoolTlGridSource::PoolTlGridSource(gram::ModelPool& pool, Executor to_core)
    : pool_(pool), to_core_(std::move(to_core)) {}

void PoolTlGridSource::request(ModelRun run, Done done) {
  ACOMMS_ASSERT_CORE_THREAD();
  gram::ModelRequest request;
  request.kind = run.kind == ModelRun::Kind::kTransmissionLoss ? gram::ModelKind::kTransmissionLoss
                                                                : gram::ModelKind::kArrivals;
  request.environments = {std::move(run.environment)};
  // The answer may come inside submit() (a cache hit, a refusal): it is
  // always posted, so `done` never runs inside request().
  pool_.submit(std::move(request), "",
               [kind = run.kind, done = std::move(done), to_core = to_core_](gram::ModelOutcome outcome) mutable {
                 auto answer = std::make_shared<ModelAnswer>();
                 if (outcome.status != gram::ModelStatus::kOk) {
                   answer->error = outcome.message.empty() ? "the model run did not complete" : outcome.message;
                 } else if (kind == ModelRun::Kind::kTransmissionLoss) {
                   // Aliasing: the grid lives in the pool's (cached) result.
                   answer->tl = std::shared_ptr<const gram::TransmissionLoss>(outcome.result, &outcome.result->tl.at(0));
                 } else if (!outcome.result->arrivals.empty() && !outcome.result->arrivals[0].arrivals.empty()) {
                   answer->delay_spread_s = gram::rms_delay_spread(outcome.result->arrivals[0].arrivals, 60.0).tau_rms_s;
                 }
                 to_core([answer, done = std::move(done)] { done(std::move(*answer)); });
               });
}

}  // namespace acomms::drivers
