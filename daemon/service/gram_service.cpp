// acomms.v1.Gram (see gram_service.h).
#include "service/gram_service.h"

#include <chrono>
#include <memory>
#include <mutex>

#include "gram/depth_objective_proto.h"
#include "gram/list_directed.h"
#include "util/seconds.h"

namespace acomms::service {
namespace {

// Bounds what one request may make the daemon parse.
constexpr std::size_t kMaxCastBytes = 4u << 20;
constexpr int kMaxCasts = 64;

grpc::Status status_of(const gram::ModelOutcome& outcome) {
  using gram::ModelStatus;
  switch (outcome.status) {
    case ModelStatus::kOk: return grpc::Status::OK;
    case ModelStatus::kInvalid: return {grpc::StatusCode::INVALID_ARGUMENT, outcome.message};
    case ModelStatus::kSuperseded: return {grpc::StatusCode::ABORTED, outcome.message};
    case ModelStatus::kQueueFull: return {grpc::StatusCode::RESOURCE_EXHAUSTED, outcome.message};
    case ModelStatus::kCancelled: return {grpc::StatusCode::CANCELLED, "the client cancelled the model run"};
    case ModelStatus::kDeadlineExceeded:
      return {grpc::StatusCode::DEADLINE_EXCEEDED, "the client's deadline passed; the model run was stopped"};
    case ModelStatus::kEngineFailed: return {grpc::StatusCode::INTERNAL, outcome.message};
    case ModelStatus::kShuttingDown: break;
  }
  return {grpc::StatusCode::UNAVAILABLE, outcome.message};
}

// The client's deadline on the steady clock the model polls.
gram::CancelToken::Clock::time_point run_deadline(const grpc::CallbackServerContext& context) {
  const auto deadline = context.deadline();
  if (deadline >= std::chrono::system_clock::time_point::max() - std::chrono::hours(24 * 365))
    return gram::CancelToken::Clock::time_point::max();
  return gram::CancelToken::Clock::now() +
         std::chrono::duration_cast<gram::CancelToken::Clock::duration>(deadline - std::chrono::system_clock::now());
}

std::vector<std::string> mask_paths(const google::protobuf::FieldMask& mask) {
  return {mask.paths().begin(), mask.paths().end()};
}

// One model call: owns itself until gRPC is done with it, and passes the
// client's cancel (or deadline) on to the pool's ticket.
class ModelCall final : public grpc::ServerUnaryReactor {
 public:
  static ModelCall* start() {
    auto call = std::shared_ptr<ModelCall>(new ModelCall);
    call->self_ = call;
    return call.get();
  }
  std::shared_ptr<ModelCall> shared() { return self_; }

  void set_ticket(std::shared_ptr<gram::ModelTicket> ticket) {
    bool cancel_now;
    {
      std::lock_guard lock(mutex_);
      ticket_ = ticket;
      cancel_now = cancelled_;
    }
    if (cancel_now) ticket->cancel();
  }
  void OnCancel() override {
    std::shared_ptr<gram::ModelTicket> ticket;
    {
      std::lock_guard lock(mutex_);
      cancelled_ = true;
      ticket = ticket_;
    }
    if (ticket) ticket->cancel();
  }
  void OnDone() override {
    std::shared_ptr<ModelCall> last;
    std::lock_guard lock(mutex_);
    ticket_.reset();
    last.swap(self_);  // released after the lock: may delete this
  }

 private:
  ModelCall() = default;
  std::mutex mutex_;
  bool cancelled_ = false;
  std::shared_ptr<gram::ModelTicket> ticket_;
  std::shared_ptr<ModelCall> self_;
};

grpc::ServerUnaryReactor* finish_now(grpc::CallbackServerContext* context, const grpc::Status& status) {
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  reactor->Finish(status);
  return reactor;
}

void fill_tl(const gram::TransmissionLoss& tl, v1::TransmissionLossReply* reply) {
  reply->mutable_range_m()->Add(tl.range_m.begin(), tl.range_m.end());
  reply->mutable_depth_m()->Add(tl.depth_m.begin(), tl.depth_m.end());
  reply->set_irregular(tl.irregular);
  reply->mutable_tl_db()->Add(tl.tl_db.begin(), tl.tl_db.end());
  reply->set_beam_count(tl.beam_count);
}

void fill_arrivals(const std::vector<gram::ReceiverArrivals>& receivers, v1::ArrivalsReply* reply) {
  for (const auto& r : receivers) {
    auto* out = reply->add_receivers();
    out->set_range_m(r.range_m);
    out->set_depth_m(r.depth_m);
    for (const auto& a : r.arrivals) {
      auto* arrival = out->add_arrivals();
      arrival->set_delay_s(a.delay_s);
      arrival->set_amplitude(a.amplitude);
      arrival->set_phase_deg(a.phase_deg);
      arrival->set_launch_deg(a.launch_deg);
      arrival->set_arrival_deg(a.arrival_deg);
      arrival->set_top_bounces(a.top_bounces);
      arrival->set_bottom_bounces(a.bottom_bounces);
      arrival->set_caustics(a.caustics);
    }
    out->set_rms_delay_spread_s(gram::rms_delay_spread(r.arrivals, 60.0).tau_rms_s);
  }
}

}  // namespace

GramService::GramService(gram::ModelPool& pool, gram::VehicleEnvironment& environment, SaveEnvironment save,
                         const ApiRoles& roles)
    : pool_(pool), environment_(environment), save_(std::move(save)), roles_(roles) {}

grpc::ServerUnaryReactor* GramService::run(grpc::CallbackServerContext* context, const v1::ModelRequestHeader& header,
                                           gram::ModelRequest request, Fill fill) {
  try {
    request.environments = environment_.resolve(header.environment(), mask_paths(header.override_mask()),
                                                request.kind == gram::ModelKind::kDepthObjective);
  } catch (const std::invalid_argument& e) {
    return finish_now(context, {grpc::StatusCode::INVALID_ARGUMENT, e.what()});
  }
  request.deadline = run_deadline(*context);
  ModelCall* call = ModelCall::start();
  auto keep = call->shared();
  auto ticket = pool_.submit(std::move(request), header.consumer(),
                             [keep, fill = std::move(fill)](gram::ModelOutcome outcome) {
                               if (outcome.status == gram::ModelStatus::kOk) fill(outcome);
                               keep->Finish(status_of(outcome));
                             });
  call->set_ticket(std::move(ticket));
  return call;
}

grpc::ServerUnaryReactor* GramService::TransmissionLoss(grpc::CallbackServerContext* context,
                                                        const v1::TransmissionLossRequest* request,
                                                        v1::TransmissionLossReply* reply) {
  if (grpc::Status denied = roles_.check(*context, "/acomms.v1.Gram/TransmissionLoss"); !denied.ok()) {
    return finish_now(context, denied);
  }
  gram::ModelRequest run_request;
  run_request.kind = gram::ModelKind::kTransmissionLoss;
  return run(context, request->header(), std::move(run_request), [reply](const gram::ModelOutcome& outcome) {
    fill_tl(outcome.result->tl.at(0), reply);
    reply->set_from_cache(outcome.from_cache);
    reply->set_engine(outcome.result->engine);
  });
}

grpc::ServerUnaryReactor* GramService::Arrivals(grpc::CallbackServerContext* context,
                                                const v1::ArrivalsRequest* request, v1::ArrivalsReply* reply) {
  if (grpc::Status denied = roles_.check(*context, "/acomms.v1.Gram/Arrivals"); !denied.ok()) {
    return finish_now(context, denied);
  }
  gram::ModelRequest run_request;
  run_request.kind = gram::ModelKind::kArrivals;
  run_request.max_arrivals = request->max_arrivals() ? request->max_arrivals() : 200;
  return run(context, request->header(), std::move(run_request), [reply](const gram::ModelOutcome& outcome) {
    fill_arrivals(outcome.result->arrivals, reply);
    reply->set_from_cache(outcome.from_cache);
  });
}

grpc::ServerUnaryReactor* GramService::DepthObjective(grpc::CallbackServerContext* context,
                                                      const v1::DepthObjectiveRequest* request,
                                                      v1::DepthObjectiveResponse* response) {
  if (grpc::Status denied = roles_.check(*context, "/acomms.v1.Gram/DepthObjective"); !denied.ok()) {
    return finish_now(context, denied);
  }
  gram::ModelRequest run_request;
  run_request.kind = gram::ModelKind::kDepthObjective;
  run_request.objective = request->query();
  return run(context, request->header(), std::move(run_request), [response](const gram::ModelOutcome& outcome) {
    *response->mutable_reply() = gram::reply_to_proto(*outcome.result->objective);
    response->set_instances(static_cast<uint32_t>(outcome.result->tl.size()));
    response->set_from_cache(outcome.from_cache);
  });
}

grpc::ServerUnaryReactor* GramService::UpdateEnvironment(grpc::CallbackServerContext* context,
                                                         const v1::UpdateEnvironmentRequest* request,
                                                         gram::KnownEnvironment* reply) {
  if (grpc::Status denied = roles_.check(*context, "/acomms.v1.Gram/UpdateEnvironment"); !denied.ok()) {
    return finish_now(context, denied);
  }
  if (request->casts_size() > kMaxCasts)
    return finish_now(context, {grpc::StatusCode::INVALID_ARGUMENT,
                                "casts: " + std::to_string(request->casts_size()) + " casts; at most " +
                                    std::to_string(kMaxCasts) + " per request"});
  gram::EnvironmentChange change;
  change.base = request->base();
  change.mask = mask_paths(request->override_mask());
  change.clear_instances = request->clear_instances();
  const double now_s = util::unix_seconds_now();
  for (int i = 0; i < request->casts_size(); ++i) {
    const v1::CtdCast& cast = request->casts(i);
    const std::string field = "casts[" + std::to_string(i) + "]";
    if (cast.csv().size() > kMaxCastBytes)
      return finish_now(context, {grpc::StatusCode::INVALID_ARGUMENT,
                                  field + ".csv is " + std::to_string(cast.csv().size()) + " bytes; at most " +
                                      std::to_string(kMaxCastBytes)});
    if (!(cast.time_s() >= 0))
      return finish_now(context, {grpc::StatusCode::INVALID_ARGUMENT, field + ".time_s must be at least 0 (0: now)"});
    change.casts.push_back({cast.time_s() > 0 ? cast.time_s() : now_s, cast.csv(),
                            cast.name().empty() ? field : cast.name()});
  }
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  try {
    environment_.update(change, [this, reactor, reply](const gram::KnownEnvironment& state) {
      *reply = state;
      save_(state, [reactor](std::exception_ptr error) {
        if (!error) {
          reactor->Finish(grpc::Status::OK);
          return;
        }
        std::string why = "the store did not record the environment";
        try {
          std::rethrow_exception(error);
        } catch (const std::exception& e) {
          why += std::string(": ") + e.what();
        }
        reactor->Finish({grpc::StatusCode::UNAVAILABLE, why});
      });
    });
  } catch (const std::exception& e) {  // invalid_argument, ImportError: nothing changed
    reactor->Finish({grpc::StatusCode::INVALID_ARGUMENT, e.what()});
  }
  return reactor;
}

grpc::ServerUnaryReactor* GramService::GetEnvironment(grpc::CallbackServerContext* context,
                                                      const v1::GetEnvironmentRequest*,
                                                      gram::KnownEnvironment* reply) {
  if (grpc::Status denied = roles_.check(*context, "/acomms.v1.Gram/GetEnvironment"); !denied.ok()) {
    return finish_now(context, denied);
  }
  *reply = environment_.snapshot();
  return finish_now(context, grpc::Status::OK);
}

grpc::ServerUnaryReactor* GramService::PoolStatus(grpc::CallbackServerContext* context, const v1::PoolStatusRequest*,
                                                  v1::PoolStatusReply* reply) {
  if (grpc::Status denied = roles_.check(*context, "/acomms.v1.Gram/PoolStatus"); !denied.ok()) {
    return finish_now(context, denied);
  }
  const gram::ModelPoolStats s = pool_.stats();
  reply->set_workers(s.workers);
  reply->set_running(s.running);
  reply->set_waiting(static_cast<uint32_t>(s.waiting));
  reply->set_cache_entries(s.cache_entries);
  reply->set_cache_bytes(s.cache_bytes);
  reply->set_cache_hits(s.cache_hits);
  reply->set_completed(s.completed);
  reply->set_engine(pool_.engine_name());
  return finish_now(context, grpc::Status::OK);
}

}  // namespace acomms::service
