#include "mac/blank_slot.h"

namespace acomms::mac {
namespace {

int64_t positive_mod(int64_t a, int64_t m) {
  int64_t r = a % m;
  return r < 0 ? r + m : r;
}

}  // namespace

const char* blank_rule_name(BlankRule rule) {
  switch (rule) {
    case BlankRule::kFigure: return "figure";
    case BlankRule::kCongruence: return "congruence";
    case BlankRule::kAnywhere: return "anywhere";
  }
  return "?";
}

std::optional<BlankRule> blank_rule_from_name(std::string_view name) {
  for (BlankRule rule : {BlankRule::kFigure, BlankRule::kCongruence, BlankRule::kAnywhere}) {
    if (name == blank_rule_name(rule)) return rule;
  }
  return std::nullopt;
}

uint64_t blank_hash(int64_t cycle_count, int64_t id_sum) {
  uint64_t x = static_cast<uint64_t>(cycle_count) * 0x9e3779b97f4a7c15ULL +
               static_cast<uint64_t>(id_sum);
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

bool blank_excited(BlankRule rule, int64_t cycle_count, int64_t id_sum, uint32_t coolness) {
  const uint64_t c = coolness == 0 ? 1 : coolness;
  if (rule == BlankRule::kCongruence)
    return positive_mod(cycle_count, static_cast<int64_t>(c)) ==
           positive_mod(id_sum, static_cast<int64_t>(c));
  return blank_hash(cycle_count, id_sum) % c == 0;
}

size_t blank_slot_index(BlankRule rule, size_t slots, int64_t cycle_count, int64_t id_sum,
                        uint32_t coolness) {
  if (slots < 2) return 0;
  if (!blank_excited(rule, cycle_count, id_sum, coolness)) return slots - 1;
  if (rule != BlankRule::kAnywhere) return slots - 2;
  const uint64_t c = coolness == 0 ? 1 : coolness;
  return static_cast<size_t>((blank_hash(cycle_count, id_sum) / c) % (slots - 1));
}

}  // namespace acomms::mac
