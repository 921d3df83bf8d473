#pragma once
// acomms.v1.Gram: the acoustic model as a service (api/proto/acomms/v1/
// gram.proto). Thin, like Acomms: parse, merge the request's environment
// over the one the vehicle knows, one call into gram (the worker pool, or
// the environment), finish. Every method is a callback (reactor) method:
// no gRPC thread ever waits for a model or for the disk. A client's cancel
// or deadline reaches the run through the reactor's OnCancel (and the
// deadline is also the run's own, so it stops even if gRPC is late).

#include <exception>
#include <functional>

#include "acomms/gram/known_environment.pb.h"
#include "acomms/v1/gram.grpc.pb.h"
#include "gram/model_pool.h"
#include "gram/vehicle_environment.h"
#include "service/api_roles.h"

namespace acomms::service {

// Records the environment's new state durably, then calls `done` (null on
// success) on any thread. Must not block.
using SaveEnvironment =
    std::function<void(const gram::KnownEnvironment& state, std::function<void(std::exception_ptr)> done)>;

class GramService final : public v1::Gram::CallbackService {
 public:
  // `roles` (who may call what: api_roles.h) must outlive the service.
  GramService(gram::ModelPool& pool, gram::VehicleEnvironment& environment, SaveEnvironment save,
              const ApiRoles& roles);

  grpc::ServerUnaryReactor* TransmissionLoss(grpc::CallbackServerContext*, const v1::TransmissionLossRequest*,
                                             v1::TransmissionLossReply*) override;
  grpc::ServerUnaryReactor* Arrivals(grpc::CallbackServerContext*, const v1::ArrivalsRequest*,
                                     v1::ArrivalsReply*) override;
  grpc::ServerUnaryReactor* DepthObjective(grpc::CallbackServerContext*, const v1::DepthObjectiveRequest*,
                                           v1::DepthObjectiveResponse*) override;
  grpc::ServerUnaryReactor* UpdateEnvironment(grpc::CallbackServerContext*, const v1::UpdateEnvironmentRequest*,
                                              gram::KnownEnvironment*) override;
  grpc::ServerUnaryReactor* GetEnvironment(grpc::CallbackServerContext*, const v1::GetEnvironmentRequest*,
                                           gram::KnownEnvironment*) override;
  grpc::ServerUnaryReactor* PoolStatus(grpc::CallbackServerContext*, const v1::PoolStatusRequest*,
                                       v1::PoolStatusReply*) override;

 private:
  using Fill = std::function<void(const gram::ModelOutcome&)>;
  // Resolves the header's environment, submits, and finishes the call with
  // the outcome's status after `fill` wrote the reply.
  grpc::ServerUnaryReactor* run(grpc::CallbackServerContext* context, const v1::ModelRequestHeader& header,
                                gram::ModelRequest request, Fill fill);

  gram::ModelPool& pool_;
  gram::VehicleEnvironment& environment_;
  SaveEnvironment save_;
  const ApiRoles& roles_;
};

}  // namespace acomms::service
