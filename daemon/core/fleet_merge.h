#pragma once
// How a fleet node's settings are merged from its ancestors (README "Fleet
// configuration"), with where each field came from.
//
// The problem: a node of a fleet file is the sum of several levels (cruise,
// global, class, vehicle), and a person reading a flattened config must be
// able to tell which file and line gave each value. The decision: merge by
// reflection over any message (acomms.v1.Config, acomms.v1.FleetKeys), so a
// field added to the config merges without new code, and carry beside the
// message a Provenance: field path -> file:line.
//
// The rules: a set scalar overrides (proto3 fields without `optional` are
// set only when not zero/empty, so a child cannot reset such a field to
// zero); a singular message merges field by field; a repeated field follows
// its entry in repeated_rules(): kAppend, kAppendUnique (skip values already
// present), kReplace (a child's list replaces the inherited one) or kKeyed
// (entries with the same key merge field by field, others are appended; the
// n-th entry of a key meets the n-th inherited entry of that key, so a
// cycle naming one src twice keeps both slots). A repeated field missing
// from the table is replaced, and FleetMerge.EveryRepeatedFieldHasARule
// fails until the table names it.
//
// Paths: "mac.slot[1].rate" (index in the merged message), "mac" for the
// line of `mac {`.
//
// Thread-safe: functions of their arguments only; the rule table is a
// constant built once.

#include <map>
#include <string>
#include <vector>

#include <google/protobuf/message.h>
#include <google/protobuf/text_format.h>

namespace acomms::core {

struct Origin {
  std::string file;
  int line = 0;  // 1-based
};
std::string to_string(const Origin& origin);  // "file:line"

using Provenance = std::map<std::string, Origin>;

enum class RepeatedRule { kAppend, kAppendUnique, kReplace, kKeyed };

struct RepeatedFieldRule {
  RepeatedRule rule;
  std::vector<std::string> key_fields;  // kKeyed: the fields that make the key
};

// One value of `field` (element `index`, -1 when singular) as one line of
// text format: how the merge compares values and builds keys, and how
// import finds what configs share.
std::string value_text(const google::protobuf::Message& message, const google::protobuf::FieldDescriptor* field,
                       int index);

// Full field name ("acomms.v1.MacConfig.slot") -> its rule.
const std::map<std::string, RepeatedFieldRule>& repeated_rules();

// Every set field of `message` (parsed with `tree`) located in `file`,
// paths prefixed by `prefix` ("" for the top).
void record_provenance(const google::protobuf::Message& message, const google::protobuf::TextFormat::ParseInfoTree& tree,
                       const std::string& file, Provenance& into, const std::string& prefix = "");

// Merges `src` (located by `src_where`) over `dst`, updating `dst_where`.
// Both messages must be of the same type.
void merge_located(const google::protobuf::Message& src, const Provenance& src_where, google::protobuf::Message& dst,
                   Provenance& dst_where);

}  // namespace acomms::core
