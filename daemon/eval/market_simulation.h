#pragma once
// The "marketplace" evaluation of the dynamic priority in Schneider (2013),
// section 2.3.4 (T. Schneider, "Advances in Integrating Autonomy with
// Acoustic Communications for Intelligent Networks of Marine Robots", PhD
// thesis, MIT/WHOI), as a library function with no I/O.
// `acommsctl sim queue-market` prints it.
//
// The experiment compares three ways of choosing which queue gets the one
// message slot of each transmission, scored by what the receiver gains.
//
// Model, exactly as implemented
// -----------------------------
// * Message types (Schneider (2013), Table 2.4), one queue each:
//       type  value_base  ttl
//        1        1       1000 s
//        2        2       2000 s
//        3        1       3000 s
// * A trial starts at t = 0 and has N transmissions (default 100) at
//   t_k = k * tau, k = 1..N (default tau = 100 s). Each transmission carries
//   exactly one message, and every transmission is received (single hop,
//   lossless link), so "sent" and "received" coincide.
// * Queue contents are drawn afresh at every transmission: each queue,
//   independently, is empty with probability P_empty. A non-empty queue
//   offers one message, its newest, generated at a uniformly random instant
//   of the interval before the transmission, so its age is U[0, tau).
//   If every queue is empty, nothing is sent and nothing is scored.
// * Score of a received message of type i at time t:
//       S = D_b + D_s - D_e
//       D_b = value_base_i
//       D_s = (t - t_last_i) / tau_s   t_last_i: when a message of type i was
//                                      last received (t = 0, the trial
//                                      start, if never); rewards variety
//       D_e = age / ttl_i              penalises stale data
//   with tau_s = R * tau (R = --tau-s-ratio). A trial's score is the sum of S
//   over its received messages; a point reports the mean over the trials.
// * Policies (choose among the non-empty queues):
//     dynamic      highest acomms::queue::dynamic_priority(value_base, ttl,
//                  t - t_last_sent_i), t_last_sent_i = 0 before the first
//                  send; ties (within 1e-9 relative) go to the queue that
//                  sent longest ago, then to the earlier type in the table.
//     fixed_value  highest value_base; ties to the lower ttl, then the
//                  earlier type (a strict, static order: 2, 1, 3).
//     lowest_ttl   lowest ttl; ties to the higher value_base, then the
//                  earlier type (a strict, static order: 1, 2, 3).
// * Common random numbers: trial j of every policy and every P_empty sees
//   the same random draws (one uniform u for occupancy, queue non-empty iff
//   u >= P_empty, and one for the age, per queue and transmission), taken
//   from a SplitMix64 stream seeded by (seed, j). Results are therefore
//   deterministic for a seed, independent of the other P_empty points
//   requested, and the policy comparison is paired.
//
// Sources: the experiment's parameters and score come from the issue's
// summary of Schneider (2013) (Table 2.4, N, tau, P_empty,
// S = D_b + D_s - D_e); the priority and "t_last = time of the last send
// from this queue" from the goby-acomms queue documentation. The thesis text of 2.3.4 was not
// available, so the arrival model (per-transmission emptiness, age U[0, tau)),
// t_last = 0 at the start, the lossless link and the tie rules are choices
// made here, as the simplest reading.
//
// Worth knowing when reading the numbers: the gaps (t - t_last) of one type
// add up to the time that type was last received, so a trial's total D_s is
// (sum over types of their last reception time) / tau_s. With full queues
// (P_empty = 0) everything but D_e is deterministic: fixed_value always sends
// type 2 (2N + N tau / tau_s), lowest_ttl type 1 (N + N tau / tau_s), and
// dynamic cycles 1 2 1 2 1 3 2 ... (42/42/16 messages in N = 100, D_b = 142,
// D_s = 295 tau / tau_s with the defaults). Dynamic therefore wins when
// tau_s is small (R = 0.1) and fixed_value when it is large (R = 10); with
// the defaults the crossover at P_empty = 0 is near R = 3.3.
//
// Thread-safe: a pure function of its config and seed.

#include <cstdint>
#include <string>
#include <vector>

namespace acomms::eval {

struct MarketMessageType {
  double value_base = 1;
  double ttl_s = 1;
};

// Schneider (2013), Table 2.4: (1, 1000 s), (2, 2000 s), (1, 3000 s).
std::vector<MarketMessageType> schneider2013_market_types();

// 0, 0.1, ..., 0.9.
std::vector<double> default_p_empty_grid();

struct MarketConfig {
  std::vector<MarketMessageType> types = schneider2013_market_types();
  int transmissions = 100;        // N
  double tau_s = 100;             // tau: seconds between transmissions
  double tau_s_ratio = 0.1;       // R: the variety time scale tau_s = R * tau
  int trials = 1000;
  uint64_t seed = 20130601;
};

// Mean total score per trial of each policy at one P_empty.
struct MarketPoint {
  double p_empty = 0;
  double dynamic = 0;
  double fixed_value = 0;
  double lowest_ttl = 0;
};

// Runs the experiment at each P_empty (each in [0, 1]). Throws
// std::invalid_argument for an unusable config (no types, ttl <= 0,
// value_base < 0, N < 1, tau <= 0, R <= 0, trials < 1, P_empty outside
// [0, 1]).
std::vector<MarketPoint> simulate_market(const MarketConfig& config,
                                         const std::vector<double>& p_empty);

// "p_empty,dynamic,fixed_value,lowest_ttl\n" then one line per point.
std::string format_market_csv(const std::vector<MarketPoint>& points);

}  // namespace acomms::eval
