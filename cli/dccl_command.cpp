#include "dccl_command.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "dccl/codec.h"
#include "dccl/plugin_codecs.h"
#include "global_options.h"
#include "dccl/hex.h"
#include "dccl/vector_line.h"

namespace acomms::cli {
namespace {

struct DcclOptions {
  std::vector<std::string> proto_files;
  std::vector<std::string> include_dirs;
  std::string passphrase;
  bool use_crypto = false;
  bool strict = false;
  std::string type_name;
};

void load(dccl::Codec& codec, const DcclOptions& options) {
  dccl::install_plugin_codecs(codec.registry());
  for (const auto& file : options.proto_files) codec.load(file, options.include_dirs);
  if (options.use_crypto) codec.set_crypto(options.passphrase);
  codec.set_strict(options.strict);
}

std::string trim(const std::string& text) {
  size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  size_t end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

// One input line of `encode`: "|pkg.Type| field: value ...". A trailing
// " => hex" (the conformance vectors' format) is ignored, so a vectors file
// can be piped straight in.
std::string encode_line(const dccl::Codec& codec, const std::string& line) {
  // " => " inside a string literal is part of the string.
  dccl::VectorLine parsed = dccl::parse_vector_line(line);
  const std::string& type = parsed.type;
  const std::string& text = parsed.text;
  std::unique_ptr<google::protobuf::Message> message = codec.new_message(type);

  class Collector : public google::protobuf::io::ErrorCollector {
   public:
    void AddError(int, google::protobuf::io::ColumnNumber column, const std::string& message) override {
      if (first.empty()) first = "column " + std::to_string(column + 1) + ": " + message;
    }
    std::string first;
  } errors;
  google::protobuf::TextFormat::Parser parser;
  parser.RecordErrorsTo(&errors);
  if (!parser.ParseFromString(text, message.get())) {
    throw std::invalid_argument(type + " text format: " + errors.first);
  }
  return dccl::to_hex(codec.encode(*message));
}

// Reads stdin a line at a time (blank lines skipped) and prints what
// `handle` makes of each, or "error: line N: ..." when it throws: one
// answer per input line, in order. Returns the exit code: 1 if any failed.
int for_each_input_line(const std::function<std::string(const std::string&)>& handle) {
  int failures = 0;
  std::string line;
  for (int number = 1; std::getline(std::cin, line); ++number) {
    line = trim(line);
    if (line.empty()) continue;
    try {
      std::cout << handle(line);
    } catch (const std::exception& e) {
      std::cout << "error: line " << number << ": " << e.what() << "\n";
      ++failures;
    }
  }
  std::cout.flush();
  return failures == 0 ? 0 : 1;
}

int run_encode(const DcclOptions& options) {
  dccl::Codec codec;
  load(codec, options);
  return for_each_input_line([&](const std::string& line) { return encode_line(codec, line) + "\n"; });
}

int run_decode(const DcclOptions& options) {
  dccl::Codec codec;
  load(codec, options);
  return for_each_input_line([&](const std::string& line) {
    std::string bytes = dccl::from_hex(line);
    std::vector<std::unique_ptr<google::protobuf::Message>> messages;
    if (options.type_name.empty()) {
      messages = codec.decode(bytes);
    } else {
      // Named type (needed for omit_id types): messages of that one type
      // back to back.
      for (size_t offset = 0; offset < bytes.size();) {
        size_t used = 0;
        messages.push_back(codec.decode_as(options.type_name, std::string_view(bytes).substr(offset), &used));
        if (used == 0) break;
        offset += used;
      }
    }
    std::string out;
    for (const auto& message : messages) {
      std::string text = message->ShortDebugString();
      out += "|" + message->GetDescriptor()->full_name() + "|" + (text.empty() ? "" : " " + text) + "\n";
    }
    return out;
  });
}

std::string bits_text(const dccl::SizeBits& bits) {
  return bits.min == bits.max ? std::to_string(bits.min)
                              : std::to_string(bits.min) + ".." + std::to_string(bits.max);
}

int run_analyze(const DcclOptions& options) {
  dccl::Codec codec;
  load(codec, options);
  const dccl::TypeInfo* info = codec.find_type(options.type_name);
  if (info == nullptr) {
    std::string known;
    for (const auto* type : codec.types()) known += (known.empty() ? "" : ", ") + type->name;
    throw std::invalid_argument("no DCCL type " + options.type_name + " (loaded: " + known + ")");
  }
  std::printf("%s\n", info->name.c_str());
  if (info->omit_id) {
    std::printf("  id:             omitted (omit_id)\n");
  } else {
    std::printf("  id:             %d (%u bits)\n", info->id, info->id_bits);
  }
  std::printf("  codec version:  %d\n", info->codec_version);
  std::printf("  max_bytes:      %u\n\n", info->max_bytes);
  std::printf("  %-32s %-18s %-8s %-10s %s\n", "field", "codec", "part", "bits", "resolution");
  for (const auto& field : info->fields) {
    std::string name = std::string(2 * field.depth, ' ') + field.path.substr(info->name.size() + 1);
    std::string resolution = field.resolution > 0 ? std::to_string(field.resolution) : "";
    if (!resolution.empty()) {
      resolution.erase(resolution.find_last_not_of('0') + 1);
      if (resolution.back() == '.') resolution.pop_back();
    }
    std::printf("  %-32s %-18s %-8s %-10s %s\n", name.c_str(), field.codec.c_str(),
                field.in_head ? "head" : "body", bits_text(field.bits).c_str(), resolution.c_str());
  }
  uint64_t head_min = info->id_bits + info->head.min, head_max = info->id_bits + info->head.max;
  std::printf("\n  head:  %s bits (id %u + fields %s) -> %llu byte(s)\n",
              bits_text({head_min, head_max}).c_str(), info->id_bits, bits_text(info->head).c_str(),
              static_cast<unsigned long long>((head_max + 7) / 8));
  std::printf("  body:  %s bits -> %llu..%llu byte(s)\n", bits_text(info->body).c_str(),
              static_cast<unsigned long long>((info->body.min + 7) / 8),
              static_cast<unsigned long long>((info->body.max + 7) / 8));
  std::printf("  encoded size: min %llu, max %llu bytes (max_bytes %u)\n",
              static_cast<unsigned long long>(info->min_size_bytes()),
              static_cast<unsigned long long>(info->max_size_bytes()), info->max_bytes);
  return 0;
}

// The examples of --help, on the example types shipped with acommsd (the
// decode example's line is what the encode example prints).
constexpr const char* kEncodeExample =
    "echo '|example.Status| src: 3 dest: 0 time: 1764000000 x: 120 y: -40 depth: 12.5' | "
    "acommsctl dccl encode -f examples/messages.proto";
constexpr const char* kDecodeExample = "echo 28030084433ca19bfa00000000000000 | acommsctl dccl decode -f examples/messages.proto";
constexpr const char* kAnalyzeExample = "acommsctl dccl analyze -f examples/messages.proto -t example.Status";

void add_schema_options(CLI::App* command, DcclOptions& options) {
  command->add_option("-f,--proto", options.proto_files, "DCCL .proto file(s) to load")->required()->type_name("FILE");
  command->add_option("-I,--include", options.include_dirs, "Directory to resolve imports in")->type_name("DIR");
}

// encode and decode: schema options, --passphrase, and a line-by-line run
// whose failures (already printed as error lines) become the exit code.
CLI::App* add_line_command(CLI::App* dccl, const char* name, const char* description,
                           const char* passphrase_help, DcclOptions& options,
                           int (*run)(const DcclOptions&)) {
  CLI::App* command = dccl->add_subcommand(name, description);
  add_schema_options(command, options);
  CLI::Option* passphrase = command->add_option("--passphrase", options.passphrase, passphrase_help);
  command->callback([passphrase, &options, run] {
    options.use_crypto = passphrase->count() > 0;
    int code = run(options);
    if (code != 0) throw CLI::RuntimeError(code);
  });
  return command;
}

}  // namespace

void add_dccl_command(CLI::App& app, const GlobalOptions&) {
  static DcclOptions options;
  CLI::App* dccl = app.add_subcommand(
      "dccl", "Encode, decode and analyze DCCL messages offline (no daemon needed)");
  dccl->require_subcommand(1);
  dccl->footer(std::string("Examples:\n  ") + kEncodeExample + "\n  " + kDecodeExample + "\n  " + kAnalyzeExample);

  CLI::App* encode = add_line_command(
      dccl, "encode", "Read '|pkg.Type| <text format>' lines on stdin; print one hex line each",
      "Encrypt bodies (AES-256-CTR)", options, run_encode);
  encode->add_flag("--strict", options.strict,
                   "Refuse out-of-range values, over-long strings and extra repeats");
  encode->footer(std::string("Example:\n  ") + kEncodeExample);

  CLI::App* decode = add_line_command(
      dccl, "decode", "Read hex lines on stdin; print '|pkg.Type| <text format>' for each message",
      "Decrypt bodies (AES-256-CTR)", options, run_decode);
  decode->add_option("-t,--type", options.type_name,
                     "Decode as this type (required for omit_id types, which carry no id)");
  decode->footer(std::string("Example:\n  ") + kDecodeExample);

  CLI::App* analyze = dccl->add_subcommand(
      "analyze", "Print a type's bit budget per field, head and body sizes, min/max size");
  add_schema_options(analyze, options);
  analyze->add_option("-t,--type", options.type_name, "Full type name, e.g. gv.NavigationReport")
      ->required();
  analyze->footer(std::string("Example:\n  ") + kAnalyzeExample);
  analyze->callback([] { run_analyze(options); });
}

}  // namespace acomms::cli
