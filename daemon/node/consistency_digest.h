#pragma once
// A node's consistency digest: 32 bits that say whether two nodes can
// understand each other on a link (README "Consistency across a fleet").
//
// The problem. Nodes of a fleet are configured one by one. If two of them
// bind a DCCL id to different types, or to different versions of a type,
// every message of that id decodes wrong (or not at all) at the other; if
// their fixed TDMA cycles differ, they talk over each other. Neither shows
// until data is lost at sea.
//
// The decision. Each node hashes what must agree, in a canonical text form,
// with SHA-256 and keeps the first 32 bits (a chance of 1 in 4e9 that two
// different configurations look alike: enough to notice a mistake, not a
// defence against forgery). What goes in:
//  - every loaded DCCL type (config and LoadDefinitions), sorted by id then
//    full name: its id (or "omit_id"), its full name, and its descriptor
//    with the descriptors of every message and enum type its fields use,
//    each as deterministic protobuf bytes with fields sorted by number.
//    Field names, numbers, types, labels, defaults and options (the DCCL
//    bounds: max, min, precision, codec, max_bytes, ...) are in it;
//  - the link's MAC settings that every node of the link must share: for
//    "fixed" its cycle (now, after any SetCycle: src, dest, rate, seconds
//    of each slot) and epoch; for "auto_discovery" slot_seconds, rate,
//    coolness, expire_cycles, blank_rule and epoch; for "polled" and
//    "none" nothing (the master alone holds a polled cycle: the others
//    answer its polls, so their configs rightly differ).
// What stays out, because it is the node's own and may differ: comments and
// file names of the .proto files, the order of declarations, data_dir,
// modem ids, drivers and their settings, queue policies, keys, gRPC,
// telemetry, GRAM, routes, link names and costs, mac.max_range_m.
//
// So a node has one digest per link (its definitions are shared, its links'
// MAC cycles are not). The digest is a plain value: a fleet file can hold
// the expected one (consistency.expected_digest), `acommsd --print-digest`
// prints it for a config, and nodes exchange it (consistency_announce.h).
//
// Thread-safe: pure functions of their input; the codec must not change
// while canonical_definitions reads it (core thread at run time).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "acomms/v1/config.pb.h"
#include "dccl/codec.h"
#include "mac/mac.h"

namespace acomms::node {

// The loaded types as hashed (text with binary descriptor bytes).
std::string canonical_definitions(const dccl::Codec& codec);
// The MAC settings a link's nodes share, as hashed. `cycle`: the MAC's
// cycle now (for "fixed"; the configured one before the MAC exists).
std::string canonical_mac(const v1::MacConfig& config, const mac::Cycle& cycle);
// The first 32 bits of SHA-256 over both, in a versioned frame.
uint32_t consistency_digest(std::string_view canonical_definitions, std::string_view canonical_mac);

// 8 lower-case hex digits.
std::string digest_hex(uint32_t digest);
// 8 hex digits (either case) back to the digest; nullopt otherwise.
std::optional<uint32_t> parse_digest(std::string_view hex);

// Every link's digest for `config` with the types `codec` holds (the
// config's own definitions: make_codec), in link order, by link name. The
// links' MACs are taken as configured. Throws std::invalid_argument for a
// bad `link` block (core::node_links).
std::vector<std::pair<std::string, uint32_t>> config_digests(const v1::Config& config, const dccl::Codec& codec);

}  // namespace acomms::node
