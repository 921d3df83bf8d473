#pragma once
// The fleet's message keys, read from the file auth.keyring_file names.
//
// Problem: a key that anyone on the vehicle can read is no key, and a fleet
// cannot re-key every vehicle at the same instant. Decision: one small text
// file, owned by the daemon's user and closed to group and others (refused
// otherwise, as ssh refuses an open private key), holding every key a node
// accepts, each with the id its messages carry and, for a key being
// retired, the time after which it is no longer accepted; and which key
// seals what this node sends:
//
//   # acommsd keyring (chmod 600)
//   key 1 000102030405060708090a0b0c0d0e0f until 2026-12-01T00:00:00Z
//   key 2 00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff
//   sign 2
//
// Keys are AES keys in hex (16, 24 or 32 bytes). Re-read on SIGHUP, so a
// roll needs no restart: add the new key, then move `sign` to it and give
// the old one an `until` once every node has the new one.
//
// Thread-safe: reads its own file and keeps nothing.

#include <optional>
#include <string>

#include "dccl/message_auth.h"

namespace acomms::node {

// Throws std::runtime_error starting "auth.keyring_file PATH: " and saying
// what is wrong (cannot be read, open to group/others, owned by another
// user, line N: what the line lacks, a key of the wrong length, a sign id
// with no key, no sign line).
dccl::Keyring read_keyring_file(const std::string& path);

// "2026-12-01T00:00:00Z" as Unix seconds; nullopt if it is not that form.
std::optional<double> parse_utc_time(const std::string& text);

}  // namespace acomms::node
