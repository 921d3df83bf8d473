// Submit, Encode and Decode: the calls that take a message from a client.
#include <cmath>

#include "dccl/message_json.h"
#include "service/acomms_service.h"
#include "service/rpc_status.h"

namespace acomms::service {
namespace {

// The most a submitted message may be: far above any DCCL message (whose
// max_bytes is small), low enough that a runaway client cannot make the
// daemon parse megabytes.
constexpr size_t kMaxMessageBytes = 64 * 1024;

grpc::Status submit_status(const queue::SubmitResult& result) {
  using Error = queue::SubmitResult::Error;
  switch (result.error) {
    case Error::kNone: return grpc::Status::OK;
    case Error::kUnknownType: return {grpc::StatusCode::NOT_FOUND, result.text};
    case Error::kQueueFull: return {grpc::StatusCode::RESOURCE_EXHAUSTED, result.text};
    case Error::kInvalidMessage: return {grpc::StatusCode::INVALID_ARGUMENT, result.text};
    case Error::kStoreFull: return {grpc::StatusCode::RESOURCE_EXHAUSTED, result.text};
    case Error::kStoreUnavailable: break;
  }
  return {grpc::StatusCode::UNAVAILABLE, result.text};
}

}  // namespace

grpc::Status AcommsService::parse_message(const std::string& type, const std::string* payload,
                                          const std::string* json,
                                          std::unique_ptr<google::protobuf::Message>* out) const {
  using grpc::StatusCode;
  if (node_.codec.find_type(type) == nullptr) {
    return type_not_loaded(type);
  }
  if ((payload && payload->size() > kMaxMessageBytes) || (json && json->size() > kMaxMessageBytes)) {
    return {StatusCode::INVALID_ARGUMENT, "message is larger than " + std::to_string(kMaxMessageBytes) + " bytes"};
  }
  std::unique_ptr<google::protobuf::Message> message = node_.codec.new_message(type);
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

grpc::Status AcommsService::parse_submitted(const v1::SubmitRequest& request,
                                            std::unique_ptr<google::protobuf::Message>* out) const {
  if (!(request.ttl_s() >= 0) || !std::isfinite(request.ttl_s())) {
    return {grpc::StatusCode::INVALID_ARGUMENT, "ttl_s must be 0 (the queue's) or a positive number of seconds"};
  }
  // Released before the submit, which takes it again: types only grow, so
  // the parsed message's type is still there.
  auto stable = node_.submitter.types_stable();
  return parse_message(
      request.type(), request.message_case() == v1::SubmitRequest::kPayload ? &request.payload() : nullptr,
      request.message_case() == v1::SubmitRequest::kJson ? &request.json() : nullptr, out);
}

grpc::ServerUnaryReactor* AcommsService::Submit(grpc::CallbackServerContext* context,
                                                const v1::SubmitRequest* request, v1::SubmitResponse* response) {
  // The answer comes once the message is durable and queued, or refused,
  // on whichever thread that is known (queue/submitter.h); gRPC keeps
  // request and response alive until Finish.
  grpc::ServerUnaryReactor* reactor = context->DefaultReactor();
  if (grpc::Status denied = allowed(*context, "Submit"); !denied.ok()) {
    reactor->Finish(denied);
    return reactor;
  }
  std::unique_ptr<google::protobuf::Message> message;
  grpc::Status parsed = parse_submitted(*request, &message);
  if (!parsed.ok()) {
    reactor->Finish(parsed);
    return reactor;
  }
  node_.submitter.submit(*message, request->ttl_s(), [response, reactor](queue::SubmitResult result) {
    if (result.ok()) response->set_message_id(result.message_id);
    reactor->Finish(submit_status(result));
  });
  return reactor;
}

grpc::Status AcommsService::Encode(grpc::ServerContext* context, const v1::EncodeRequest* request,
                                   v1::EncodeResponse* response) {
  if (grpc::Status denied = allowed(*context, "Encode"); !denied.ok()) return denied;
  auto stable = node_.submitter.types_stable();
  // An authenticated type comes out sealed (tag and stamp): a frame any
  // modem could transmit and a receiver would accept, so it takes the role
  // that may send (Submit's), not a viewer's.
  if (node_.codec.find_type(request->type()) != nullptr && node_.codec.authenticated(request->type())) {
    if (grpc::Status denied = allowed(*context, "Submit"); !denied.ok()) {
      return {grpc::StatusCode::PERMISSION_DENIED,
              "Encode of authenticated type " + request->type() + " makes a sealed frame: " + denied.error_message()};
    }
  }
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
    response->set_encoded(node_.codec.encode(*message));
  } catch (const dccl::Error& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  }
  return grpc::Status::OK;
}

grpc::Status AcommsService::Decode(grpc::ServerContext* context, const v1::DecodeRequest* request,
                                   v1::DecodeResponse* response) {
  if (grpc::Status denied = allowed(*context, "Decode"); !denied.ok()) return denied;
  if (request->encoded().size() > kMaxMessageBytes) {
    return {grpc::StatusCode::INVALID_ARGUMENT,
            "encoded is larger than " + std::to_string(kMaxMessageBytes) + " bytes"};
  }
  if (request->encoded().empty()) return {grpc::StatusCode::INVALID_ARGUMENT, "encoded is empty"};
  auto stable = node_.submitter.types_stable();
  try {
    std::vector<std::unique_ptr<google::protobuf::Message>> messages;
    if (request->type().empty()) {
      messages = node_.codec.decode(request->encoded());
    } else {
      if (node_.codec.find_type(request->type()) == nullptr) {
        return type_not_loaded(request->type());
      }
      messages.push_back(node_.codec.decode_as(request->type(), request->encoded()));
    }
    for (const auto& message : messages) {
      v1::DecodedMessage* out = response->add_messages();
      out->set_type(message->GetDescriptor()->full_name());
      out->set_payload(message->SerializePartialAsString());
      out->set_json(dccl::message_json(*message));
    }
  } catch (const dccl::Error& e) {
    return {grpc::StatusCode::INVALID_ARGUMENT, e.what()};
  }
  return grpc::Status::OK;
}

}  // namespace acomms::service
