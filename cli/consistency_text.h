#pragma once
// The fleet-consistency lines of `acommsctl status` and `acommsctl link
// status` (README "Consistency across a fleet"): this node's digest and,
// per node heard announcing one, whether it agrees and since when it has
// not.
//
// Thread-safe: prints to stdout; no state.

#include <string>

#include "acomms/v1/acomms.pb.h"

namespace acomms::cli {

// `indent` starts every line; `own` is the node's own digest text (empty:
// consistency disabled, nothing printed). `now_s`: Unix seconds.
void print_consistency(const std::string& indent, const std::string& own,
                       const google::protobuf::RepeatedPtrField<v1::NodeConsistency>& nodes, double now_s);

}  // namespace acomms::cli
