// DriverSpecific: a modem's own kind of transmission, passed through.
//
// The service reads nothing of the request beyond its type: the extension
// is the driver's (link/driver_specific.h), so no plugin header is needed
// here. The call waits for the link's answer, which comes within the
// call's deadline (the LinkController's gate and the driver both stop at
// it); a client without a deadline gets kDefaultTimeout.

#include <chrono>
#include <future>
#include <memory>

#include "service/acomms_service.h"

namespace acomms::service {
namespace {

using link::DriverSpecificStatus;

constexpr std::chrono::seconds kDefaultTimeout{300};
// After the deadline, the core has this long to say so itself.
constexpr std::chrono::seconds kGrace{5};

grpc::StatusCode code_of(DriverSpecificStatus status) {
  switch (status) {
    case DriverSpecificStatus::kOk: return grpc::StatusCode::OK;
    case DriverSpecificStatus::kInvalidArgument: return grpc::StatusCode::INVALID_ARGUMENT;
    case DriverSpecificStatus::kFailedPrecondition: return grpc::StatusCode::FAILED_PRECONDITION;
    case DriverSpecificStatus::kUnimplemented: return grpc::StatusCode::UNIMPLEMENTED;
    case DriverSpecificStatus::kDeadlineExceeded: return grpc::StatusCode::DEADLINE_EXCEEDED;
    case DriverSpecificStatus::kUnavailable: return grpc::StatusCode::UNAVAILABLE;
    case DriverSpecificStatus::kAborted: return grpc::StatusCode::ABORTED;
  }
  return grpc::StatusCode::UNKNOWN;
}

}  // namespace

grpc::Status AcommsService::DriverSpecific(grpc::ServerContext* context, const v1::DriverSpecificRequest* request,
                                           v1::DriverSpecificResponse* response) {
  if (grpc::Status denied = allowed(*context, "DriverSpecific"); !denied.ok()) return denied;
  const v1::ModemTransmission& tx = request->transmission();
  if (tx.type() != v1::ModemTransmission::DRIVER_SPECIFIC) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            "transmission.type must be DRIVER_SPECIFIC (3), with the driver's extension; data goes through Submit"};
  }
  Link* link = nullptr;
  if (grpc::Status found = find_link(request->link(), &link); !found.ok()) return found;
  auto now = std::chrono::system_clock::now();
  auto deadline = context->deadline();
  if (deadline > now + kDefaultTimeout) deadline = now + kDefaultTimeout;
  double timeout_s = std::chrono::duration<double>(deadline - now).count();
  if (timeout_s <= 0) return {grpc::StatusCode::DEADLINE_EXCEEDED, "the call's deadline had passed on arrival"};

  auto promise = std::make_shared<std::promise<link::DriverSpecificResult>>();
  std::future<link::DriverSpecificResult> future = promise->get_future();
  node_.core.post([link, tx, timeout_s, promise] {
    link->controller.request_driver_specific(tx, timeout_s, [promise](link::DriverSpecificResult result) {
      promise->set_value(std::move(result));
    });
  });
  if (future.wait_until(deadline + kGrace) != std::future_status::ready) {
    return {grpc::StatusCode::DEADLINE_EXCEEDED, "no answer from the link within the call's deadline"};
  }
  link::DriverSpecificResult result = future.get();
  if (result.status != DriverSpecificStatus::kOk) return {code_of(result.status), result.error};
  *response->mutable_transmission() = std::move(result.transmission);
  response->set_waited_s(result.waited_s);
  return grpc::Status::OK;
}

}  // namespace acomms::service
