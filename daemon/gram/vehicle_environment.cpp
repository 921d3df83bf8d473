// The environment the vehicle knows (see vehicle_environment.h).
#include "gram/vehicle_environment.h"

#include <algorithm>
#include <stdexcept>

#include "gram/ctd_cast.h"
#include "gram/environment_merge.h"
#include "gram/profile_merge.h"

namespace acomms::gram {

VehicleEnvironment::VehicleEnvironment(Environment base, VehicleEnvironmentOptions options) : options_(options) {
  *state_.mutable_base() = std::move(base);
}

void VehicleEnvironment::restore(KnownEnvironment stored) {
  std::lock_guard lock(mutex_);
  state_ = std::move(stored);
  ++version_;
}

uint64_t VehicleEnvironment::version() const {
  std::lock_guard lock(mutex_);
  return version_;
}

KnownEnvironment VehicleEnvironment::snapshot() const {
  std::lock_guard lock(mutex_);
  return state_;
}

std::vector<Environment> VehicleEnvironment::resolve(const Environment& override,
                                                     const std::vector<std::string>& mask,
                                                     bool every_instance) const {
  const KnownEnvironment state = snapshot();
  const bool own_profile = override.sound_speed_size() > 0 ||
                           std::find(mask.begin(), mask.end(), "sound_speed") != mask.end();
  std::vector<Environment> runs;
  auto with_profile = [&](const ProfileInstance* instance) {
    Environment held = state.base();
    if (instance) *held.mutable_sound_speed() = instance->sound_speed();
    runs.push_back(merge_environment(held, override, mask));
  };
  if (state.instances().empty() || own_profile) {
    with_profile(nullptr);
  } else if (every_instance) {
    for (const ProfileInstance& instance : state.instances()) with_profile(&instance);
  } else {
    with_profile(&state.instances(state.instances_size() - 1));
  }
  return runs;
}

ProfileInstance VehicleEnvironment::instance_from_cast(const Environment& base, const CastInput& cast) const {
  const std::string name = cast.name.empty() ? "cast" : cast.name;
  const auto samples = read_ctd_csv(cast.csv, name);
  CtdProfileOptions options;
  options.bin_m = options_.ctd_bin_m;
  const Profile measured = sound_speed_from_ctd(samples, options);
  if (measured.size() < 2)
    throw std::invalid_argument(name + ": " + std::to_string(measured.size()) +
                                " depth bin(s) of " + std::to_string(options.bin_m) +
                                " m with samples; a profile needs at least 2");
  Profile profile = measured;
  if (base.sound_speed_size() >= 2)
    profile = merge_cast(Profile(base.sound_speed().begin(), base.sound_speed().end()), measured, CastMerge::kMerge);
  if (options_.ctd_thin_mps > 0) profile = thin_profile(profile, options_.ctd_thin_mps);
  ProfileInstance instance;
  instance.set_time_s(cast.time_s);
  instance.set_samples(static_cast<uint32_t>(samples.size()));
  for (const auto& point : profile) *instance.add_sound_speed() = point;
  return instance;
}

KnownEnvironment VehicleEnvironment::update(const EnvironmentChange& change, const Persist& persist) {
  std::lock_guard lock(mutex_);
  KnownEnvironment next = state_;
  *next.mutable_base() = merge_environment(state_.base(), change.base, change.mask);
  if (change.clear_instances) next.clear_instances();
  std::vector<ProfileInstance> instances(next.instances().begin(), next.instances().end());
  for (const CastInput& cast : change.casts) instances.push_back(instance_from_cast(next.base(), cast));
  std::stable_sort(instances.begin(), instances.end(),
                   [](const auto& a, const auto& b) { return a.time_s() < b.time_s(); });
  next.clear_instances();
  const double newest = instances.empty() ? 0.0 : instances.back().time_s();
  for (auto& instance : instances)
    if (instance.time_s() >= newest - options_.instance_window_s) *next.add_instances() = std::move(instance);
  state_ = next;
  ++version_;
  if (persist) persist(state_);
  return next;
}

}  // namespace acomms::gram
