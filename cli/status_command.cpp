#include "status_command.h"

#include <google/protobuf/util/json_util.h>

#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "acomms/v1/acomms.grpc.pb.h"
#include "connection.h"
#include "global_options.h"

namespace acomms::cli {
namespace {

std::string to_json(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = true;
  options.always_print_primitive_fields = true;
  std::string json;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json;
}

void print_human(const v1::Status& status) {
  std::printf("acommsd %s\n", status.version().c_str());
  std::printf("  uptime:          %.1f s\n", status.uptime_s());
  std::printf("  data dir:        %s\n", status.data_dir().c_str());
  std::printf("  schema version:  %lld\n", static_cast<long long>(status.schema_version()));
  std::printf("  driver:          %s (modem id %u)\n", status.driver().c_str(), status.modem_id());
  std::printf("  mac:             %s\n", status.mac().c_str());
  std::printf("  dccl types:      %d\n", status.dccl_types());
}

void run_status(const GlobalOptions& options) {
  auto channel = connect(options.endpoint, options.timeout_s);
  auto stub = v1::Acomms::NewStub(channel);
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(options.timeout_s * 1000)));
  v1::Status status;
  grpc::Status rpc = stub->GetStatus(&context, v1::GetStatusRequest(), &status);
  if (!rpc.ok()) throw std::runtime_error("GetStatus failed: " + rpc.error_message());
  if (options.json) {
    std::cout << to_json(status) << "\n";
  } else {
    print_human(status);
  }
}

}  // namespace

void add_status_command(CLI::App& app, const GlobalOptions& options) {
  CLI::App* status = app.add_subcommand("status", "Show the daemon's version, uptime and setup");
  status->callback([&options] { run_status(options); });
}

}  // namespace acomms::cli
