#include "node/auth_setup.h"

#include <spdlog/spdlog.h>

#include <set>
#include <stdexcept>

#include "node/keyring_file.h"

namespace acomms::node {
namespace {

constexpr unsigned kDefaultTagBits = 64;

std::string describe(const dccl::Keyring& ring) {
  std::string ids;
  for (const auto& [id, key] : ring.keys) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
  return "keys " + ids + ", signing with " + std::to_string(ring.sign_id);
}

}  // namespace

std::shared_ptr<dccl::MessageAuthenticator> make_authenticator(const v1::AuthConfig& auth, dccl::Codec& codec,
                                                               int32_t own_id) {
  if (auth.type().empty()) {
    if (!auth.keyring_file().empty()) spdlog::warn("auth.keyring_file is set but auth lists no type: nothing is authenticated");
    return nullptr;
  }
  if (auth.keyring_file().empty()) throw std::runtime_error("auth.type is listed but auth.keyring_file is not set");
  std::set<std::string> types;
  for (const v1::AuthenticatedType& type : auth.type()) {
    if (!types.insert(type.type()).second) throw std::runtime_error("auth.type " + type.type() + " is listed twice");
  }
  const unsigned tag_bits = auth.has_tag_bits() ? auth.tag_bits() : kDefaultTagBits;
  std::shared_ptr<dccl::MessageAuthenticator> authenticator;
  dccl::Keyring ring = read_keyring_file(auth.keyring_file());
  const std::string described = describe(ring);
  try {
    authenticator = std::make_shared<dccl::MessageAuthenticator>(tag_bits, std::move(ring), own_id);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  try {
    codec.set_authentication(authenticator, types);
  } catch (const dccl::Error& e) {
    throw std::runtime_error(std::string("auth: ") + e.what());
  }
  spdlog::info("auth: {} type{} authenticated, {}-bit tags ({} bits a message), {}", types.size(),
               types.size() == 1 ? "" : "s", tag_bits, authenticator->trailer_bytes() * 8, described);
  return authenticator;
}

void authenticate_queues(const v1::AuthConfig& auth, queue::QueueManager& queues) {
  for (const v1::AuthenticatedType& type : auth.type()) {
    try {
      queues.authenticate(type.type(), type.window_s());
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(e.what());
    }
  }
}

bool reload_keyring(const v1::AuthConfig& auth, dccl::MessageAuthenticator& authenticator) {
  try {
    dccl::Keyring ring = read_keyring_file(auth.keyring_file());
    const std::string described = describe(ring);
    authenticator.set_keyring(std::move(ring));
    spdlog::info("auth: keyring reloaded: {}", described);
    return true;
  } catch (const std::exception& e) {
    spdlog::error("auth: keyring not reloaded, the previous keys stay in use: {}", e.what());
    return false;
  }
}

}  // namespace acomms::node
