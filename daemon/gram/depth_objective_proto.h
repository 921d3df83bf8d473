// The depth objective's wire form (api/proto/acomms/gram/depth_objective.proto)
// to and from the library's request and result.
//
// Problem: a query arrives from a client we do not control; proto3 cannot
// say "unset" for a scalar, so a forgotten horizon_s arrives as 0 and must
// be refused, not run. Decision: the conversion validates everything that
// validate_depth_objective_request checks plus what only the wire can get
// wrong (no H_max choice; h_max_window_maximum = false; a sonar with no noise
// level), and the error names the proto field. Thread-safe: pure functions.
#pragma once

#include "acomms/gram/depth_objective.pb.h"
#include "gram/depth_objective.h"

namespace acomms::gram {

// Throws std::invalid_argument naming the field and the bound.
DepthObjectiveRequest request_from_proto(const DepthObjectiveQuery& query);

DepthObjectiveReply reply_to_proto(const DepthObjectiveResult& result);

}  // namespace acomms::gram
