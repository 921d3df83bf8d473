#include "nav_command.h"

#include <charconv>
#include <cstdio>
#include <iostream>

#include "api_client.h"
#include "global_options.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> cells;
  size_t start = 0;
  for (;;) {
    size_t comma = line.find(',', start);
    std::string cell = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\r')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    cells.push_back(cell);
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

}  // namespace

NavigationCsv::NavigationCsv(const std::string& header) {
  std::vector<std::string> names = split_csv(header);
  columns_ = names.size();
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string& n = names[i];
    const int c = static_cast<int>(i);
    if (n == "time" || n == "t") time_ = c;
    else if (n == "lat") lat_ = c;
    else if (n == "lon") lon_ = c;
    else if (n == "x") x_ = c;
    else if (n == "y") y_ = c;
    else if (n == "depth") depth_ = c;
    else if (n == "z") z_ = c;
  }
  const bool latlon = lat_ >= 0 && lon_ >= 0, local = x_ >= 0 && y_ >= 0;
  if (time_ < 0 || latlon == local || (depth_ < 0) == (z_ < 0)) {
    throw UsageError("nav: the first line must name the columns: time, then lat,lon or x,y, then depth or z "
                     "(e.g. \"time,lat,lon,depth\"); got \"" + header + "\"");
  }
}

v1::NavigationFix NavigationCsv::parse(const std::string& line, size_t line_number) const {
  std::vector<std::string> cells = split_csv(line);
  if (cells.size() < columns_) {
    throw UsageError("nav: line " + std::to_string(line_number) + " has " + std::to_string(cells.size()) +
                     " columns, the header " + std::to_string(columns_));
  }
  auto number = [&](int column, const char* name) {
    const std::string& cell = cells[static_cast<size_t>(column)];
    double value = 0;
    auto [ptr, error] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
    if (cell.empty() || error != std::errc() || ptr != cell.data() + cell.size()) {
      throw UsageError("nav: line " + std::to_string(line_number) + ": " + name + " \"" + cell + "\" is not a number");
    }
    return value;
  };
  v1::NavigationFix fix;
  fix.set_time(number(time_, "time"));
  if (lat_ >= 0) {
    fix.mutable_latlon()->set_lat(number(lat_, "lat"));
    fix.mutable_latlon()->set_lon(number(lon_, "lon"));
  } else {
    fix.mutable_local()->set_x(number(x_, "x"));
    fix.mutable_local()->set_y(number(y_, "y"));
  }
  fix.set_depth(depth_ >= 0 ? number(depth_, "depth") : -number(z_, "z"));
  return fix;
}

namespace {

void run_nav(const GlobalOptions& global) {
  std::string line;
  size_t line_number = 1;
  if (!std::getline(std::cin, line)) throw UsageError("nav: no input (expected a CSV header on stdin)");
  NavigationCsv csv(line);
  ApiClient client(global);
  // No deadline: the stream lasts as long as the vehicle's navigation does.
  grpc::ClientContext context;
  v1::SubmitNavigationResponse response;
  std::unique_ptr<grpc::ClientWriter<v1::NavigationFix>> writer = client.stub().SubmitNavigation(&context, &response);
  while (std::getline(std::cin, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    v1::NavigationFix fix;
    try {
      fix = csv.parse(line, line_number);
    } catch (const UsageError&) {
      writer->WritesDone();
      writer->Finish();
      throw;
    }
    if (!writer->Write(fix)) break;  // the daemon ended the call: Finish says why
  }
  writer->WritesDone();
  check(writer->Finish());
  if (global.json) {
    print_json(response);
  } else {
    std::printf("%llu fixes taken, %llu ignored (time not after the previous), %llu telemetry messages queued\n",
                static_cast<unsigned long long>(response.accepted_fixes()),
                static_cast<unsigned long long>(response.ignored_fixes()),
                static_cast<unsigned long long>(response.messages_queued()));
  }
}

}  // namespace

void add_nav_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* nav = app.add_subcommand("nav", "Feed this vehicle's navigation (CSV on stdin) to position telemetry");
  nav->footer(
      "The first line names the columns: time (s since the Unix epoch), lat,lon (WGS84; needs "
      "telemetry.datum in the daemon's config) or x,y (local metres east, north), and depth (m, down) "
      "or z (m, up). The daemon samples the fixes every telemetry.tau_s and streams them to "
      "telemetry.receiver; the sim driver also places this node at the newest fix.\n\n"
      "Examples:\n"
      "  printf 'time,lat,lon,depth\\n1764000000,41.52,-70.67,12\\n' | acommsctl nav\n"
      "  tail -n +1 -f fixes.csv | acommsctl nav");
  nav->callback([&global] { run_nav(global); });
}

}  // namespace acomms::cli
