// The built-in model as a ModelEngine (see model_engine.h), registered as
// "builtin" (gram/engine_registry.h).
#include "gram/engine_registry.h"
#include "gram/model_engine.h"

namespace acomms::gram {
namespace {

class BuiltinEngine final : public ModelEngine {
 public:
  std::string name() const override { return "builtin"; }
  TransmissionLoss transmission_loss(const Environment& env, const CancelToken& cancel) override {
    RunOptions options;
    options.threads = 1;
    options.cancel = &cancel;
    return compute_transmission_loss(env, options);
  }
};

const EngineRegistrar registrar("builtin", [](const EngineSettings&) { return make_builtin_engine(); });

}  // namespace

std::unique_ptr<ModelEngine> make_builtin_engine() { return std::make_unique<BuiltinEngine>(); }

}  // namespace acomms::gram
