#include "gram/engine_registry.h"

#include <stdexcept>

namespace acomms::gram {
namespace {

// A function-local static, so it exists whichever engine registers first.
EngineRegistry& linked_engines() {
  static EngineRegistry registry;
  return registry;
}

}  // namespace

const EngineRegistry& EngineRegistry::linked() { return linked_engines(); }

EngineRegistrar::EngineRegistrar(const std::string& name, EngineFactory factory, EngineTraits traits) {
  linked_engines().add(name, std::move(factory), traits);
}

void EngineRegistry::add(const std::string& name, EngineFactory factory, EngineTraits traits) {
  engines_[name] = Entry{std::move(factory), traits};
}

const EngineRegistry::Entry& EngineRegistry::find(const std::string& name) const {
  auto it = engines_.find(name);
  if (it == engines_.end()) {
    std::string known;
    for (const std::string& n : names()) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("no engine \"" + name + "\" (known: " + known + ")");
  }
  return it->second;
}

const EngineTraits& EngineRegistry::traits(const std::string& name) const { return find(name).traits; }

std::unique_ptr<ModelEngine> EngineRegistry::create(const std::string& name, const EngineSettings& settings) const {
  return find(name).factory(settings);
}

std::vector<std::string> EngineRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, entry] : engines_) out.push_back(name);
  return out;
}

}  // namespace acomms::gram
