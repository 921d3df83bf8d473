#pragma once
// The daemon's API as commands use it: one unary call is one line, with the
// deadline from --timeout applied and a refusal turned into RpcError.

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>

#include "acomms/v1/acomms.grpc.pb.h"
#include "global_options.h"
#include "rpc_error.h"

namespace acomms::cli {

class ApiClient {
 public:
  // Connects now, so that an absent daemon fails before any work is done.
  explicit ApiClient(const GlobalOptions& options);

  v1::Acomms::Stub& stub() { return *stub_; }

  // A context whose deadline is --timeout from now.
  void set_deadline(grpc::ClientContext& context) const;

  // Calls a unary RPC, e.g. call(&v1::Acomms::Stub::ListTypes, request).
  template <typename Request, typename Response>
  Response call(grpc::Status (v1::Acomms::Stub::*method)(grpc::ClientContext*, const Request&, Response*),
                const Request& request) {
    grpc::ClientContext context;
    set_deadline(context);
    Response response;
    check(((*stub_).*method)(&context, request, &response));
    return response;
  }

 private:
  double timeout_s_;
  std::unique_ptr<v1::Acomms::Stub> stub_;
};

}  // namespace acomms::cli
