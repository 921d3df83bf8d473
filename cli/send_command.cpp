#include "send_command.h"

#include <unistd.h>

#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "api_client.h"
#include "global_options.h"
#include "interactive_prompt.h"
#include "message_builder.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

struct SendOptions {
  std::string type;
  std::vector<std::string> assignments;
  std::string json;
  CLI::Option* json_option = nullptr;
  bool interactive = false;
  double ttl_s = 0;
};

// The message from field=value arguments, checked here so that a typo is
// a usage error naming the valid fields rather than a round trip.
std::string payload_from_assignments(ApiClient& client, const SendOptions& options) {
  std::unique_ptr<TypeSchema> schema = fetch_schema(client, options.type);
  std::unique_ptr<google::protobuf::Message> message = schema->new_message();
  for (const std::string& argument : options.assignments) {
    auto [path, value] = split_assignment(argument);
    assign_path(*message, path, value);
  }
  // Required fields are the daemon's to check: it first fills the ones its
  // queue roles provide (source, time), which a person should not type.
  return message->SerializePartialAsString();
}

// Nothing when the person answered no. (An empty payload is a real
// message: a type whose fields are all unset encodes to no bytes.)
std::optional<std::string> payload_from_prompt(ApiClient& client, const SendOptions& options) {
  std::unique_ptr<TypeSchema> schema = fetch_schema(client, options.type);
  const PromptStreams streams{std::cin, std::cerr, ::isatty(STDIN_FILENO) == 0};
  std::unique_ptr<google::protobuf::Message> message = prompt_message(*schema, streams);
  if (!confirm_send(*message, streams)) {
    if (!std::cin) throw UsageError("input ended before the answer to \"send?\"");
    return std::nullopt;
  }
  return message->SerializePartialAsString();
}

// `send T x=1 --json` means "answer in JSON": CLI11 hands the option the
// next word, which is no JSON object, so it goes back to the fields.
void take_back_misread_json(SendOptions& options) {
  const size_t first = options.json.find_first_not_of(" \t\n");
  if (first != std::string::npos && options.json[first] != '{') {
    options.assignments.push_back(options.json);
    options.json.clear();
  }
}

void check_one_message_source(const SendOptions& options) {
  const bool json_in = !options.json.empty();
  if (options.interactive && (json_in || !options.assignments.empty())) {
    throw UsageError("--interactive asks for every field: give no field=value or JSON with it");
  }
  if (json_in && !options.assignments.empty()) {
    throw UsageError("give the message either as field=value arguments or as --json, not both");
  }
}

void run_send(const GlobalOptions& global, SendOptions options) {
  const bool json_out = global.json || options.json_option->count() > 0;
  take_back_misread_json(options);
  check_one_message_source(options);
  ApiClient client(global);
  v1::SubmitRequest request;
  request.set_type(options.type);
  request.set_ttl_s(options.ttl_s);
  if (!options.json.empty()) {
    request.set_json(options.json);
  } else if (options.interactive) {
    std::optional<std::string> payload = payload_from_prompt(client, options);
    if (!payload) {
      std::cerr << "not sent\n";
      return;
    }
    request.set_payload(*payload);
  } else {
    request.set_payload(payload_from_assignments(client, options));
  }
  v1::SubmitResponse response = client.call(&v1::Acomms::Stub::Submit, request);
  if (json_out) {
    std::cout << "{\"message_id\": " << response.message_id() << "}\n";
  } else {
    std::cout << response.message_id() << "\n";
  }
}

}  // namespace

void add_send_command(CLI::App& app, const GlobalOptions& global) {
  static SendOptions options;
  CLI::App* send = app.add_subcommand("send", "Queue a message for the acoustic link; prints its message id");
  send->add_option("TYPE", options.type, "DCCL type, e.g. gv.NavigationReport (see `defs list`)")
      ->required()
      ->type_name("");
  send->add_option("FIELD=VALUE", options.assignments,
                   "Field values: numbers, true/false, enum names, hex bytes 0x0a1b, comma-separated "
                   "lists for repeated fields, dotted paths for nested fields (header.time=...)")
      ->type_name("");
  options.json_option =
      send->add_option("--json", options.json,
                       "The message as a JSON object instead of field=value (output is JSON too); "
                       "alone, just JSON output")
          ->expected(0, 1)
          ->type_name("JSON");
  send->add_flag("-i,--interactive", options.interactive,
                 "Ask for each field on stdin, showing its type, DCCL bounds and enum values; confirm "
                 "before sending (works with a pipe too)");
  send->add_option("--ttl", options.ttl_s,
                   "Seconds this message may wait before it expires (default: the queue's; at most its "
                   "duplicate window)")
      ->check(CLI::NonNegativeNumber)
      ->type_name("SECONDS");
  send->footer(
      "The daemon encodes the message with DCCL, keeps it durably in the type's queue and sends it in "
      "one of this node's slots. The message id is what `queue cancel` and `events --message` take. "
      "Out-of-bounds values are refused by a strict daemon (INVALID_ARGUMENT names the field and bound).\n\n"
      "Examples:\n"
      "  acommsctl send gv.NavigationReport x=120.5 y=-40 z=-12 veh_class=AUV battery_ok=true\n"
      "  acommsctl send gv.NavigationReport --json '{\"x\": 120.5, \"y\": -40, \"z\": -12}' --ttl 600\n"
      "  acommsctl send gv.NavigationReport --interactive");
  send->callback([&global] { run_send(global, options); });
}

}  // namespace acomms::cli
