#include "link/driver_registry.h"

#include <stdexcept>

namespace acomms::link {
namespace {

// A function-local static, so it exists whichever plugin registers first.
DriverRegistry& linked_drivers() {
  static DriverRegistry registry;
  return registry;
}

}  // namespace

const DriverRegistry& DriverRegistry::linked() { return linked_drivers(); }

DriverRegistrar::DriverRegistrar(const std::string& name, DriverFactory factory, DriverTraits traits) {
  linked_drivers().add(name, std::move(factory), std::move(traits));
}

void DriverRegistry::add(const std::string& name, DriverFactory factory, DriverTraits traits) {
  drivers_[name] = Entry{std::move(factory), std::move(traits)};
}

const DriverRegistry::Entry& DriverRegistry::find(const std::string& name) const {
  auto it = drivers_.find(name);
  if (it == drivers_.end()) {
    std::string known;
    for (const auto& [n, entry] : drivers_) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("no driver \"" + name + "\" (known: " + known + ")");
  }
  return it->second;
}

std::unique_ptr<Driver> DriverRegistry::create(const std::string& name, const DriverContext& context) const {
  return find(name).factory(context);
}

const DriverTraits& DriverRegistry::traits(const std::string& name) const { return find(name).traits; }

std::vector<std::string> DriverRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, entry] : drivers_) out.push_back(name);
  return out;
}

}  // namespace acomms::link
