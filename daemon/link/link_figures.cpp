#include "link/link_figures.h"

namespace acomms::link {

v1::LinkFigures link_figures(const v1::ModemTransmission& transmission) {
  v1::LinkFigures link;
  link.set_transmission_src(transmission.src());
  link.set_rate(transmission.rate());
  link.set_link_quality(transmission.link_quality());
  if (!transmission.has_figures()) return link;
  const v1::ReceptionFigures& f = transmission.figures();
  if (f.has_snr_in_db()) link.set_snr_in_db(f.snr_in_db());
  if (f.has_snr_out_db()) link.set_snr_out_db(f.snr_out_db());
  if (f.has_signal_level_db()) link.set_signal_level_db(f.signal_level_db());
  if (f.has_mse_db()) link.set_mse_db(f.mse_db());
  if (f.has_doppler_mps()) link.set_doppler_mps(f.doppler_mps());
  if (f.has_delay_spread_s()) link.set_delay_spread_s(f.delay_spread_s());
  if (f.has_packet_type()) link.set_packet_type(f.packet_type());
  if (f.has_bad_frames()) link.set_bad_frames(f.bad_frames());
  if (f.has_noise_db()) link.set_noise_db(f.noise_db());
  if (f.has_range_m()) link.set_range_m(f.range_m());
  if (f.has_predicted_tl_db()) link.set_predicted_tl_db(f.predicted_tl_db());
  if (f.has_predicted_snr_db()) link.set_predicted_snr_db(f.predicted_snr_db());
  return link;
}

}  // namespace acomms::link
