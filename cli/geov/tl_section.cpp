#include "tl_section.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "acomms/v1/acomms.grpc.pb.h"
#include "acomms/v1/gram.grpc.pb.h"
#include "connection.h"
#include "gram_plot.h"
#include "rpc_error.h"
#include "plot/axes.h"
#include "util/seconds.h"

namespace acomms::cli::geov {
namespace {

constexpr double kEnvironmentDeadlineS = 5, kRunDeadlineS = 30;

void set_deadline(grpc::ClientContext& context, double seconds) {
  context.set_deadline(std::chrono::system_clock::now() +
                       std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
}

std::string metres(double m) { return plot::tick_label(m, m < 100 ? 0.1 : 1); }

SectionRefusal refusal_of(const grpc::Status& status, const std::string& what) {
  switch (status.error_code()) {
    case grpc::StatusCode::UNAVAILABLE:
      return {503, what + ": the daemon cannot be reached now (" + status.error_message() + ")"};
    case grpc::StatusCode::RESOURCE_EXHAUSTED:
      return {503, what + ": the daemon's model is busy (" + status.error_message() + "); try again shortly"};
    case grpc::StatusCode::DEADLINE_EXCEEDED:
      return {504, what + ": the daemon's model took longer than " + metres(kRunDeadlineS) + " s"};
    default:
      return {502, what + ": the daemon refused: " + std::string(status_code_name(status.error_code())) + ": " +
                       status.error_message()};
  }
}

}  // namespace

SectionPlan plan_section(const gram::KnownEnvironment& held, double range_m) {
  SectionPlan plan;
  plan.drawn = held.base();
  if (held.instances_size() > 0) {
    *plan.drawn.mutable_sound_speed() = held.instances(held.instances_size() - 1).sound_speed();
  }
  if (plan.drawn.sound_speed_size() < 2 || !(plan.drawn.frequency_hz() > 0)) {
    throw SectionRefusal{503, "the daemon holds no environment (no sound speed profile or frequency): give gram.base "
                              "in its config, or a cast: acommsctl gram env update --ctd CAST.csv"};
  }
  if (!(range_m <= kMaxSectionM / 1.25)) {
    throw SectionRefusal{422, "the vehicle is " + metres(range_m) + " m from the buoy; the map draws sections up to " +
                                  metres(kMaxSectionM / 1.25) + " m"};
  }
  plan.range_m = range_m;
  plan.length_m = std::max(kMinSectionM, std::ceil(range_m * 1.25 / 10) * 10);
  const double top = plan.drawn.sound_speed(0).depth_m();
  double bottom = plan.drawn.sound_speed(plan.drawn.sound_speed_size() - 1).depth_m();
  if (plan.drawn.bathymetry_size() > 0) {
    double deepest = 0;
    for (const auto& point : plan.drawn.bathymetry()) deepest = std::max(deepest, point.depth_m());
    bottom = std::min(bottom, deepest);
  }
  gram::Environment& request = plan.request;
  for (int i = 0; i < kRanges; ++i) request.add_receiver_range_m(plan.length_m * i / (kRanges - 1));
  for (int i = 0; i < kDepths; ++i) request.add_receiver_depth_m(top + (bottom - top) * i / (kDepths - 1));
  // Rays stop past the section, not before it.
  request.set_box_range_m(std::max(plan.drawn.box_range_m(), plan.length_m * 1.05));
  plan.drawn.clear_irregular_receivers();
  *plan.drawn.mutable_receiver_range_m() = request.receiver_range_m();
  *plan.drawn.mutable_receiver_depth_m() = request.receiver_depth_m();
  plan.drawn.set_box_range_m(request.box_range_m());
  return plan;
}

TlSection::TlSection(GlobalOptions daemon, const Fleet& fleet) : daemon_(std::move(daemon)), fleet_(fleet) {}
TlSection::~TlSection() = default;

SectionPicture TlSection::picture(const telemetry::Position& vehicle) {
  std::lock_guard lock(mutex_);
  const double now = util::unix_seconds_now();
  auto it = kept_.find(vehicle.src());
  if (it != kept_.end()) {
    const Kept& k = it->second;
    const double moved = std::hypot(vehicle.x() - k.x, vehicle.y() - k.y);
    if (now - k.made_at < kReuseS && moved < 0.02 * std::max(k.range_m, 100.0) &&
        std::abs(vehicle.depth() - k.depth) < 2) {
      return {k.png, k.range_m};
    }
  }
  SectionPicture made = run(vehicle);
  kept_[vehicle.src()] = Kept{vehicle.x(), vehicle.y(), vehicle.depth(), made.range_m, now, made.png};
  return made;
}

SectionPicture TlSection::run(const telemetry::Position& vehicle) {
  std::shared_ptr<grpc::Channel> channel;
  try {
    channel = connect(daemon_);
  } catch (const std::exception& e) {
    throw SectionRefusal{503, e.what()};
  }
  // The buoy: the daemon's own node, at its last position or the datum.
  auto api = v1::Acomms::NewStub(channel);
  v1::LinkStatusResponse link;
  {
    grpc::ClientContext context;
    set_deadline(context, kEnvironmentDeadlineS);
    if (grpc::Status s = api->LinkStatus(&context, v1::LinkStatusRequest(), &link); !s.ok()) {
      throw refusal_of(s, "the buoy's node id");
    }
  }
  const int32_t buoy = static_cast<int32_t>(link.modem_id());
  double bx = 0, by = 0;
  if (auto own = fleet_.last_position(buoy)) {
    bx = own->x();
    by = own->y();
  }
  auto model = v1::Gram::NewStub(channel);
  gram::KnownEnvironment held;
  {
    grpc::ClientContext context;
    set_deadline(context, kEnvironmentDeadlineS);
    if (grpc::Status s = model->GetEnvironment(&context, v1::GetEnvironmentRequest(), &held); !s.ok()) {
      throw refusal_of(s, "the daemon's environment");
    }
  }
  const SectionPlan plan = plan_section(held, std::hypot(vehicle.x() - bx, vehicle.y() - by));
  v1::TransmissionLossRequest request;
  *request.mutable_header()->mutable_environment() = plan.request;
  request.mutable_header()->set_consumer("geov-section");
  v1::TransmissionLossReply reply;
  {
    grpc::ClientContext context;
    set_deadline(context, kRunDeadlineS);
    if (grpc::Status s = model->TransmissionLoss(&context, request, &reply); !s.ok()) {
      throw refusal_of(s, "the transmission-loss run");
    }
  }
  gram::TransmissionLoss tl;
  tl.range_m.assign(reply.range_m().begin(), reply.range_m().end());
  tl.depth_m.assign(reply.depth_m().begin(), reply.depth_m().end());
  tl.tl_db.assign(reply.tl_db().begin(), reply.tl_db().end());
  tl.irregular = reply.irregular();
  if (tl.irregular || tl.range_m.empty() || tl.depth_m.empty() || tl.tl_db.size() != tl.range_m.size() * tl.depth_m.size()) {
    throw SectionRefusal{502, "the daemon's transmission loss is not the grid asked for"};
  }
  TlMarks marks;
  marks.source = "buoy, node " + std::to_string(buoy);
  marks.receiver = TlReceiver{plan.range_m, vehicle.depth(),
                              "node " + std::to_string(vehicle.src()) + ", " + metres(vehicle.depth()) + " m"};
  const std::string input = "node " + std::to_string(buoy) + " towards node " + std::to_string(vehicle.src()) + " (" +
                            metres(plan.range_m) + " m)";
  return {draw_tl(tl, plan.drawn, input, marks).png(), plan.range_m};
}

}  // namespace acomms::cli::geov
