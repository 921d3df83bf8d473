// Subscribe: received messages streamed to a client.
#include "service/acomms_service.h"
#include "service/rpc_status.h"

namespace acomms::service {
namespace {

// How often a waiting stream checks whether its client went away.
constexpr std::chrono::milliseconds kPollCancel(200);

}  // namespace

grpc::Status AcommsService::Subscribe(grpc::ServerContext* context, const v1::SubscribeRequest* request,
                                      grpc::ServerWriter<v1::ReceivedMessage>* writer) {
  Subscription::Filter filter;
  {
    auto stable = node_.submitter.types_stable();
    for (const std::string& type : request->types()) {
      if (node_.codec.find_type(type) == nullptr) {
        return type_not_loaded(type);
      }
      filter.types.insert(type);
    }
  }
  if (request->has_src()) filter.src = request->src();
  std::shared_ptr<Subscription> subscription = node_.subscribers.subscribe(std::move(filter));
  // Headers go out now, so the client knows it is subscribed before the
  // first message (tests and tools wait for this).
  writer->SendInitialMetadata();
  grpc::Status result = grpc::Status::OK;
  while (!context->IsCancelled()) {
    if (std::optional<v1::ReceivedMessage> message = subscription->next(kPollCancel)) {
      if (!writer->Write(*message)) break;  // the client went away
      continue;
    }
    if (std::optional<grpc::Status> ended = subscription->ended()) {
      result = *ended;
      break;
    }
  }
  node_.subscribers.unsubscribe(subscription);
  return result;
}

}  // namespace acomms::service
