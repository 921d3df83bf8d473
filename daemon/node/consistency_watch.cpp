// Consistency checked at sea (consistency_watch.h says what and why).
#include "node/consistency_watch.h"

#include <spdlog/spdlog.h>

#include <stdexcept>

#include "core/core_thread.h"
#include "node/consistency_announce.h"
#include "node/consistency_digest.h"

namespace acomms::node {

ConsistencyWatch::ConsistencyWatch(const v1::ConsistencyConfig& config, const dccl::Codec& codec,
                                   std::vector<Link> links)
    : codec_(codec),
      links_(std::move(links)),
      enabled_(config.has_enabled() && config.enabled()),
      interval_s_(config.has_announce_interval_s() ? config.announce_interval_s() : kDefaultAnnounceIntervalS),
      announce_id_(config.has_announce_id() ? config.announce_id() : kDefaultAnnounceId) {
  if (announce_id_ < 128 || announce_id_ > 32767) {
    throw std::invalid_argument("consistency.announce_id " + std::to_string(announce_id_) + " is not in 128..32767");
  }
  if (!(interval_s_ >= 1)) {
    throw std::invalid_argument("consistency.announce_interval_s " + std::to_string(interval_s_) +
                                " is below 1 s");
  }
  for (const std::string& hex : config.expected_digest()) {
    std::optional<uint32_t> digest = parse_digest(hex);
    if (!digest) {
      throw std::invalid_argument("consistency.expected_digest \"" + hex +
                                  "\" is not 8 hex digits (acommsd --print-digest prints them)");
    }
    expected_.insert(*digest);
  }
  // Disabled, the id is not taken: a config whose types use it loads as
  // before, and a frame with that id is an ordinary message (the daemon
  // sets no piggyback).
  if (!enabled_) return;
  if (const dccl::TypeInfo* taken = codec.find_id(static_cast<int>(announce_id_))) {
    throw std::invalid_argument("consistency.announce_id " + std::to_string(announce_id_) + " is the DCCL id of " +
                                taken->name + ": choose another announce_id");
  }
  if (expected_.empty()) return;
  for (size_t i = 0; i < links_.size(); ++i) {
    const uint32_t own = own_digest(static_cast<int>(i));
    if (expected_.count(own) == 0) {
      spdlog::warn("consistency: this node's digest on link {} is {}, not the fleet's expected digest: its "
                   "definitions or MAC cycle differ from the fleet's (README \"Consistency across a fleet\")",
                   links_[i].name, digest_hex(own));
    }
  }
}

const std::string& ConsistencyWatch::link_name(int link) const {
  static const std::string none;
  return link >= 0 && static_cast<size_t>(link) < links_.size() ? links_[static_cast<size_t>(link)].name : none;
}

uint32_t ConsistencyWatch::own_digest(int link) const {
  const Link& l = links_.at(static_cast<size_t>(link));
  return consistency_digest(canonical_definitions(codec_), canonical_mac(*l.config, l.mac->cycle()));
}

bool ConsistencyWatch::agrees(uint32_t digest, int link) const {
  if (!expected_.empty()) return expected_.count(digest) > 0;
  return digest == own_digest(link);
}

std::string ConsistencyWatch::take(int link, size_t room, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!enabled_ || room < kAnnounceBytes || link < 0 || static_cast<size_t>(link) >= links_.size()) return {};
  auto last = last_sent_.find(link);
  if (last != last_sent_.end() && now - last->second < interval_s_) return {};
  last_sent_[link] = now;
  return encode_announce(own_digest(link), announce_id_);
}

size_t ConsistencyWatch::on_received(std::string_view rest, int32_t src, int link, double now) {
  ACOMMS_ASSERT_CORE_THREAD();
  std::string error;
  std::optional<uint32_t> digest = decode_announce(rest, announce_id_, &error);
  if (!digest) {
    ++malformed_;
    spdlog::warn("consistency: bad announce from node {}: {}", src, error);
    return 0;
  }
  // Disabled: read past, unrecorded.
  if (!enabled_ || link < 0 || static_cast<size_t>(link) >= links_.size()) return kAnnounceBytes;
  HeardDigest& heard = heard_[{link, src}];
  const bool agreed_before = heard.announces == 0 || heard.agrees;
  heard.digest = *digest;
  heard.agrees = agrees(*digest, link);
  heard.last_heard = now;
  ++heard.announces;
  if (heard.agrees) {
    if (!agreed_before) spdlog::info("consistency: node {} on link {} agrees again", src, link_name(link));
    heard.disagrees_since = 0;
    return kAnnounceBytes;
  }
  ++unexpected_;
  if (heard.disagrees_since == 0) heard.disagrees_since = now;
  if (logged_.emplace(src, *digest).second) {
    spdlog::warn("consistency: node {} on link {} announces digest {}, this node expects {}: its message "
                 "definitions or MAC cycle differ (README \"Consistency across a fleet\")",
                 src, link_name(link), digest_hex(*digest),
                 expected_.empty() ? digest_hex(own_digest(link)) + " (its own)" : std::string("the fleet's"));
  }
  return kAnnounceBytes;
}

void ConsistencyWatch::fill_heard(const std::pair<int, int32_t>& key, const HeardDigest& heard,
                                  v1::NodeConsistency* out) const {
  out->set_node(key.second);
  out->set_link(link_name(key.first));
  out->set_digest(digest_hex(heard.digest));
  out->set_agrees(heard.agrees);
  out->set_last_heard(heard.last_heard);
  out->set_disagrees_since(heard.disagrees_since);
  out->set_announces(heard.announces);
}

void ConsistencyWatch::fill(v1::Status* status) const {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!enabled_) return;
  std::string digests;
  for (size_t i = 0; i < links_.size(); ++i) {
    const std::string hex = digest_hex(own_digest(static_cast<int>(i)));
    digests += links_.size() == 1 ? hex : (digests.empty() ? "" : ",") + links_[i].name + "=" + hex;
  }
  status->set_consistency_digest(digests);
  for (const auto& [key, heard] : heard_) fill_heard(key, heard, status->add_consistency());
  status->set_unexpected_digests(unexpected_);
  status->set_malformed_announces(malformed_);
}

void ConsistencyWatch::fill_link(int link, v1::LinkStatusResponse* response) const {
  ACOMMS_ASSERT_CORE_THREAD();
  if (!enabled_ || link < 0 || static_cast<size_t>(link) >= links_.size()) return;
  response->set_consistency_digest(digest_hex(own_digest(link)));
  for (const auto& [key, heard] : heard_) {
    if (key.first == link) fill_heard(key, heard, response->add_consistency());
  }
}

}  // namespace acomms::node
