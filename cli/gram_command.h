#pragma once
// `acommsctl gram ...`: the built-in acoustic model, offline (no daemon).
//   gram ssp --ctd FILE.csv           the sound speed profile of a CTD cast
//   gram tl --env FILE.env [--png F]  transmission loss as CSV, or a picture
//   gram arrivals --env FILE.env --at RANGE_M,DEPTH_M
//                                     the arrivals there and their delay spread
// See daemon/gram and shared/spec/gram.md.

#include <CLI/CLI.hpp>

namespace acomms::cli {

CLI::App* add_gram_command(CLI::App& app);

}  // namespace acomms::cli
