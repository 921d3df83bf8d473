#pragma once
// Model engines by name, as drivers (link/driver_registry.h) and field
// codecs (dccl/plugin_codecs.h) are found.
//
// The problem: the daemon's gram.engine picks what computes transmission
// loss, and a list of known engines in the code that reads the config would
// have to be edited for every engine added (and its error message with it).
// The decision: each engine adds its factory with a static EngineRegistrar
// in its own .cpp (their library, acomms_gram_engines, is linked whole, so
// the linker keeps those objects); whoever reads the config takes
// EngineRegistry::linked() and looks the name up there. An engine declares
// whether it runs an external program: such an engine is given that
// program and the time limit of one run, the others need nothing.
//
// Thread-safety: linked() is filled during static initialisation only and
// read only afterwards, so lookups may run on any thread; a registry of
// one's own (a copy) is not safe to change while others read it.

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gram/model_engine.h"

namespace acomms::gram {

// What an engine is built with. Only an external engine reads it.
struct EngineSettings {
  std::string executable;  // the program an external engine runs
  std::string work_root;   // where its runs may write (created if missing)
  std::chrono::duration<double> timeout{60.0};  // wall-clock limit of one run
};

// What an engine says about itself.
struct EngineTraits {
  // Runs a program of its own (EngineSettings::executable), rather than
  // computing in this process.
  bool external = false;
};

using EngineFactory = std::function<std::unique_ptr<ModelEngine>(const EngineSettings& settings)>;

class EngineRegistry {
 public:
  // The engines linked into this program, each added by its EngineRegistrar.
  static const EngineRegistry& linked();

  // Registers (or replaces) an engine.
  void add(const std::string& name, EngineFactory factory, EngineTraits traits = {});
  bool contains(const std::string& name) const { return engines_.count(name) != 0; }
  // Throws std::invalid_argument (as create()) when there is no such engine.
  const EngineTraits& traits(const std::string& name) const;
  // Builds the engine `name`. Throws std::invalid_argument naming the known
  // engines when there is no such engine, or whatever the factory throws.
  std::unique_ptr<ModelEngine> create(const std::string& name, const EngineSettings& settings) const;
  // Sorted.
  std::vector<std::string> names() const;

 private:
  struct Entry {
    EngineFactory factory;
    EngineTraits traits;
  };
  const Entry& find(const std::string& name) const;

  std::map<std::string, Entry> engines_;
};

// Adds engine `name` to EngineRegistry::linked(). Define one as a static
// object in the engine's .cpp.
class EngineRegistrar {
 public:
  EngineRegistrar(const std::string& name, EngineFactory factory, EngineTraits traits = {});
};

}  // namespace acomms::gram
