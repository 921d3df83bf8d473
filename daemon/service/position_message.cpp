#include "service/position_message.h"

#include "dccl/message_json.h"

namespace acomms::service {

telemetry::Position to_position(const telemetry::ReceivedPosition& p, const telemetry::NodeSettings& settings) {
  telemetry::Position out;
  out.set_src(p.src);
  out.set_time(static_cast<double>(p.time_s));
  out.set_x(p.position_m[0]);
  out.set_y(p.position_m[1]);
  out.set_z(p.position_m[2]);
  out.set_depth(p.position_m[2] == 0 ? 0 : -p.position_m[2]);
  out.set_full(p.full);
  if (settings.datum) {
    telemetry::LatLon at = settings.datum->to_latlon(telemetry::LocalXY{p.position_m[0], p.position_m[1]});
    out.set_lat(at.lat);
    out.set_lon(at.lon);
  }
  return out;
}

v1::ReceivedMessage to_received_message(const telemetry::Position& position, int32_t own_id, double now,
                                        int64_t seq) {
  v1::ReceivedMessage out;
  out.set_type(kPositionType);
  out.set_payload(position.SerializeAsString());
  out.set_json(dccl::message_json(position));
  out.set_src(position.src());
  out.set_dest(own_id);
  out.set_receive_time(now);
  out.set_seq(seq);
  return out;
}

}  // namespace acomms::service
