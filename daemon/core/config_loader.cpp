#include "core/config_loader.h"

#include <google/protobuf/io/tokenizer.h>
#include <google/protobuf/text_format.h>
#include <sys/un.h>

#include <cctype>
#include <cmath>
#include <charconv>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/config_error.h"
#include "core/first_parse_error.h"
#include "core/node_links.h"

namespace acomms::core {

// Defined in the generated file that embeds packaging/acommsd.conf.
const std::vector<std::pair<std::string_view, std::string_view>>& embedded_example_config();

namespace {

namespace pb = google::protobuf;

std::vector<std::string> lines_of(std::string_view text) {
  std::vector<std::string> lines;
  std::istringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Where a parse error really is. The parser reports the token it stopped at,
// which for a bad value is often the next line, and its messages name the
// field only sometimes ('Unknown enumeration value of "X" for field "y"'),
// never for a bad literal ("Expected integer, got: abc"). So: take the field
// the message names, else the last `name:` / `name {` at or before the
// error, and point at that name.
struct ParseErrorPlace {
  int line;    // 1-based
  int column;  // 1-based
  std::string field;
};

ParseErrorPlace place_parse_error(std::string_view text, int line0, int column0,
                                  const std::string& message) {
  static const std::regex named_in_message(R"re(field (?:named )?"([A-Za-z_][A-Za-z0-9_]*)")re");
  static const std::regex field_token(R"(([A-Za-z_][A-Za-z0-9_]*)\s*(:|\{))");
  std::vector<std::string> lines = lines_of(text);
  std::smatch match;
  std::string wanted;
  if (std::regex_search(message, match, named_in_message)) wanted = match[1];

  // Scan back from the error for a field token (the named one, if any).
  for (int line = std::min<int>(line0, static_cast<int>(lines.size()) - 1); line >= 0; --line) {
    const std::string& current = lines[line];
    int limit = line == line0 ? column0 : static_cast<int>(current.size());
    ParseErrorPlace best{0, 0, ""};
    for (std::sregex_iterator it(current.begin(), current.end(), field_token), end; it != end;
         ++it) {
      if (it->position(1) > limit) break;
      if (wanted.empty() || (*it)[1] == wanted) {
        best = {line + 1, static_cast<int>(it->position(1)) + 1, (*it)[1]};
      }
    }
    if (!best.field.empty()) return best;
    if (wanted.empty()) break;  // only the error's own line can hold an unnamed field
  }
  return {line0 + 1, column0 + 1, wanted};
}

// Location of a (possibly nested) field in the parsed text, for errors found
// after parsing. Falls back to "no location" for fields absent from the text.
struct Place {
  int line = 0;
  int column = 0;
};

// `index` picks the element of the first repeated field on the path
// (link.name: the link's); any later repeated field, its first element.
Place place_of(const pb::TextFormat::ParseInfoTree& tree, const pb::Descriptor* type,
               const std::vector<std::string>& path, int index) {
  const pb::TextFormat::ParseInfoTree* node = &tree;
  bool index_used = false;
  auto element = [&](const pb::FieldDescriptor* field) {
    if (!field->is_repeated()) return -1;
    int at = index_used ? 0 : index;
    index_used = true;
    return at;
  };
  for (size_t i = 0; i < path.size(); ++i) {
    const pb::FieldDescriptor* field = type->FindFieldByName(path[i]);
    if (field == nullptr || node == nullptr) return {};
    if (i + 1 == path.size()) {
      pb::TextFormat::ParseLocation loc = node->GetLocation(field, element(field));
      if (loc.line < 0) return {};
      return {loc.line + 1, loc.column + 1};
    }
    node = node->GetTreeForNested(field, element(field));
    type = field->message_type();
  }
  return {};
}

bool valid_port(std::string_view text) {
  unsigned port = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), port);
  return ec == std::errc() && end == text.data() + text.size() && port >= 1 && port <= 65535;
}

// "host:port" or "[v6]:port"; returns the reason it is not, or empty.
std::string tcp_address_problem(const std::string& address) {
  size_t colon = address.rfind(':');
  if (colon == std::string::npos || colon == 0) {
    return "\"" + address + "\" is not host:port (for example \"127.0.0.1:50051\")";
  }
  std::string host = address.substr(0, colon);
  if (host.front() == '[' && host.back() != ']') return "\"" + address + "\": unclosed '[' in IPv6 host";
  if (!valid_port(std::string_view(address).substr(colon + 1))) {
    return "\"" + address + "\": port must be a number from 1 to 65535";
  }
  return {};
}

bool valid_plugin_name(const std::string& name) {
  static const std::regex pattern("[a-z][a-z0-9_]*");
  return std::regex_match(name, pattern);
}

// TCP is either TLS or plaintext by an explicit choice: a config written
// before TLS existed (tcp_listen alone) stops here instead of silently
// serving anyone on the network.
template <typename Fail>
void validate_tcp(const v1::GrpcConfig& grpc, Fail& fail) {
  if (grpc.tcp_listen().empty()) {
    if (grpc.has_tls()) fail({"grpc", "tls"}, "applies only to tcp_listen, which is not set");
    if (grpc.insecure_tcp()) fail({"grpc", "insecure_tcp"}, "applies only to tcp_listen, which is not set");
    return;
  }
  std::string problem = tcp_address_problem(grpc.tcp_listen());
  if (!problem.empty()) fail({"grpc", "tcp_listen"}, problem);
  if (!grpc.has_tls() && !grpc.insecure_tcp()) {
    fail({"grpc", "tcp_listen"},
         "TCP now needs TLS: add grpc { tls { cert_file: \"...\" key_file: \"...\" } } "
         "(and client_ca_file for client certificates), or set grpc { insecure_tcp: true } to "
         "keep plaintext TCP with no authentication (see \"Upgrading\" in the README)");
  }
  if (grpc.has_tls() && grpc.insecure_tcp()) {
    fail({"grpc", "insecure_tcp"}, "set tls or insecure_tcp: true, not both");
  }
  if (grpc.has_tls()) {
    if (grpc.tls().cert_file().empty()) fail({"grpc", "tls", "cert_file"}, "required with tls");
    if (grpc.tls().key_file().empty()) fail({"grpc", "tls", "key_file"}, "required with tls");
  }
}

void validate(const v1::Config& config, const pb::TextFormat::ParseInfoTree& tree,
              const std::string& file_name) {
  auto fail = [&](const std::vector<std::string>& path, const std::string& problem, int index = 0) {
    Place where = place_of(tree, v1::Config::descriptor(), path, index);
    std::string dotted;
    for (const auto& part : path) dotted += (dotted.empty() ? "" : ".") + part;
    throw ConfigError(file_name, where.line, where.column, dotted, problem);
  };
  validate_tcp(config.grpc(), fail);
  if (config.store().event_retention_days() < 0) {
    fail({"store", "event_retention_days"}, "must be 0 (no age bound) or more");
  }
  if (config.store().event_retention_mb() < 0) {
    fail({"store", "event_retention_mb"}, "must be 0 (no size bound) or more");
  }
  if (config.grpc().unix_socket().size() >= sizeof(sockaddr_un::sun_path)) {
    fail({"grpc", "unix_socket"},
         "path is " + std::to_string(config.grpc().unix_socket().size()) +
             " bytes; unix sockets allow at most " +
             std::to_string(sizeof(sockaddr_un::sun_path) - 1));
  }
  if (config.dccl().has_passphrase() && !config.dccl().passphrase_file().empty()) {
    fail({"dccl", "passphrase_file"}, "set passphrase or passphrase_file, not both");
  }
  for (int i = 0; i < config.dccl().crypto_exempt_ids_size(); ++i) {
    int id = config.dccl().crypto_exempt_ids(i);
    if (id < 0 || id > 32767) {
      fail({"dccl", "crypto_exempt_ids"}, std::to_string(id) + " is not a DCCL id (0 to 32767)", i);
    }
  }
  if (config.auth().has_tag_bits()) {
    const uint32_t bits = config.auth().tag_bits();
    if (bits < 32 || bits > 64 || bits % 8 != 0) fail({"auth", "tag_bits"}, "must be 32 to 64, a multiple of 8");
  }
  if (config.auth().type_size() > 0 && config.auth().keyring_file().empty()) {
    fail({"auth", "type"}, "authenticated types need auth.keyring_file");
  }
  for (int i = 0; i < config.auth().type_size(); ++i) {
    const double window = config.auth().type(i).window_s();
    if (!(window > 0) || !std::isfinite(window)) {
      fail({"auth", "type"},
           config.auth().type(i).type() + ": window_s must be more than 0 seconds (0 would refuse every message as stale)",
           i);
    }
  }
  if (!config.driver().name().empty() && !valid_plugin_name(config.driver().name())) {
    fail({"driver", "name"}, "\"" + config.driver().name() +
                                 "\" is not a driver name (lowercase letters, digits, '_')");
  }
  if (!config.mac().name().empty() && !valid_plugin_name(config.mac().name())) {
    fail({"mac", "name"},
         "\"" + config.mac().name() + "\" is not a MAC name (lowercase letters, digits, '_')");
  }
  for (int i = 0; i < config.link_size(); ++i) {
    const v1::LinkConfig& link = config.link(i);
    if (!link.driver().name().empty() && !valid_plugin_name(link.driver().name())) {
      fail({"link", "driver", "name"},
           "\"" + link.driver().name() + "\" is not a driver name (lowercase letters, digits, '_')", i);
    }
    if (!link.mac().name().empty() && !valid_plugin_name(link.mac().name())) {
      fail({"link", "mac", "name"}, "\"" + link.mac().name() + "\" is not a MAC name (lowercase letters, digits, '_')",
           i);
    }
  }
  if (std::optional<LinkConfigProblem> problem = link_config_problem(config)) {
    fail(problem->field, problem->problem, problem->index);
  }
}

void fill_defaults(v1::Config& config) {
  if (config.data_dir().empty()) config.set_data_dir(std::string(kDefaultDataDir));
  if (config.grpc().unix_socket().empty()) {
    config.mutable_grpc()->set_unix_socket(std::string(kDefaultUnixSocket));
  }
  if (config.log_level() == v1::LOG_LEVEL_UNSPECIFIED) config.set_log_level(v1::INFO);
  if (config.link_size() > 0) {
    // Several links: each gets the defaults the single form gets, and the
    // node's one id (core/node_links.h).
    const int32_t id = node_id(config);
    for (v1::LinkConfig& link : *config.mutable_link()) {
      if (link.driver().name().empty()) link.mutable_driver()->set_name(std::string(kDefaultDriver));
      link.mutable_driver()->set_modem_id(static_cast<uint32_t>(id));
      if (link.mac().name().empty()) link.mutable_mac()->set_name(std::string(kDefaultMac));
    }
    return;
  }
  if (config.driver().name().empty()) config.mutable_driver()->set_name(std::string(kDefaultDriver));
  if (config.driver().modem_id() == 0) config.mutable_driver()->set_modem_id(1);
  if (config.mac().name().empty()) config.mutable_mac()->set_name(std::string(kDefaultMac));
}

}  // namespace

v1::Config parse_config(std::string_view text, const std::string& file_name) {
  v1::Config config;
  pb::TextFormat::Parser parser;
  FirstParseError errors;
  pb::TextFormat::ParseInfoTree tree;
  parser.RecordErrorsTo(&errors);
  parser.WriteLocationsTo(&tree);
  if (!parser.ParseFromString(std::string(text), &config)) {
    if (!errors.error()) throw ConfigError(file_name, 0, 0, "", "not a valid config");
    const auto& e = *errors.error();
    ParseErrorPlace where = place_parse_error(text, e.line, e.column, e.message);
    throw ConfigError(file_name, where.line, where.column, where.field, e.message);
  }
  validate(config, tree, file_name);
  fill_defaults(config);
  return config;
}

v1::Config load_config_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path, 0, 0, "", "cannot open config file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ConfigError(path, 0, 0, "", "cannot read config file");
  return parse_config(text.str(), path);
}

std::string_view example_config() { return embedded_example_config().front().second; }

void check_effective_config(const v1::Config& config) {
  if (config.data_dir().empty()) throw std::invalid_argument("data dir: must not be empty");
  const std::string& socket = config.grpc().unix_socket();
  if (socket.empty()) throw std::invalid_argument("unix socket: must not be empty");
  if (socket.size() >= sizeof(sockaddr_un::sun_path)) {
    throw std::invalid_argument("unix socket: path \"" + socket + "\" is longer than " +
                                std::to_string(sizeof(sockaddr_un::sun_path) - 1) + " bytes");
  }
}

}  // namespace acomms::core
