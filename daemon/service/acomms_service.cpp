#include "service/acomms_service.h"

#include <google/protobuf/util/json_util.h>

#include <cmath>

namespace acomms::service {
namespace {

// The most a submitted message may be: far above any DCCL message (whose
// max_bytes is small), low enough that a runaway client cannot make the
// daemon parse megabytes.
constexpr size_t kMaxSubmitBytes = 64 * 1024;

}  // namespace

AcommsService::AcommsService(DaemonFacts facts, const dccl::Codec& codec, queue::QueueManager& queues,
                             core::EventLoop& core)
    : facts_(std::move(facts)),
      codec_(codec),
      queues_(queues),
      core_(core),
      started_(std::chrono::steady_clock::now()) {}

grpc::Status AcommsService::GetStatus(grpc::ServerContext*, const v1::GetStatusRequest*,
                                      v1::Status* response) {
  response->set_version(facts_.version);
  response->set_uptime_s(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count());
  response->set_data_dir(facts_.data_dir);
  response->set_schema_version(static_cast<int32_t>(facts_.schema_version));
  response->set_driver(facts_.driver);
  response->set_mac(facts_.mac);
  response->set_modem_id(facts_.modem_id);
  response->set_dccl_types(facts_.dccl_types);
  return grpc::Status::OK;
}

grpc::Status AcommsService::Submit(grpc::ServerContext*, const v1::SubmitRequest* request,
                                   v1::SubmitResponse* response) {
  using grpc::StatusCode;
  if (codec_.find_type(request->type()) == nullptr) {
    return {StatusCode::NOT_FOUND, "no DCCL type \"" + request->type() + "\" is loaded"};
  }
  if (request->payload().size() > kMaxSubmitBytes || request->json().size() > kMaxSubmitBytes) {
    return {StatusCode::INVALID_ARGUMENT,
            "message is larger than " + std::to_string(kMaxSubmitBytes) + " bytes"};
  }
  if (!(request->ttl_s() >= 0) || !std::isfinite(request->ttl_s())) {
    return {StatusCode::INVALID_ARGUMENT, "ttl_s must be 0 (the queue's) or a positive number of seconds"};
  }
  std::unique_ptr<google::protobuf::Message> message = codec_.new_message(request->type());
  switch (request->message_case()) {
    case v1::SubmitRequest::kPayload:
      if (!message->ParsePartialFromString(request->payload())) {
        return {StatusCode::INVALID_ARGUMENT, "payload is not a serialized " + request->type()};
      }
      break;
    case v1::SubmitRequest::kJson: {
      google::protobuf::util::Status parsed = google::protobuf::util::JsonStringToMessage(request->json(), message.get());
      if (!parsed.ok()) {
        std::string why(parsed.message());
        if (why.rfind(": ", 0) == 0) why.erase(0, 2);  // the parser leaves an empty path in front
        return {StatusCode::INVALID_ARGUMENT, "json: " + why};
      }
      break;
    }
    default:
      return {StatusCode::INVALID_ARGUMENT, "give the message as payload (protobuf) or json"};
  }
  if (!message->IsInitialized()) {
    return {StatusCode::INVALID_ARGUMENT,
            request->type() + ": required field(s) missing: " + message->InitializationErrorString()};
  }
  queue::QueuedMessage queued;
  try {
    // Encoding and the durable write happen here, on this gRPC thread, so
    // concurrent submits share commits and the core thread never waits on
    // the disk.
    queued = queues_.journal_new(*message, request->ttl_s());
  } catch (const queue::UnknownTypeError& e) {
    return {StatusCode::NOT_FOUND, e.what()};
  } catch (const dccl::Error& e) {
    return {StatusCode::INVALID_ARGUMENT, e.what()};
  } catch (const std::exception& e) {
    return {StatusCode::UNAVAILABLE, std::string("store: ") + e.what()};
  }
  int64_t id = queued.record.id;
  const std::string type = queued.record.type;
  bool accepted = core_.call([&] { return queues_.accept(std::move(queued)); });
  if (!accepted) {
    const queue::Queue* queue = queues_.find_queue(type);
    return {StatusCode::RESOURCE_EXHAUSTED,
            "queue " + type + " is full (max_queue " + std::to_string(queue ? queue->policy().max_queue : 0) +
                ") and refuses new messages"};
  }
  response->set_message_id(id);
  return grpc::Status::OK;
}

}  // namespace acomms::service
