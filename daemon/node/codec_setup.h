#pragma once
// The daemon's DCCL codec, set up from the config's dccl section: plugin
// codecs installed (each configured from its own field of the section),
// definitions loaded, encryption and strict mode applied. Called once, at
// start-up, on the starting thread.

#include <memory>

#include "acomms/v1/config.pb.h"
#include "dccl/codec.h"

namespace acomms::node {

// Throws std::runtime_error (a schema problem, an unreadable passphrase file)
// with a message that names the file and what to fix.
std::unique_ptr<dccl::Codec> make_codec(const v1::DcclConfig& config);

}  // namespace acomms::node
