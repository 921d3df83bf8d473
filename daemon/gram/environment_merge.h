// A request's environment merged over the one the daemon holds, field by
// field.
//
// Problem: a behaviour asking "what if the source were at 30 m" should send
// only that, not restate the bottom and the profile; protobuf's MergeFrom
// appends repeated fields (two profiles glued together) and proto3 cannot
// say a scalar was set to zero. Decision: every field the override sets
// (non-default) replaces the base's; sub-messages merge recursively; a
// non-empty repeated field replaces the whole list; a path listed in
// `mask` (e.g. "bottom.kind", "bathymetry") is taken from the override as
// it is, zero or empty included. Thread-safe: pure function.
#pragma once

#include <string>
#include <vector>

#include "acomms/gram/environment.pb.h"

namespace acomms::gram {

// Throws std::invalid_argument naming a mask path that is no field of
// Environment.
Environment merge_environment(const Environment& base, const Environment& override,
                              const std::vector<std::string>& mask = {});

}  // namespace acomms::gram
