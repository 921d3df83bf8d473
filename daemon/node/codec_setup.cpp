#include "node/codec_setup.h"

#include <spdlog/spdlog.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "dccl/plugin_codecs.h"

namespace acomms::node {
namespace {

std::string read_passphrase_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("dccl.passphrase_file " + path + ": cannot read");
  std::ostringstream text;
  text << in.rdbuf();
  std::string passphrase = text.str();
  // Editors add a final newline nobody means as part of the secret.
  if (!passphrase.empty() && passphrase.back() == '\n') passphrase.pop_back();
  if (!passphrase.empty() && passphrase.back() == '\r') passphrase.pop_back();
  return passphrase;
}

}  // namespace

std::unique_ptr<dccl::Codec> make_codec(const v1::DcclConfig& config) {
  auto codec = std::make_unique<dccl::Codec>();
  // Each plugin codec takes its settings from its own field of the dccl
  // section (the arithmetic codec: arithmetic_models), for this codec only.
  try {
    dccl::install_plugin_codecs(codec->registry(), &config);
  } catch (const dccl::Error& e) {
    throw std::runtime_error(std::string("dccl.") + e.what());
  }
  std::vector<std::string> include_dirs(config.include_dirs().begin(), config.include_dirs().end());
  // Position telemetry's types, always, and first: their ids are reserved,
  // so a user type claiming one is refused naming both.
  try {
    codec->load("acomms/telemetry/messages.proto");
  } catch (const dccl::Error& e) {
    throw std::runtime_error(std::string("dccl: the telemetry types (acomms/telemetry/messages.proto) do not load: ") +
                             e.what());
  }
  for (const std::string& file : config.proto_files()) {
    try {
      const std::map<std::string, std::string> refused_before = codec->refused_types();
      auto types = codec->load(file, include_dirs);
      spdlog::info("dccl: {}: {} message type{}", file, types.size(), types.size() == 1 ? "" : "s");
      // Refused types do not stop the daemon (the file's other types load),
      // but nobody can send them: say so at start.
      for (const auto& [type, why] : codec->refused_types()) {
        if (!refused_before.count(type)) spdlog::warn("dccl: {}: type {} refused: {}", file, type, why);
      }
    } catch (const dccl::Error& e) {
      throw std::runtime_error("dccl definitions " + file + ":\n" + e.what());
    }
  }
  if (config.has_passphrase() || !config.passphrase_file().empty()) {
    std::string passphrase = config.has_passphrase() ? config.passphrase()
                                                     : read_passphrase_file(config.passphrase_file());
    std::set<int> exempt(config.crypto_exempt_ids().begin(), config.crypto_exempt_ids().end());
    codec->set_crypto(passphrase, exempt);
    spdlog::info("dccl: bodies encrypted ({} id{} exempt)", exempt.size(), exempt.size() == 1 ? "" : "s");
  }
  // Strict unless turned off: a client should hear that a value is out of
  // range, not find it zeroed at the other end.
  codec->set_strict(!config.has_strict() || config.strict());
  return codec;
}

}  // namespace acomms::node
