// The environment the vehicle knows (Schneider (2013) §4.2–§4.3): a base
// from the config (bottom, bathymetry, frequency, source, receivers),
// updated at run time with the CTD casts the vehicle takes. Each cast's raw samples
// are binned into a profile, merged into the base profile inside the
// cast's depth span (gram/profile_merge.h) and kept as one instance;
// instances older than the window before the newest are dropped
// (Schneider's 30-minute averages). A run takes the newest instance's
// profile; the depth objective takes every instance (eq. 4.4).
//
// Persistence is the owner's: every change hands the new state to the
// `persist` callback while the lock is held, so states reach the store in
// the order they were made and the last one written is the latest.
// Thread-safe (one mutex; runs read a copy).
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "acomms/gram/environment.pb.h"
#include "acomms/gram/known_environment.pb.h"

namespace acomms::gram {

struct VehicleEnvironmentOptions {
  double ctd_bin_m = 1.0;
  double ctd_thin_mps = 0.05;  // 0: keep every bin
  double instance_window_s = 1800.0;
};

struct CastInput {
  double time_s = 0;  // seconds since the epoch
  std::string csv;    // raw samples (gram/ctd_cast.h columns)
  std::string name;   // for errors
};

struct EnvironmentChange {
  Environment base;                // merged into the base field by field
  std::vector<std::string> mask;   // override_mask paths
  std::vector<CastInput> casts;
  bool clear_instances = false;
};

class VehicleEnvironment {
 public:
  using Persist = std::function<void(const KnownEnvironment& state)>;

  VehicleEnvironment(Environment base, VehicleEnvironmentOptions options);

  // Replaces the state with one read back from the store at start.
  void restore(KnownEnvironment stored);
  KnownEnvironment snapshot() const;

  // The environments of a run: the base with the newest instance's profile,
  // `override` merged over it field by field (environment_merge.h). With
  // `every_instance`, one per instance (oldest first) unless the override
  // gives its own sound speed. Throws std::invalid_argument (bad mask path).
  std::vector<Environment> resolve(const Environment& override, const std::vector<std::string>& mask,
                                   bool every_instance) const;

  // Applies `change` and calls `persist` with the new state; returns it.
  // Throws std::invalid_argument or ImportError (naming the cast, line and
  // column) and then changes nothing.
  KnownEnvironment update(const EnvironmentChange& change, const Persist& persist);

  // Changes with every restore and update (never otherwise): a reader that
  // keeps what it derived from resolve() (node/link_prediction.h) derives
  // it again only when this moved. Read it before resolving: a change in
  // between then costs one more resolve, never a stale result.
  uint64_t version() const;

 private:
  ProfileInstance instance_from_cast(const Environment& base, const CastInput& cast) const;

  VehicleEnvironmentOptions options_;
  mutable std::mutex mutex_;
  KnownEnvironment state_;
  uint64_t version_ = 0;
};

}  // namespace acomms::gram
