#include "gram_command.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "comma_list.h"
#include "gram/arrivals.h"
#include "gram/beam_fan.h"
#include "gram/bellhop_import.h"
#include "gram/ctd_cast.h"
#include "gram/profile_merge.h"
#include "gram/shd_export.h"
#include "gram/tl_csv.h"
#include "gram/transmission_loss.h"
#include "gram_plot.h"
#include "gram_service_command.h"
#include "plot/axes.h"
#include "rpc_error.h"  // UsageError

namespace acomms::cli {
namespace {

struct GramOptions {
  std::string ctd, env, png, at, receiver;
  std::string format = "csv";
  double bin_m = 1.0;
  double thin_mps = 0;
  bool mackenzie = false;
  unsigned threads = 0;
};

gram::Environment load_env(const std::string& path) {
  auto imported = gram::import_bellhop_env_file(path);
  for (const auto& warning : imported.warnings) std::cerr << "acommsctl: " << path << ": " << warning << "\n";
  return std::move(imported.environment);
}

void report_beams(const gram::Environment& env, std::uint32_t used) {
  if (env.beam_count() == 0) std::cerr << "acommsctl: " << used << " beams (automatic, spec §4.7)\n";
}

void run_ssp(const GramOptions& o) {
  std::ifstream in(o.ctd, std::ios::binary);
  if (!in) throw UsageError("cannot read " + o.ctd);
  std::ostringstream text;
  text << in.rdbuf();
  const auto cast = gram::read_ctd_csv(text.str(), o.ctd);
  gram::CtdProfileOptions options;
  options.bin_m = o.bin_m;
  options.equation = o.mackenzie ? gram::SoundSpeedEquation::kMackenzie : gram::SoundSpeedEquation::kUnesco;
  std::cout << "depth_m,speed_mps\n";
  std::cout.setf(std::ios::fixed);
  auto profile = gram::sound_speed_from_ctd(cast, options);
  if (o.thin_mps > 0) profile = gram::thin_profile(profile, o.thin_mps);
  for (const auto& p : profile)
    std::cout << std::setprecision(3) << p.depth_m() << "," << std::setprecision(4) << p.speed_mps() << "\n";
}

// Writes `bytes` to standard output, all of it, or fails naming the cause.
void write_stdout(const std::string& bytes) {
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), stdout) != bytes.size())
    throw std::runtime_error("cannot write the output: " + std::string(std::strerror(errno)));
}

// "RANGE_M,DEPTH_M" of --at and --receiver.
std::pair<double, double> range_depth(const std::string& option, const std::string& text) {
  const auto parts = split_commas(text);
  try {
    if (parts.size() != 2) throw std::invalid_argument(text);
    return {std::stod(parts[0]), std::stod(parts[1])};
  } catch (const std::exception&) {
    throw UsageError(option + " \"" + text + "\": give RANGE_M,DEPTH_M, e.g. " + option + " 2000,50");
  }
}

void run_tl(const GramOptions& o) {
  TlMarks marks;
  if (!o.receiver.empty()) {
    if (o.png.empty()) throw UsageError("--receiver marks a receiver on the picture: give --png too");
    const auto [range, depth] = range_depth("--receiver", o.receiver);
    marks.receiver = TlReceiver{range, depth, "receiver, " + plot::tick_label(depth, 0.1) + " m"};
  }
  const gram::Environment env = load_env(o.env);
  const bool shd = o.format == "shd";
  if (shd && o.png.empty() && ::isatty(STDOUT_FILENO))
    throw UsageError("--format shd writes a binary file to standard output: redirect it, e.g. > field.shd");
  gram::RunOptions run;
  run.threads = o.threads;
  run.keep_pressure = shd && o.png.empty();
  const auto tl = gram::compute_transmission_loss(env, run);
  report_beams(env, tl.beam_count);
  if (!o.png.empty()) {
    write_tl_png(o.png, tl, env, o.env, marks);
    return;
  }
  if (shd) {
    gram::ShdField field;
    try {
      field = gram::shd_field_of(tl, env);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--format shd: ") + e.what());
    }
    write_stdout(gram::write_shd(field, gram::ShdLayout::k2023));
  } else {
    // Formatted on the run's threads; written block after block.
    for (const auto& block : gram::tl_csv_blocks(tl, o.threads)) write_stdout(block);
  }
  if (std::fflush(stdout) != 0) throw std::runtime_error("cannot write the output: " + std::string(std::strerror(errno)));
}

void run_arrivals(const GramOptions& o) {
  const auto [range, depth] = range_depth("--at", o.at);
  gram::Environment env = load_env(o.env);
  // Keep the file's beam count: the automatic rule depends on its receivers.
  if (env.beam_count() == 0) env.set_beam_count(gram::beam_count(env));
  env.clear_receiver_range_m();
  env.clear_receiver_depth_m();
  env.set_irregular_receivers(true);
  env.add_receiver_range_m(range);
  env.add_receiver_depth_m(depth);
  const auto result = gram::compute_arrivals(env);
  const auto& arrivals = result.at(0).arrivals;
  std::cout << "delay_s,amplitude,phase_deg,launch_deg,arrival_deg,n_surface,n_bottom\n";
  for (const auto& a : arrivals)
    std::cout << std::fixed << std::setprecision(9) << a.delay_s << "," << std::scientific << std::setprecision(6)
              << a.amplitude << "," << std::fixed << std::setprecision(4) << a.phase_deg << ","
              << a.launch_deg << "," << a.arrival_deg << "," << a.top_bounces << "," << a.bottom_bounces << "\n";
  const auto spread = gram::rms_delay_spread(arrivals, 60.0);
  std::cout << std::defaultfloat << "# rms_delay_spread_s=" << spread.tau_rms_s << " over "
            << spread.arrivals_used << " arrivals within 60 dB of the strongest\n";
}

}  // namespace

CLI::App* add_gram_command(CLI::App& app, const GlobalOptions& global) {
  static GramOptions options;
  CLI::App* gram = app.add_subcommand(
      "gram", "The acoustic model: offline (ssp, tl, arrivals: sound speed from a CTD cast, transmission "
              "loss and arrivals from a BELLHOP-format environment), or the daemon's (depth, env)");
  gram->require_subcommand(1);
  gram->footer(
      "Examples:\n"
      "  acommsctl gram tl --env examples/glint10.env --png tl.png\n"
      "  acommsctl gram depth --range 3000 --speed 1.5 --max-depth 90");

  CLI::App* ssp = gram->add_subcommand(
      "ssp", "Print the sound speed profile (depth_m,speed_mps) of a CTD cast: a CSV with columns "
             "depth_m or p_dbar, t90_degc, s_psu or conductivity_ms_per_cm, lat_deg");
  ssp->add_option("--ctd", options.ctd, "The cast (CSV)")->required()->type_name("FILE.csv");
  ssp->add_option("--bin", options.bin_m, "Depth bin (m) for averaging")->check(CLI::PositiveNumber)->capture_default_str();
  ssp->add_option("--thin", options.thin_mps,
                  "Drop points that linear interpolation reproduces within this many m/s (0: keep all)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  ssp->add_flag("--mackenzie", options.mackenzie, "Mackenzie 1981 instead of UNESCO (Chen-Millero)");
  ssp->footer("Example:\n  acommsctl gram ssp --ctd cast.csv --bin 2 --thin 0.05 > profile.csv");
  ssp->callback([] { run_ssp(options); });

  CLI::App* tl = gram->add_subcommand(
      "tl", "Transmission loss on the environment's receiver grid as CSV range_m,depth_m,tl_db (ranges and "
            "depths exact, the shortest text that reads back as the model's value; TL to 0.001 dB, empty at "
            "range 0, inf where no beam reaches), as BELLHOP's binary .shd with --format shd, or a picture "
            "with --png");
  tl->add_option("--env", options.env, "BELLHOP-format environment")->required()->type_name("FILE.env");
  auto* png = tl->add_option("--png", options.png, "Draw TL against range and depth, with the profile, to this PNG")
                  ->type_name("FILE");
  tl->add_option("--format", options.format,
                 "csv, or shd: the pressure field as BELLHOP writes it (2023 layout, rectilinear grids) to "
                 "standard output, for BELLHOP's plotting tools")
      ->check(CLI::IsMember({"csv", "shd"}))
      ->excludes(png)
      ->capture_default_str();
  tl->add_option("--receiver", options.receiver,
                 "With --png: mark a receiver (a vehicle) at this range and depth, with its depth across the field")
      ->type_name("RANGE_M,DEPTH_M");
  tl->add_option("--threads", options.threads,
                 "Threads for the model and the CSV text (0: all cores); the output is the same bytes")
      ->capture_default_str();
  tl->footer(
      "Examples:\n"
      "  acommsctl gram tl --env examples/glint10.env > tl.csv\n"
      "  acommsctl gram tl --env examples/glint10.env --format shd > tl.shd\n"
      "  acommsctl gram tl --env examples/glint10.env --png tl.png\n"
      "  acommsctl gram tl --env examples/glint10.env --png tl.png --receiver 3000,40");
  tl->callback([] { run_tl(options); });

  CLI::App* arrivals = gram->add_subcommand(
      "arrivals", "The arrivals (delay, amplitude, phase, angles, bounces) at one receiver and their "
                  "RMS delay spread");
  arrivals->add_option("--env", options.env, "BELLHOP-format environment")->required()->type_name("FILE.env");
  arrivals->add_option("--at", options.at, "The receiver: range (m) and depth (m)")->required()->type_name("RANGE_M,DEPTH_M");
  arrivals->footer("Example:\n  acommsctl gram arrivals --env examples/glint10.env --at 2000,50");
  arrivals->callback([] { run_arrivals(options); });

  add_gram_service_commands(*gram, global);
  return gram;
}

}  // namespace acomms::cli
