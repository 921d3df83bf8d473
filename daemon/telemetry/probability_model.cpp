#include "telemetry/probability_model.h"

#include "telemetry/learned_model.h"
#include "telemetry/probability_models.h"

namespace acomms::telemetry {

std::unique_ptr<ProbabilityModel> make_model(const TelemetryConfig& config) {
  const int32_t lo = config.innovation_min, hi = config.innovation_max;
  switch (config.model) {
    case ModelKind::kUniform:
      return std::make_unique<UniformModel>(lo, hi);
    case ModelKind::kGaussian:
      return std::make_unique<GaussianModel>(lo, hi);
    case ModelKind::kAdaptive:
      return std::make_unique<AdaptiveModel>(lo, hi);
    case ModelKind::kLearned:
      return std::make_unique<LearnedModel>(lo, hi);
  }
  return nullptr;
}

}  // namespace acomms::telemetry
