// c(z) and its derivatives for the ray model.
//
// Problem: the ray and dynamic ray equations need c, c_z and c_zz at any
// depth, many million times per run. Decision: layers are the SSP intervals;
// callers keep the layer index on the ray and pass it back, so evaluation is
// O(1); layer_at() binary-searches only when a ray starts or is lost.
// Invariant: at a node exactly, the layer is the one the ray travels into
// (c-linear c_z jumps at nodes, spec §1.1/§4.4).
// Thread-safe after construction.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "gram/cubic_spline.h"

namespace acomms::gram {

class SoundSpeedProfile {
 public:
  // The profile must be valid (see validate_environment).
  explicit SoundSpeedProfile(const Environment& env);

  struct Value {
    double c, cz, czz;
  };
  // Inline: the tracer calls this several times per step.
  Value at(double z, std::size_t layer) const {
    if (spline_) return spline_at(z, layer);
    return {speed_[layer] + gradient_[layer] * (z - depth_[layer]), gradient_[layer], 0.0};
  }
  // The layer holding z; at a node, the one below if heading down (dz > 0).
  std::size_t layer_at(double z, double heading_dz) const;

  std::size_t layer_count() const { return depth_.size() - 1; }
  double node(std::size_t i) const { return depth_[i]; }
  double top() const { return depth_.front(); }
  double bottom() const { return depth_.back(); }
  // True when c_z jumps at nodes, so rays must land on them (c-linear).
  bool lands_on_nodes() const { return !spline_; }

 private:
  Value spline_at(double z, std::size_t layer) const;

  std::vector<double> depth_;
  std::vector<double> speed_;
  std::vector<double> gradient_;  // c_z of each layer (c-linear), computed once
  std::optional<CubicSpline> spline_;
};

}  // namespace acomms::gram
