#pragma once
// `acommsctl nav`: feeds this vehicle's navigation to the daemon
// (SubmitNavigation) from CSV lines on stdin, for position telemetry and
// the simulator's node position.

#include <CLI/CLI.hpp>

#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/acomms.pb.h"

namespace acomms::cli {

struct GlobalOptions;

void add_nav_command(CLI::App& app, const GlobalOptions& options);

// Reads CSV whose first line names the columns: time (or t), then either
// lat and lon (WGS84 degrees) or x and y (local metres), and depth (metres
// down) or z (metres up). Other columns are ignored. Calls `each` per line;
// throws UsageError naming the line and column of a bad value.
class NavigationCsv {
 public:
  explicit NavigationCsv(const std::string& header);
  v1::NavigationFix parse(const std::string& line, size_t line_number) const;

 private:
  size_t columns_ = 0;
  int time_ = -1, lat_ = -1, lon_ = -1, x_ = -1, y_ = -1, depth_ = -1, z_ = -1;
};

}  // namespace acomms::cli
