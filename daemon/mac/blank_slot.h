#pragma once
// Where the auto-discovery MAC puts its one blank (listening) slot.
//
// A node's cycle has n = (known nodes, itself included) + 1 slots: the known
// ids in ascending order, with the blank inserted at index b (0-based), the
// ids keeping their order around it. b depends only on
//     k  the cycle's count since midnight UTC (or since the epoch),
//     S  the sum of the known ids, this node's own included,
//     C  the coolness (>= 1),
// so that nodes knowing the same world always agree on it. Cycle k is
// "excited" in one cycle out of C on average; a larger C is a cooler network
// whose blank moves less often.
//
// H(k, S) is a fixed 64-bit mix, so that every implementation agrees:
//     x = uint64(k) * 0x9e3779b97f4a7c15 + uint64(S)    (mod 2^64)
//     x ^= x >> 30; x *= 0xbf58476d1ce4e5b9;
//     x ^= x >> 27; x *= 0x94d049bb133111eb; x ^= x >> 31;   H = x
//
// kFigure: Schneider (2013), Figure 2.10 and Table 2.7. The
//     blank rests in the last slot and moves to the penultimate one when
//     excited:
//         excited  <=>  H(k, S) mod C == 0
//         b = n - 2 if excited, else n - 1.
//     Equations 2.6-2.7 of Schneider (2013) disagree with its figure and
//     table on the resting place; the figure and table are followed. (Its
//     text gives no formula for "excited" that we could consult; a hash of
//     k and S is the pseudo-random choice from exactly those inputs.)
// kCongruence: the same placement with goby-acomms' test
//         excited  <=>  k mod C == S mod C.
// kAnywhere (the default): a generalisation that the figure and table
//     agree with for two-slot cycles only: not excited, b = n - 1; excited,
//         b = (H(k, S) / C) mod (n - 1),   any slot but the last.
//
// What the Monte Carlo (`acommsctl sim mac-discovery --monte-carlo`) shows,
// and why. Under kFigure and kCongruence the first n - 2 slots always hold
// the lowest n - 2 known ids, in order. Two nodes whose views have the same
// size (hence the same cycle grid) and in which both hold the same rank
// r <= n - 3 (e.g. each is the lowest id it knows) therefore transmit in
// the same slot of every cycle, forever: half duplex, they never hear each
// other, and without control messages nobody can tell them. From three
// nodes on, 27-73 % of random networks (sizes 3-6, C = size + 1) reach
// such a lock and never converge, whatever p_collide. kCongruence adds a
// second lock: two nodes with a == b (mod C) and otherwise equal views
// are excited in the same cycles, so even two lone nodes with congruent
// ids never meet (about 1 in C pairs). kAnywhere lets the blank reach
// every slot, so locked nodes are separated as soon as their (differing)
// sums excite them differently; only views with exactly equal sums, sizes
// and ranks can stay locked: at C = size + 1, 200 random networks of each
// size 3-6 all converged (tests/unit/eval keeps that under 1 %).
//
// Thread-safe: pure functions.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace acomms::mac {

enum class BlankRule { kFigure, kCongruence, kAnywhere };

// The rule a node uses when its config names none, and the default of
// `acommsctl sim mac-discovery`: one constant, so that what the evaluation
// shows is what a fleet that takes the defaults runs. kAnywhere, because it
// is the one rule under which random networks converge (see above); kFigure
// stays selectable to reproduce Schneider (2013), Table 2.7.
inline constexpr BlankRule kDefaultBlankRule = BlankRule::kAnywhere;

// "figure", "congruence", "anywhere": the names config and CLI use.
const char* blank_rule_name(BlankRule rule);
// The rule of that name, or nullopt for any other text.
std::optional<BlankRule> blank_rule_from_name(std::string_view name);

// H(k, S) above.
uint64_t blank_hash(int64_t cycle_count, int64_t id_sum);

// Is cycle `cycle_count` excited? `coolness` must be >= 1.
bool blank_excited(BlankRule rule, int64_t cycle_count, int64_t id_sum, uint32_t coolness);

// 0-based index of the blank in a cycle of `slots` slots (the blank
// included; slots >= 2).
size_t blank_slot_index(BlankRule rule, size_t slots, int64_t cycle_count, int64_t id_sum,
                        uint32_t coolness);

}  // namespace acomms::mac
