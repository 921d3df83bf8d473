#include "gram_service_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include <google/protobuf/text_format.h>

#include "acomms/v1/gram.grpc.pb.h"
#include "connection.h"
#include "gram_plot.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace {

struct DepthOptions {
  double range_m = 0, speed_mps = 0, heading_deg = 0, horizon_s = 120;
  double h_max_db = 108;
  bool h_max_window = false;
  double min_depth_m = 0, max_depth_m = 0, min_altitude_m = 0;
  double lowpass_per_m = 0;
  bool zero_phase = false;
  double source_level_db = NAN, noise_level_db = NAN, array_gain_db = 0, threshold_db = 0;
  double source_depth_m = NAN;
  std::string consumer = "acommsctl", png;
  double deadline_s = 60;
  double noise_decrease_db_per_km = NAN;
  // The forecast strategy (deep water): asked for when a horizon is given.
  // 0.51 m/s: 20 deg of pitch at 1.5 m/s (1.5 sin 20 deg).
  double forecast_horizon_s = NAN, current_depth_m = 0, vertical_speed_mps = 0.51, caustic_uncertainty_m = 50;
  double leg_end_m = NAN;
  double reception_snr50_db = NAN, reception_slope_per_db = 0;
};

struct EnvOptions {
  std::string ctd;
  double time_s = 0;
  bool clear = false;
};

std::unique_ptr<v1::Gram::Stub> gram_stub(const GlobalOptions& options) {
  return v1::Gram::NewStub(connect(options));
}

void set_deadline(grpc::ClientContext& context, double seconds) {
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
}

void print_objective(const v1::DepthObjectiveResponse& response) {
  const auto& r = response.reply();
  std::printf("depth_m,h_bar_db,objective,objective_filtered%s\n",
              r.points_size() && r.points(0).noise_level_db() != 0 ? ",noise_level_db,signal_excess_db" : "");
  for (const auto& p : r.points()) {
    std::printf("%.2f,%.3f,%.5f,%.5f", p.depth_m(), p.h_bar_db(), p.objective(), p.objective_filtered());
    if (p.noise_level_db() != 0) std::printf(",%.3f,%.3f", p.noise_level_db(), p.signal_excess_db());
    std::printf("\n");
  }
  std::printf("# window %.1f-%.1f m (%u ranges%s), %u profile instance(s), H_max %.1f dB, bottom %.1f m\n",
              r.window_begin_m(), r.window_end_m(), r.ranges_in_window(), r.window_widened() ? ", widened" : "",
              response.instances(), r.h_max_db(), r.bottom_m());
  std::printf("# best depth %.2f m (objective %.4f)%s\n", r.best_depth_m(), r.best_objective(),
              r.any_signal() ? "" : " — no allowed depth is predicted to receive");
  if (r.has_forecast()) {
    const auto& f = r.forecast();
    // The plan's first window: its rate (the target is on a path, not at
    // the end of a straight one).
    const double first_rate = f.path_depth_m_size() > 1 && f.columns_size() > 1 && f.columns(1).time_s() > 0
                                  ? std::abs(f.path_depth_m(1) - f.path_depth_m(0)) / f.columns(1).time_s()
                                  : 0;
    std::printf("# forecast over %.0f s (%d windows): %s, the plan's best point %.2f m in %.0f s (score %.4f); "
                "first window at %.3f m/s; at the next window be at %.2f m\n",
                f.forecast_horizon_s(), f.columns_size(), f.choice().c_str(), f.target_depth_m(), f.target_time_s(),
                f.target_objective(), first_rate, f.next_depth_m());
    std::printf("# plan (depth at each window, m; mean score %.4f):", f.expected_score());
    for (int k = 0; k < f.path_depth_m_size(); ++k) std::printf("%s %.1f", k ? "," : "", f.path_depth_m(k));
    std::printf("\n");
  }
}

void run_depth(const DepthOptions& o, const GlobalOptions& global) {
  v1::DepthObjectiveRequest request;
  request.mutable_header()->set_consumer(o.consumer);
  if (!std::isnan(o.source_depth_m)) request.mutable_header()->mutable_environment()->set_source_depth_m(o.source_depth_m);
  auto* q = request.mutable_query();
  q->set_range_m(o.range_m);
  q->set_speed_mps(o.speed_mps);
  q->set_heading_deg(o.heading_deg);
  q->set_horizon_s(o.horizon_s);
  if (o.h_max_window) q->set_h_max_window_maximum(true);
  else q->set_h_max_db(o.h_max_db);
  q->mutable_limits()->set_min_depth_m(o.min_depth_m);
  q->mutable_limits()->set_max_depth_m(o.max_depth_m);
  q->mutable_limits()->set_min_altitude_m(o.min_altitude_m);
  if (o.lowpass_per_m > 0) {
    q->mutable_lowpass()->set_cutoff_per_m(o.lowpass_per_m);
    q->mutable_lowpass()->set_zero_phase(o.zero_phase);
  }
  if (!std::isnan(o.source_level_db)) {
    if (std::isnan(o.noise_level_db)) throw UsageError("--source-level needs --noise-level (dB re 1 µPa in the band)");
    auto* s = q->mutable_sonar();
    s->set_source_level_db(o.source_level_db);
    s->set_noise_level_db(o.noise_level_db);
    s->set_array_gain_db(o.array_gain_db);
    s->set_threshold_db(o.threshold_db);
    if (!std::isnan(o.noise_decrease_db_per_km)) s->set_noise_decrease_db_per_km(o.noise_decrease_db_per_km);
  } else if (!std::isnan(o.noise_decrease_db_per_km)) {
    throw UsageError("--noise-decrease needs the sonar equation: give --source-level and --noise-level");
  }
  if (!std::isnan(o.forecast_horizon_s)) {
    auto* f = q->mutable_forecast();
    f->set_forecast_horizon_s(o.forecast_horizon_s);
    f->set_current_depth_m(o.current_depth_m);
    f->set_vertical_speed_mps(o.vertical_speed_mps);
    f->set_caustic_uncertainty_m(o.caustic_uncertainty_m);
    if (!std::isnan(o.leg_end_m)) f->set_leg_end_range_m(o.leg_end_m);
    if (!std::isnan(o.reception_snr50_db)) {
      if (std::isnan(o.source_level_db))
        throw UsageError("--reception-snr50 needs the sonar equation: give --source-level and --noise-level");
      f->set_reception_snr50_db(o.reception_snr50_db);
      f->set_reception_slope_per_db(o.reception_slope_per_db);
    }
  } else if (!std::isnan(o.leg_end_m) || !std::isnan(o.reception_snr50_db)) {
    throw UsageError("--leg-end and --reception-snr50 need the forecast: give --forecast-horizon");
  }
  auto stub = gram_stub(global);
  grpc::ClientContext context;
  set_deadline(context, o.deadline_s);
  v1::DepthObjectiveResponse response;
  check(stub->DepthObjective(&context, request, &response));
  if (global.json) print_json(response);
  else print_objective(response);
  if (!o.png.empty()) {
    char title[160];
    std::snprintf(title, sizeof title, "Depth objective for %s, %.0f m away, H_max %.1f dB", o.consumer.c_str(), o.range_m,
                  response.reply().h_max_db());
    // The source: the other node, at the depth asked for, else the one the
    // daemon's environment holds.
    std::optional<double> source_depth;
    if (!std::isnan(o.source_depth_m)) {
      source_depth = o.source_depth_m;
    } else {
      grpc::ClientContext env_context;
      set_deadline(env_context, global.timeout_s);
      gram::KnownEnvironment held;
      if (stub->GetEnvironment(&env_context, v1::GetEnvironmentRequest(), &held).ok() && held.base().source_depth_m() > 0)
        source_depth = held.base().source_depth_m();
    }
    write_objective_png(o.png, response.reply(), title, source_depth);
  }
}

void run_env_show(const GlobalOptions& global) {
  auto stub = gram_stub(global);
  grpc::ClientContext context;
  set_deadline(context, global.timeout_s);
  gram::KnownEnvironment held;
  check(stub->GetEnvironment(&context, v1::GetEnvironmentRequest(), &held));
  if (global.json) {
    print_json(held);
    return;
  }
  std::string text;
  google::protobuf::TextFormat::PrintToString(held, &text);
  std::cout << text;
}

void run_env_update(const EnvOptions& o, const GlobalOptions& global) {
  v1::UpdateEnvironmentRequest request;
  request.set_clear_instances(o.clear);
  if (!o.ctd.empty()) {
    std::ifstream in(o.ctd, std::ios::binary);
    if (!in) throw UsageError("cannot read " + o.ctd);
    std::ostringstream text;
    text << in.rdbuf();
    auto* cast = request.add_casts();
    cast->set_csv(text.str());
    cast->set_time_s(o.time_s);
    cast->set_name(o.ctd);
  } else if (!o.clear) {
    throw UsageError("give --ctd FILE.csv (and/or --clear)");
  }
  auto stub = gram_stub(global);
  grpc::ClientContext context;
  set_deadline(context, global.timeout_s);
  gram::KnownEnvironment held;
  check(stub->UpdateEnvironment(&context, request, &held));
  if (global.json) {
    print_json(held);
    return;
  }
  std::printf("%d profile instance(s) held\n", held.instances_size());
  for (const auto& i : held.instances())
    std::printf("  t=%.0f s: %d points from %u samples\n", i.time_s(), i.sound_speed_size(), i.samples());
}

// A number that is finite: the options left unset are NaN, so "nan" given
// would read as not given.
const CLI::Validator finite_number(
    [](std::string& text) -> std::string {
      try {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v)) return "";
      } catch (const std::exception&) {
      }
      return "must be a finite number, not " + text;
    },
    "FINITE");

}  // namespace

void add_gram_service_commands(CLI::App& gram, const GlobalOptions& options) {
  static DepthOptions depth_options;
  static EnvOptions env_options;
  CLI::App* depth = gram.add_subcommand(
      "depth", "Ask the daemon for the depth objective over depth (Schneider (2013) eq. 4.1-4.4, 4.7) and the best depth "
               "within the vehicle's limits");
  auto& d = depth_options;
  depth->add_option("--range", d.range_m, "Current range to the other node (m)")->required();
  depth->add_option("--speed", d.speed_mps, "Vehicle speed (m/s)")->required();
  depth->add_option("--heading", d.heading_deg, "Heading from the line away from the other node (deg; 0 opening, 180 closing)")
      ->capture_default_str();
  depth->add_option("--horizon", d.horizon_s, "Model window tau_a (s)")->capture_default_str();
  depth->add_option("--h-max", d.h_max_db, "H_max of eq. 4.3 (dB)")->capture_default_str();
  depth->add_flag("--h-max-window", d.h_max_window, "H_max = the window's largest H-bar instead");
  depth->add_option("--min-depth", d.min_depth_m, "Shallowest allowed depth (m)")->capture_default_str();
  depth->add_option("--max-depth", d.max_depth_m, "Deepest allowed depth (m)")->required();
  depth->add_option("--min-altitude", d.min_altitude_m, "Clearance above the bottom (m)")->capture_default_str();
  depth->add_option("--lowpass", d.lowpass_per_m, "Low-pass cutoff over depth (1/m; 0.02 = the thesis's 1/50 m; 0: none)")
      ->capture_default_str();
  depth->add_flag("--zero-phase", d.zero_phase, "Forward-backward low-pass (no lag)");
  depth->add_option("--source-level", d.source_level_db, "Sonar equation: SL (dB re 1 uPa at 1 m)")->check(finite_number);
  depth->add_option("--noise-level", d.noise_level_db, "Sonar equation: NL in the band (dB re 1 uPa)")->check(finite_number);
  depth->add_option("--array-gain", d.array_gain_db, "Sonar equation: AG (dB)")->capture_default_str();
  depth->add_option("--threshold", d.threshold_db, "Sonar equation: SE threshold (dB)")->capture_default_str();
  depth->add_option("--source-depth", d.source_depth_m, "Override the other node's depth (m)")->check(finite_number);
  depth->add_option("--consumer", d.consumer, "Consumer key: a newer request of the same key supersedes a waiting one")
      ->capture_default_str();
  depth->add_option("--deadline", d.deadline_s, "Seconds the model may take")->capture_default_str();
  depth->add_option("--png", d.png, "Also plot the objective against depth to this PNG")->type_name("FILE");
  depth->add_option("--noise-decrease", d.noise_decrease_db_per_km,
                    "Sonar equation, deep water: NL falls by this many dB/km below the profile's critical depth "
                    "(spec 6.6 after Schneider 2013 4.4; 3 is typical)")
      ->check(finite_number);
  depth->add_option("--forecast-horizon", d.forecast_horizon_s,
                    "Also run the forecast strategy (deep water): plan over this many seconds ahead, one window "
                    "every --horizon")
      ->check(finite_number);
  depth->add_option("--current-depth", d.current_depth_m, "Forecast: the vehicle's depth now (m)")->capture_default_str();
  depth->add_option("--vertical-speed", d.vertical_speed_mps, "Forecast: the vehicle's most vertical speed (m/s)")
      ->capture_default_str();
  depth->add_option("--caustic-uncertainty", d.caustic_uncertainty_m,
                    "Forecast: how well a caustic's depth is known (m); the objective is low-passed from the "
                    "surface with cutoff 1/this (0: --lowpass)")
      ->capture_default_str();
  depth->add_option("--leg-end", d.leg_end_m,
                    "Forecast: the range (m) where the vehicle's leg ends (a turn): no window past it is forecast")
      ->check(finite_number);
  depth->add_option("--reception-snr50", d.reception_snr50_db,
                    "Forecast with the sonar equation: the modem's SNR (dB) at which half the packets decode; the "
                    "plan then maximises the packets expected (default: the objective)")
      ->check(finite_number);
  depth->add_option("--reception-slope", d.reception_slope_per_db,
                    "Forecast: the reception curve's logistic slope (1/dB; 0: 1)")
      ->capture_default_str();
  depth->footer(
      "Examples:\n  acommsctl gram depth --range 3000 --speed 1.5 --max-depth 90 --min-altitude 5 --lowpass 0.02\n"
      "  acommsctl gram depth --range 30000 --speed 1.5 --max-depth 4900 --forecast-horizon 3600 --current-depth 20 "
      "--leg-end 60000\n"
      "  acommsctl gram depth --range 30000 --speed 1.5 --max-depth 4800 --source-level 190 --noise-level 93 "
      "--noise-decrease 3 --forecast-horizon 3600 --current-depth 20 --reception-snr50 10");
  depth->callback([&options] { run_depth(depth_options, options); });

  CLI::App* env = gram.add_subcommand("env", "The environment the daemon holds: show it, or feed it CTD casts");
  env->require_subcommand(1);
  env->footer(
      "Examples:\n"
      "  acommsctl gram env show\n"
      "  acommsctl gram env update --ctd cast.csv");
  CLI::App* show = env->add_subcommand("show", "Print the base environment and the profile instances held");
  show->footer("Example:\n  acommsctl gram env show --json");
  show->callback([&options] { run_env_show(options); });
  CLI::App* update = env->add_subcommand("update", "Add a CTD cast (raw samples, CSV) as a profile instance");
  update->add_option("--ctd", env_options.ctd, "The cast: depth_m or p_dbar, t90_degc, s_psu or conductivity_ms_per_cm, lat_deg")
      ->type_name("FILE.csv");
  update->add_option("--time", env_options.time_s, "When the cast was taken (s since the epoch; 0: now)")
      ->capture_default_str();
  update->add_flag("--clear", env_options.clear, "Drop the instances held first");
  update->footer(
      "Examples:\n"
      "  acommsctl gram env update --ctd cast.csv --time 1764000000\n"
      "  acommsctl gram env update --clear --ctd cast.csv");
  update->callback([&options] { run_env_update(env_options, options); });
}

}  // namespace acomms::cli
