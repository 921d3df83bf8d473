#pragma once
// The systemd readiness protocol (sd_notify), spoken directly: one datagram
// to the unix socket named by $NOTIFY_SOCKET. Implemented here rather than
// linking libsystemd because libsystemd is only shipped as a shared library
// and acommsd links everything statically. Without $NOTIFY_SOCKET (not run by
// systemd with Type=notify) every call is a no-op.
//
// Thread-safe: each call opens, uses and closes a socket of its own.

#include <string_view>

namespace acomms::core {

// Sends `state` (e.g. "READY=1", "STOPPING=1", "STATUS=serving"). Returns false
// if a notify socket is set but the datagram could not be sent.
bool systemd_notify(std::string_view state);

}  // namespace acomms::core
