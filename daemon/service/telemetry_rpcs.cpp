// SubmitNavigation and Track: position telemetry's way in and out.
#include <cmath>
#include <future>
#include <string>

#include "service/acomms_service.h"
#include "service/position_message.h"

namespace acomms::service {
namespace {

// The fix in local metres (z up), or the status that refuses it.
grpc::Status to_fix(const v1::NavigationFix& fix, uint64_t index, const telemetry::NodeSettings& settings,
                    telemetry::Fix* out) {
  const std::string where = "fix " + std::to_string(index) + ": ";
  auto invalid = [&](const std::string& what) {
    return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, where + what);
  };
  if (!std::isfinite(fix.time()) || fix.time() <= 0) {
    return invalid("time " + std::to_string(fix.time()) + " must be a positive number of seconds since the Unix epoch");
  }
  if (!std::isfinite(fix.depth()) || fix.depth() < -100 || fix.depth() > 12000) {
    return invalid("depth " + std::to_string(fix.depth()) + " must be within [-100, 12000] m");
  }
  out->time_s = fix.time();
  out->position_m[2] = -fix.depth();
  switch (fix.horizontal_case()) {
    case v1::NavigationFix::kLatlon: {
      if (!settings.datum) {
        return grpc::Status(grpc::StatusCode::FAILED_PRECONDITION,
                            where + "latlon needs telemetry.datum in the daemon's config (or send local x/y)");
      }
      const telemetry::LatLon at{fix.latlon().lat(), fix.latlon().lon()};
      try {
        telemetry::check_latlon(at, "latlon");
      } catch (const std::invalid_argument& e) {
        return invalid(e.what());
      }
      const telemetry::LocalXY local = settings.datum->to_local(at);
      out->position_m[0] = local.x;
      out->position_m[1] = local.y;
      return grpc::Status::OK;
    }
    case v1::NavigationFix::kLocal:
      if (!std::isfinite(fix.local().x()) || !std::isfinite(fix.local().y())) {
        return invalid("local.x and local.y must be finite");
      }
      out->position_m[0] = fix.local().x();
      out->position_m[1] = fix.local().y();
      return grpc::Status::OK;
    default:
      return invalid("latlon or local is required");
  }
}

}  // namespace

grpc::Status AcommsService::SubmitNavigation(grpc::ServerContext* context, grpc::ServerReader<v1::NavigationFix>* reader,
                                             v1::SubmitNavigationResponse* response) {
  if (grpc::Status denied = allowed(*context, "SubmitNavigation"); !denied.ok()) return denied;
  const telemetry::NodeSettings& settings = node_.telemetry.settings();
  v1::NavigationFix fix;
  uint64_t index = 0;
  while (reader->Read(&fix)) {
    telemetry::Fix local;
    grpc::Status status = to_fix(fix, index, settings, &local);
    if (!status.ok()) return status;
    node_.core.call([&] {
      const uint64_t before = node_.telemetry.counters().fixes;
      response->set_messages_queued(response->messages_queued() + node_.telemetry.on_fix(local));
      if (node_.telemetry.counters().fixes > before) {
        response->set_accepted_fixes(response->accepted_fixes() + 1);
      }
    });
    ++index;
  }
  response->set_ignored_fixes(index - response->accepted_fixes());
  // Answered once what the fixes queued is on disk: a client that saw the
  // answer knows a kill now loses none of it.
  std::promise<std::exception_ptr> stored;
  std::future<std::exception_ptr> done = stored.get_future();
  node_.core.call([&] {
    node_.telemetry.when_stored([&stored](std::exception_ptr error) { stored.set_value(error); });
  });
  if (std::exception_ptr error = done.get()) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      return grpc::Status(grpc::StatusCode::UNAVAILABLE, std::string("telemetry messages not stored: ") + e.what());
    }
  }
  return grpc::Status::OK;
}

grpc::Status AcommsService::Track(grpc::ServerContext* context, const v1::TrackRequest* request,
                                  v1::TrackResponse* response) {
  if (grpc::Status denied = allowed(*context, "Track"); !denied.ok()) return denied;
  if (!std::isfinite(request->since())) {
    return grpc::Status(grpc::StatusCode::INVALID_ARGUMENT, "since must be finite");
  }
  const size_t limit = request->limit() == 0 ? 100000 : request->limit();
  telemetry::TrackPage page = node_.track.track(request->src(), request->since(), limit);
  for (const telemetry::ReceivedPosition& p : page.positions) {
    *response->add_positions() = to_position(p, node_.telemetry.settings());
  }
  response->set_truncated(page.truncated);
  return grpc::Status::OK;
}

}  // namespace acomms::service
