#include "api_client.h"

#include "connection.h"

namespace acomms::cli {

ApiClient::ApiClient(const GlobalOptions& options)
    : timeout_s_(options.timeout_s), stub_(v1::Acomms::NewStub(connect(options))) {}

void ApiClient::set_deadline(grpc::ClientContext& context) const {
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(timeout_s_ * 1000)));
}

}  // namespace acomms::cli
