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

DriverRegistrar::DriverRegistrar(const std::string& name, DriverFactory factory) {
  linked_drivers().add(name, std::move(factory));
}

void DriverRegistry::add(const std::string& name, DriverFactory factory) {
  factories_[name] = std::move(factory);
}

std::unique_ptr<Driver> DriverRegistry::create(const std::string& name, const DriverContext& context) const {
  auto it = factories_.find(name);
  if (it == factories_.end()) {
    std::string known;
    for (const auto& [n, f] : factories_) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("no driver \"" + name + "\" (known: " + known + ")");
  }
  return it->second(context);
}

std::vector<std::string> DriverRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, factory] : factories_) out.push_back(name);
  return out;
}

}  // namespace acomms::link
