// Combining a measured profile with a base profile, and thinning it.
//
// Problem: a vehicle's CTD cast covers only the depths it dived through,
// while the model needs c(z) from the surface to the bottom; and a cast
// binned every metre makes a c-linear ray trace land on every node
// (spec §2.6, steps 3 and 4). Decisions:
// - MERGE: the cast replaces the base inside the cast's depth span, the base
//   is kept outside it; the cast's end points are the joins.
// - OVERWRITE: the cast alone, extended to the surface and the bottom with
//   its first and last measured speeds (or with the base below the cast).
// Both keep the base's surface and bottom depths. Thinning keeps a point
// only where linear interpolation between the kept neighbours would err by
// more than the tolerance. Invariant: depths strictly increase in every
// result. Thread-safe: pure functions.
#pragma once

#include <vector>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

using Profile = std::vector<SoundSpeedPoint>;

enum class CastMerge { kMerge, kOverwrite, kOverwriteWithBaseBelow };

// `base` and `cast` must be non-empty with strictly increasing depths.
Profile merge_cast(const Profile& base, const Profile& cast, CastMerge mode);

Profile thin_profile(const Profile& profile, double tolerance_mps = 0.05);

}  // namespace acomms::gram
