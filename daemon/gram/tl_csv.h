// The transmission-loss field as CSV text: range_m,depth_m,tl_db.
//
// Problem: a 501 × 1001 field is half a million rows. Formatted with
// iostreams on one thread it took about 40% of `acommsctl gram tl`'s time,
// and the stream's precision, left at 3 by the TL column, printed every
// later range and depth with three significant digits (1395.97 m came out
// as 1.4e+03). Decision: coordinates in fixed notation with the fewest
// digits that read back as the same double (std::to_chars), each distinct
// range and depth formatted once; TL with three decimals, correctly rounded like
// printf("%.3f"), empty where the model has no value (range 0) and `inf`
// where no beam reaches. The rows are split into contiguous blocks, one per
// thread. Invariant: a row's text depends on that row alone, so the bytes
// are the same whatever the number of threads.
// Thread-safe: pure functions.
#pragma once

#include <string>
#include <vector>

#include "gram/transmission_loss.h"

namespace acomms::gram {

// The CSV in blocks, in order: written one after the other they are the
// file (the header line opens the first). Rectilinear grids: depth-major
// (every range of the first depth, then the next depth); irregular
// receivers: one row each, in the environment's order. `threads` 0: the
// hardware's concurrency; a small field is formatted on the calling thread.
std::vector<std::string> tl_csv_blocks(const TransmissionLoss& tl, unsigned threads);

// `value` with three decimals, exactly as printf("%.3f") prints it (finite
// values only); writes at most 320 characters, returns the end.
char* put_fixed3(char* out, double value);

}  // namespace acomms::gram
