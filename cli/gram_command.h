#pragma once
// `acommsctl gram ...`: the acoustic model.
// Offline (the built-in model, no daemon):
//   gram ssp --ctd FILE.csv           the sound speed profile of a CTD cast
//   gram tl --env FILE.env [--png F]  transmission loss as CSV, or a picture
//   gram arrivals --env FILE.env --at RANGE_M,DEPTH_M
//                                     the arrivals there and their delay spread
// The daemon's model service (gram_service_command.h):
//   gram depth --range R --speed V --max-depth D ...  depth objective, best depth
//   gram env show | update --ctd FILE.csv             the environment it holds
// See daemon/gram and shared/spec/gram.md.

#include <CLI/CLI.hpp>

#include "global_options.h"

namespace acomms::cli {

CLI::App* add_gram_command(CLI::App& app, const GlobalOptions& global);

}  // namespace acomms::cli
