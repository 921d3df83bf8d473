#pragma once
// How acommsctl fails. Two kinds of failure have different exit codes, so
// scripts can tell "you typed it wrong" (2) from "the daemon said no" (1):
//   UsageError  the command line or the input cannot make a request
//   RpcError    the daemon refused the request (or could not be reached)
// main() prints either as one "acommsctl: ..." line on stderr.

#include <grpcpp/grpcpp.h>

#include <stdexcept>
#include <string>

namespace acomms::cli {

constexpr int kExitRefused = 1;
constexpr int kExitUsage = 2;

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RpcError : public std::runtime_error {
 public:
  explicit RpcError(const grpc::Status& status);
  grpc::StatusCode code() const { return code_; }

 private:
  grpc::StatusCode code_;
};

// "NOT_FOUND", "INVALID_ARGUMENT", ...: the names the API documents, so a
// message can be looked up in acomms.proto.
const char* status_code_name(grpc::StatusCode code);

// Throws RpcError("CODE: the daemon's message") unless `status` is OK.
void check(const grpc::Status& status);

}  // namespace acomms::cli
