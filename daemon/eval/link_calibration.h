#pragma once
// The link physics calibrated from what the modems heard (issue "the model
// meets the sea"; Schneider (2013) §4.3.5: "statistics on modem
// performance ... for feedback learning").
//
// Problem: the model's TL, the source level and the noise never match a
// real site, and the simulator, the depth-adaptation replay and the depth
// objective all judge packets by them. The event log holds, per packet
// heard ("packet" events), the SNR the modem measured (when it decoded)
// and the SNR the model predicted for that geometry; this turns them into
// the two corrections the physics takes (gram/site_correction.h,
// gram/reception_curve.h).
//
// Decision, per link (the node that sent, heard here) and rate:
//  - excess loss: over decoded packets with both SNRs, the offset
//    mean(measured − predicted) with its spread (sample standard deviation)
//    and a 95% interval of the mean; excess_loss_db = −offset (a loss is a
//    measured SNR below the prediction). One per link (all its rates).
//    That mean sees only the survivors: with scatter near the threshold it
//    overstates the offset, so where lost packets allow, the censored fit
//    (eval/censored_excess_loss.h) gives the offset used instead.
//  A "link" is this node's link that heard the packets (LinkFigures.link:
//  a node has several) and the node that sent them.
//  - reception curve: P(decoded) = 1 / (1 + exp(−k (x − x50))) with x the
//    predicted SNR, fitted by logistic regression (Newton's method, IRLS),
//    95% intervals from the inverse Fisher information (x50 by the delta
//    method). Against the predicted SNR because a packet that failed has no
//    measured one. The physics applies its curve to the corrected SNR,
//    predicted − excess, so the block's snr50_db is x50 + offset.
// Data too few to fit are refused with the reason, never fitted anyway:
// fewer than kMinMeasured decoded packets with a measured SNR (no excess
// loss), fewer than kMinPackets packets or fewer than kMinEachOutcome
// decoded or lost (no curve: its 50% point is not inside the data), or a
// fit that does not converge to a finite, positive slope (the decoded and
// lost packets separate perfectly: the slope is unbounded).
//
// Thread-safe: pure functions on values.
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "acomms/v1/acomms.pb.h"

namespace acomms::eval {

inline constexpr std::size_t kMinMeasured = 10;
inline constexpr std::size_t kMinPackets = 30;
inline constexpr std::size_t kMinEachOutcome = 5;

// One packet heard: what calibrate fits.
struct PacketSample {
  std::string link;   // the name of this node's link that heard it (LinkFigures.link)
  int32_t src = -1;   // the node that sent it
  int32_t rate = 0;   // whose reception curve applies (mini-packets: 0)
  double time = 0;
  bool decoded = false;
  std::optional<double> measured_snr_db;  // snr_in_db, decoded packets only
  double predicted_snr_db = 0;            // finite
};

// The "packet" events that carry a finite prediction; others (another
// kind, no prediction: the model or a position was missing, or a shadow)
// are counted in `skipped` when given.
std::vector<PacketSample> packet_samples(const std::vector<v1::Event>& events, std::size_t* skipped = nullptr);

struct ExcessLossFit {
  std::size_t packets = 0;
  double offset_db = 0;  // mean(measured − predicted)
  double spread_db = 0;  // their standard deviation
  double offset_ci95_db = 0;  // ± of the mean
  double excess_loss_db() const { return -offset_db; }
};

struct ReceptionFit {
  std::size_t packets = 0, decoded = 0;
  double snr50_predicted_db = 0;  // x50, against the predicted SNR
  double slope_per_db = 0;        // k
  double snr50_ci95_db = 0, slope_ci95_per_db = 0;  // ±
};

// Fits, or nullopt with the reason in `why`.
std::optional<ExcessLossFit> fit_excess_loss(const std::vector<PacketSample>& samples, std::string* why);
std::optional<ReceptionFit> fit_reception_curve(const std::vector<PacketSample>& samples, std::string* why);

struct RateCalibration {
  std::size_t packets = 0, decoded = 0;
  std::optional<ReceptionFit> curve;
  std::string curve_refused;  // why not, when curve is unset
};

struct CensoredExcessLossFit;  // eval/censored_excess_loss.h

struct LinkCalibration {
  std::string link;  // this node's link that heard them ("default" for a top-level driver/mac)
  int32_t src = -1;
  std::size_t packets = 0;
  std::optional<ExcessLossFit> excess;
  std::string excess_refused;  // why not, when excess is unset
  // The censored fit, counting the lost packets (eval/censored_excess_loss.h);
  // where it fits it is the excess loss the block prints, the decoded-only
  // mean shown beside it.
  std::shared_ptr<const CensoredExcessLossFit> censored;
  std::string censored_refused;
  // The offset the block uses: the censored fit's, else the decoded-only
  // mean's, else 0.
  double offset_db() const;
  std::map<int32_t, RateCalibration> rates;
  // Whether anything was fitted (else the link has too few data).
  bool fitted() const;
  // The curve's 50% point against the SNR the physics forms (predicted −
  // excess): snr50_predicted + offset (offset 0 without an excess fit).
  double physics_snr50_db(const ReceptionFit& curve) const;
};

// Per link of this node and sending node, its rates in order.
std::vector<LinkCalibration> calibrate_links(const std::vector<PacketSample>& samples);

// The `physics { ... }` block of sim.proto's SimPhysicsConfig for `link`:
// excess_loss_db and one reception { } per fitted rate, with '#' comments
// naming the figures; what to add to a sim node's driver.sim.physics.
std::string physics_block(const LinkCalibration& link);

// The human report: per link and rate, the figures and intervals, or why
// they were not fitted.
std::string calibration_report(const std::vector<LinkCalibration>& links);

}  // namespace acomms::eval
