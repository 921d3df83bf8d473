// Depth objective wire conversion (see depth_objective_proto.h).
#include "gram/depth_objective_proto.h"

#include <stdexcept>

namespace acomms::gram {

DepthObjectiveRequest request_from_proto(const DepthObjectiveQuery& q) {
  DepthObjectiveRequest r;
  r.range_m = q.range_m();
  r.speed_mps = q.speed_mps();
  r.heading_deg = q.heading_deg();
  r.horizon_s = q.horizon_s();
  switch (q.h_max_case()) {
    case DepthObjectiveQuery::kHMaxDb:
      r.h_max_db = q.h_max_db();
      break;
    case DepthObjectiveQuery::kHMaxWindowMaximum:
      if (!q.h_max_window_maximum())
        throw std::invalid_argument(
            "h_max_window_maximum = false: set h_max_db for a fixed H_max instead");
      r.h_max_db = std::nullopt;
      break;
    default:
      if (!q.has_sonar())
        throw std::invalid_argument(
            "h_max is not set: give h_max_db (e.g. 108) or h_max_window_maximum = true");
      r.h_max_db = std::nullopt;  // unused: the sonar objective replaces eq. 4.3
  }
  if (!q.has_limits())
    throw std::invalid_argument("limits is not set: give min_depth_m, max_depth_m, min_altitude_m");
  r.limits = {q.limits().min_depth_m(), q.limits().max_depth_m(), q.limits().min_altitude_m()};
  if (q.has_lowpass())
    r.lowpass = LowpassOptions{q.lowpass().cutoff_per_m(), q.lowpass().zero_phase()};
  if (q.has_sonar()) {
    const SonarEquationOptions& s = q.sonar();
    SonarOptions o;
    o.source_level_db = s.source_level_db();
    o.array_gain_db = s.array_gain_db();
    o.threshold_db = s.threshold_db();
    if (s.has_noise_decrease_db_per_km()) o.noise_decrease_db_per_km = s.noise_decrease_db_per_km();
    o.site.excess_loss_db = s.excess_loss_db();
    if (s.has_own_ship_noise_db()) o.site.own_ship_noise_db = s.own_ship_noise_db();
    switch (s.noise_case()) {
      case SonarEquationOptions::kNoiseLevelDb:
        o.noise_level_db = s.noise_level_db();
        break;
      case SonarEquationOptions::kNoiseBand:
        o.band = {s.noise_band().f_lo_khz(), s.noise_band().f_hi_khz(), s.noise_band().shipping(),
                  s.noise_band().wind_mps()};
        break;
      default:
        throw std::invalid_argument("sonar.noise is not set: give noise_level_db or noise_band");
    }
    r.sonar = o;
  }
  if (q.has_forecast()) {
    DepthForecastRequest f;
    f.forecast_horizon_s = q.forecast().forecast_horizon_s();
    f.current_depth_m = q.forecast().current_depth_m();
    f.options.vertical_speed_mps = q.forecast().vertical_speed_mps();
    f.caustic_uncertainty_m = q.forecast().caustic_uncertainty_m();
    if (q.forecast().has_leg_end_range_m()) f.leg_end_range_m = q.forecast().leg_end_range_m();
    if (q.forecast().has_reception_snr50_db()) {
      ReceptionCurve curve;
      curve.snr50_db = q.forecast().reception_snr50_db();
      if (q.forecast().reception_slope_per_db() != 0) curve.slope_per_db = q.forecast().reception_slope_per_db();
      f.reception = curve;
    } else if (q.forecast().reception_slope_per_db() != 0) {
      throw std::invalid_argument(
          "reception_slope_per_db is set without reception_snr50_db: give the curve's SNR50 too, or neither");
    }
    r.forecast = f;
  }
  if (auto e = validate_depth_objective_request(r)) throw std::invalid_argument(*e);
  return r;
}

DepthObjectiveReply reply_to_proto(const DepthObjectiveResult& result) {
  DepthObjectiveReply a;
  a.set_window_begin_m(result.window.begin_m);
  a.set_window_end_m(result.window.end_m);
  a.set_window_widened(result.window.widened);
  a.set_ranges_in_window(static_cast<std::uint32_t>(result.ranges_in_window));
  a.set_h_max_db(result.h_max_db);
  a.set_bottom_m(result.bottom_m);
  a.set_best_depth_m(result.best.depth_m);
  a.set_best_objective(result.best.objective);
  a.set_any_signal(result.best.any_signal);
  if (result.critical_depth_m) a.set_critical_depth_m(*result.critical_depth_m);
  for (std::size_t i = 0; i < result.depth_m.size(); ++i) {
    auto* p = a.add_points();
    p->set_depth_m(result.depth_m[i]);
    p->set_h_bar_db(result.h_bar_db[i]);
    p->set_band_low_db(result.band_low_db[i]);
    p->set_band_high_db(result.band_high_db[i]);
    p->set_objective(result.objective[i]);
    p->set_objective_filtered(result.objective_filtered[i]);
    if (i < result.signal_excess_db.size()) p->set_signal_excess_db(result.signal_excess_db[i]);
    if (i < result.noise_level_db.size()) p->set_noise_level_db(result.noise_level_db[i]);
  }
  if (result.forecast) {
    const DepthForecastResult& f = *result.forecast;
    DepthForecastAnswer* w = a.mutable_forecast();
    w->set_choice(forecast_choice_name(f.decision.choice));
    w->set_target_depth_m(f.decision.target_depth_m);
    w->set_target_time_s(f.decision.target_time_s);
    w->set_target_objective(f.decision.target_objective);
    w->set_vertical_rate_mps(f.decision.vertical_rate_mps);
    w->set_next_depth_m(f.next_depth_m);
    w->set_forecast_horizon_s(f.horizon_used_s);
    for (double z : f.decision.path_depth_m) w->add_path_depth_m(z);
    w->set_expected_score(f.decision.expected_score);
    for (std::size_t k = 0; k < f.field.time_s.size(); ++k) {
      DepthForecastColumn* c = w->add_columns();
      c->set_time_s(f.field.time_s[k]);
      c->set_window_begin_m(f.windows[k].begin_m);
      c->set_window_end_m(f.windows[k].end_m);
      for (double v : f.field.steer[k]) c->add_objective(v);
    }
  }
  return a;
}

}  // namespace acomms::gram
