#include "daemon_feed.h"

#include <cstdio>

#include "connection.h"

namespace acomms::cli::geov {
namespace {

constexpr const char* kPositionType = "acomms.telemetry.Position";

void set_deadline(grpc::ClientContext& context, double seconds) {
  context.set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
}

}  // namespace

DaemonFeed::DaemonFeed(GlobalOptions options, Fleet& fleet, double poll_s)
    : options_(std::move(options)), fleet_(fleet), poll_s_(poll_s) {}

DaemonFeed::~DaemonFeed() { stop(); }

void DaemonFeed::connect_now() {
  std::shared_ptr<v1::Acomms::Stub> stub = v1::Acomms::NewStub(connect(options_));
  std::lock_guard lock(mutex_);
  stub_ = std::move(stub);
}

void DaemonFeed::start() {
  poller_ = std::thread([this] { poll_loop(); });
  subscriber_ = std::thread([this] { subscribe_loop(); });
}

void DaemonFeed::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    if (stream_context_) stream_context_->TryCancel();
  }
  stop_cv_.notify_all();
  if (subscriber_.joinable()) subscriber_.join();
  if (poller_.joinable()) poller_.join();
}

bool DaemonFeed::wait_for_stop(double seconds) {
  std::unique_lock lock(mutex_);
  return stop_cv_.wait_for(lock, std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)),
                           [this] { return stopping_; });
}

// One line per change of state, not one per retry.
void DaemonFeed::say(const std::string& line) {
  std::lock_guard lock(mutex_);
  if (line == last_said_) return;
  last_said_ = line;
  std::fprintf(stderr, "acommsctl geov: %s: %s\n", options_.endpoint.c_str(), line.c_str());
}

std::shared_ptr<v1::Acomms::Stub> DaemonFeed::stub() {
  std::lock_guard lock(mutex_);
  return stub_;
}

void DaemonFeed::drop_stub(const std::string& why) {
  {
    std::lock_guard lock(mutex_);
    stub_.reset();
  }
  say("lost (" + why + "); reconnecting");
}

void DaemonFeed::poll_loop() {
  while (true) {
    std::shared_ptr<v1::Acomms::Stub> current = stub();
    if (!current) {
      try {
        current = v1::Acomms::NewStub(connect(options_));
        std::lock_guard lock(mutex_);
        stub_ = current;
      } catch (const std::exception& e) {
        say(e.what());
      }
      if (current) say("connected");
    }
    if (current) poll_once(*current);
    if (wait_for_stop(poll_s_)) return;
  }
}

void DaemonFeed::poll_once(v1::Acomms::Stub& stub) {
  {
    grpc::ClientContext context;
    set_deadline(context, options_.timeout_s);
    v1::LinkStatusResponse link;
    grpc::Status status = stub.LinkStatus(&context, v1::LinkStatusRequest(), &link);
    if (!status.ok()) return drop_stub(status.error_message());
    std::lock_guard lock(mutex_);
    own_id_ = static_cast<int32_t>(link.modem_id());
    for (int32_t node : link.known_nodes()) sources_.insert(node);
  }
  std::set<int32_t> sources;
  {
    std::lock_guard lock(mutex_);
    sources = sources_;
    sources.erase(own_id_);
  }
  for (int32_t src : sources) {
    grpc::ClientContext context;
    set_deadline(context, options_.timeout_s);
    v1::TrackRequest request;
    request.set_src(src);
    request.set_since(fleet_.last_time(src));  // >=: the last one again, stored once
    v1::TrackResponse track;
    grpc::Status status = stub.Track(&context, request, &track);
    if (!status.ok()) return drop_stub(status.error_message());
    fleet_.add_positions({track.positions().begin(), track.positions().end()});
  }
  grpc::ClientContext context;
  set_deadline(context, options_.timeout_s);
  v1::ListQueuedRequest request;
  request.set_limit(1000);
  v1::ListQueuedResponse queued;
  grpc::Status status = stub.ListQueued(&context, request, &queued);
  if (!status.ok()) return drop_stub(status.error_message());
  std::map<int32_t, std::vector<QueuedToVehicle>> by_dest;
  for (const v1::QueuedMessage& m : queued.messages()) {
    by_dest[m.dest()].push_back({m.message_id(), m.type(), m.submitted_at(), m.in_flight()});
  }
  fleet_.set_queued(options_.endpoint, std::move(by_dest));
}

void DaemonFeed::subscribe_loop() {
  while (true) {
    std::shared_ptr<v1::Acomms::Stub> current = stub();
    if (current) {
      grpc::ClientContext context;
      {
        std::lock_guard lock(mutex_);
        if (stopping_) return;
        stream_context_ = &context;
      }
      v1::SubscribeRequest request;
      if (last_seq_ > 0) request.set_after(last_seq_);
      auto reader = current->Subscribe(&context, request);
      v1::ReceivedMessage message;
      bool resumed_said = false;
      while (reader->Read(&message)) {
        if (message.seq() > 0) last_seq_ = message.seq();
        if (request.has_after() && !resumed_said) {
          resumed_said = true;
          say("stream resumed after seq " + std::to_string(request.after()));
        }
        if (message.type() == kPositionType) {
          telemetry::Position p;
          if (p.ParseFromString(message.payload())) {
            fleet_.add_positions({p});
            // Heard now, through the telemetry it sent (the figures of the
            // frame, when the daemon passed them on).
            fleet_.heard(p.src(), message.receive_time(), message.has_link() ? &message.link() : nullptr);
            std::lock_guard lock(mutex_);
            sources_.insert(p.src());
          }
        } else if (message.has_link()) {
          fleet_.heard(message.src(), message.receive_time(), &message.link());
          std::lock_guard lock(mutex_);
          sources_.insert(message.src());
        }
      }
      grpc::Status status = reader->Finish();
      {
        std::lock_guard lock(mutex_);
        stream_context_ = nullptr;
      }
      if (status.error_code() == grpc::StatusCode::OUT_OF_RANGE) {
        // Pruned past our seq (the daemon was away longer than its store
        // keeps): start live again; Track still fills the positions.
        say("stream cannot resume (" + status.error_message() + "); live from now, positions from Track");
        last_seq_ = 0;
      } else if (!status.ok() && status.error_code() != grpc::StatusCode::CANCELLED) {
        say("stream ended: " + status.error_message());
      }
    }
    if (wait_for_stop(0.5)) return;
  }
}

}  // namespace acomms::cli::geov
