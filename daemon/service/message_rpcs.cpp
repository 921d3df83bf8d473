// Submit, Encode and Decode: the calls that take a message from a client.
#include <cmath>

#include "service/acomms_service.h"
#include "service/rpc_status.h"
#include "service/message_json.h"

namespace acomms::service {
namespace {

// The most a submitted message may be: far above any DCCL message (whose
// max_bytes is small), low enough that a runaway client cannot make the
// daemon parse megabytes.
constexpr size_t kMaxMessageBytes = 64 * 1024;

}  // namespace

grpc::Status AcommsService::parse_message(const std::string& type, const std::string* payload,
                                          const std::string* json,
                                          std::unique_ptr<google::protobuf::Message>* out) const {
  using grpc::StatusCode;
  if (parts_.codec.find_type(type) == nullptr) {
    return type_not_loaded(type);
  }
  if ((payload && payload->size() > kMaxMessageBytes) || (json && json->size() > kMaxMessageBytes)) {
    return {StatusCode::INVALID_ARGUMENT, "message is larger than " + std::to_string(kMaxMessageBytes) + " bytes"};
  }
  std::unique_ptr<google::protobuf::Message> message = parts_.codec.new_message(type);
  if (payload) {
    if (!message->ParsePartialFromString(*payload)) {
      return {StatusCode::INVALID_ARGUMENT, "payload is not a serialized " + type};
    }
  } else if (json) {
    std::string why = json_reader_.parse(*json, message.get());
    if (!why.empty()) return {StatusCode::INVALID_ARGUMENT, "json: " + why};
  } else {
    return {StatusCode::INVALID_ARGUMENT, "give the message as payload (protobuf) or json"};
  }
  // Required fields are checked by the caller: Submit first fills the
  // queue's source and time roles, which clients may leave out.
  *out = std::move(message);
  return grpc::Status::OK;
}

grpc::ServerUnaryReactor* AcommsService::Submit(grpc::CallbackServerContext* context,
                                                const v1::SubmitRequest* request, v1::SubmitResponse* response) {
  // The call ends in one of three places: here when the request is refused
  // before anything is stored; on the store writer's thread when the
  // message could not be stored; on the core thread once it is queued (or
  // refused by a full queue). gRPC keeps request and response alive until
  // Finish.
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  grpc::Status refused = submit_to_journal(*request, response, reactor);
  if (!refused.ok()) reactor->Finish(refused);
  return reactor;
}

grpc::Status AcommsService::submit_to_journal(const v1::SubmitRequest& request, v1::SubmitResponse* response,
                                              grpc::ServerUnaryReactor* reactor) {
  using grpc::StatusCode;
  if (!(request.ttl_s() >= 0) || !std::isfinite(request.ttl_s())) {
    return {StatusCode::INVALID_ARGUMENT, "ttl_s must be 0 (the queue's) or a positive number of seconds"};
  }
  std::shared_lock lock(definitions_);
  std::unique_ptr<google::protobuf::Message> message;
  grpc::Status parsed = parse_message(
      request.type(), request.message_case() == v1::SubmitRequest::kPayload ? &request.payload() : nullptr,
      request.message_case() == v1::SubmitRequest::kJson ? &request.json() : nullptr, &message);
  if (!parsed.ok()) return parsed;
  try {
    // Encoding happens here, on this gRPC thread; the write is shared with
    // the other Submits of the same commit, and nothing waits for the disk.
    parts_.queues.journal_new(
        *message, request.ttl_s(),
        [this, response, reactor](queue::QueuedMessage queued, std::exception_ptr error) {
          // On the store writer's thread: hand on quickly, never wait.
          if (error) {
            try {
              std::rethrow_exception(error);
            } catch (const std::exception& e) {
              reactor->Finish({StatusCode::UNAVAILABLE, std::string("store: ") + e.what()});
            }
            return;
          }
          auto durable = std::make_shared<queue::QueuedMessage>(std::move(queued));
          parts_.core.post([this, durable, response, reactor] {
            accept_submitted(std::move(*durable), response, reactor);
          });
        });
  } catch (const queue::UnknownTypeError& e) {
    return {StatusCode::NOT_FOUND, e.what()};
  } catch (const queue::QueueFullError& e) {
    return {StatusCode::RESOURCE_EXHAUSTED, e.what()};
  } catch (const dccl::Error& e) {
    return {StatusCode::INVALID_ARGUMENT, e.what()};
  } catch (const std::exception& e) {
    // The store writer refused the write: the daemon is stopping.
    return {StatusCode::UNAVAILABLE, std::string("store: ") + e.what()};
  }
  return grpc::Status::OK;
}

void AcommsService::accept_submitted(queue::QueuedMessage queued, v1::SubmitResponse* response,
                                     grpc::ServerUnaryReactor* reactor) {
  const int64_t id = queued.record.id;
  const std::string type = queued.record.type;
  if (!parts_.queues.accept(std::move(queued))) {
    // Filled while this message was being stored: it was stored, and
    // accept() dropped it again with an event.
    const queue::Queue* queue = parts_.queues.find_queue(type);
    reactor->Finish({grpc::StatusCode::RESOURCE_EXHAUSTED,
                     queue ? queue::queue_full_text(*queue) : "queue " + type + " is full"});
    return;
  }
  response->set_message_id(id);
  reactor->Finish(grpc::Status::OK);
}

grpc::Status AcommsService::Encode(grpc::ServerContext*, const v1::EncodeRequest* request,
                                   v1::EncodeResponse* response) {
  std::shared_lock lock(definitions_);
  std::unique_ptr<google::protobuf::Message> message;
  grpc::Status parsed = parse_message(
      request->type(), request->message_case() == v1::EncodeRequest::kPayload ? &request->payload() : nullptr,
      request->message_case() == v1::EncodeRequest::kJson ? &request->json() : nullptr, &message);
  if (!parsed.ok()) return parsed;
  if (!message->IsInitialized()) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            request->type() + ": required field(s) missing: " + message->InitializationErrorString()};
  }
  try {
    response->set_encoded(parts_.codec.encode(*message));
  } catch (const dccl::Error& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  }
  return grpc::Status::OK;
}

grpc::Status AcommsService::Decode(grpc::ServerContext*, const v1::DecodeRequest* request,
                                   v1::DecodeResponse* response) {
  if (request->encoded().size() > kMaxMessageBytes) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            "encoded is larger than " + std::to_string(kMaxMessageBytes) + " bytes"};
  }
  if (request->encoded().empty()) return {grpc::StatusCode::INVALID_ARGUMENT, "encoded is empty"};
  std::shared_lock lock(definitions_);
  try {
    std::vector<std::unique_ptr<google::protobuf::Message>> messages;
    if (request->type().empty()) {
      messages = parts_.codec.decode(request->encoded());
    } else {
      if (parts_.codec.find_type(request->type()) == nullptr) {
        return type_not_loaded(request->type());
      }
      messages.push_back(parts_.codec.decode_as(request->type(), request->encoded()));
    }
    for (const auto& message : messages) {
      v1::DecodedMessage* out = response->add_messages();
      out->set_type(message->GetDescriptor()->full_name());
      out->set_payload(message->SerializePartialAsString());
      out->set_json(to_json(*message));
    }
  } catch (const dccl::Error& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  }
  return grpc::Status::OK;
}

}  // namespace acomms::service
