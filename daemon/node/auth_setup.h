#pragma once
// Authenticated types set up from the config's auth section: the keyring
// read (keyring_file.h), the codec told which types carry the trailer
// (dccl/message_auth.h), and each type's queue its window
// (queue/auth_guard.h). Start-up errors name the setting; a SIGHUP re-reads
// the keyring and keeps the old one if the new one does not load.
//
// Called at start-up on the starting thread (make_authenticator before the
// queues restore, authenticate_queues after they are made, before
// restore); reload_keyring from the signal-handling thread.

#include <memory>

#include "acomms/v1/config.pb.h"
#include "dccl/codec.h"
#include "dccl/message_auth.h"
#include "queue/queue_manager.h"

namespace acomms::node {

// Null when the section lists no type. Otherwise reads the keyring, checks
// tag_bits, and makes `codec` seal and carry the trailer for the listed
// types. Throws std::runtime_error naming the field or file.
// `own_id`: the node's id, which its seals are made for (the receiver
// verifies them as from the transmission's source).
std::shared_ptr<dccl::MessageAuthenticator> make_authenticator(const v1::AuthConfig& auth, dccl::Codec& codec,
                                                               int32_t own_id);

// Gives each listed type's queue its window. Throws std::runtime_error
// naming the type (window not > 0, shorter than the queue's ttl).
void authenticate_queues(const v1::AuthConfig& auth, queue::QueueManager& queues);

// SIGHUP: re-reads the keyring into `authenticator`; logs the outcome, and
// on failure keeps the keys it had. Returns whether the new keys are in use.
bool reload_keyring(const v1::AuthConfig& auth, dccl::MessageAuthenticator& authenticator);

}  // namespace acomms::node
