#pragma once
// One daemon's contribution to the map: its live Subscribe stream (positions
// as they are reconstructed, link figures of every received message) and a
// poll once a second (Track since the last position held, for each vehicle
// it knows; the messages it has queued, by destination).
//
// Why both: the stream is immediate, and it resumes where it stopped
// (SubscribeRequest.after with the last seq handled, so what the daemon
// received while the feed reconnected is replayed, none twice), but it
// starts live: what came before the server started, and positions stored by
// a daemon older than the store's migration 0010 (they carry no seq), come
// from Track. Fleet stores each (vehicle, time) once, so the overlap is
// harmless and the track has no gap.
//
// Thread-safety: start() and stop() from the owner's thread; the feed runs
// two threads of its own that only call Fleet.

#include <condition_variable>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include <grpcpp/grpcpp.h>

#include "acomms/v1/acomms.grpc.pb.h"
#include "fleet.h"
#include "global_options.h"

namespace acomms::cli::geov {

class DaemonFeed {
 public:
  // `options.endpoint` names the daemon; its TLS options are used as given.
  DaemonFeed(GlobalOptions options, Fleet& fleet, double poll_s = 1.0);
  ~DaemonFeed();
  // Connects now: a daemon that cannot be reached at the start (a typo in
  // --daemon, a refused certificate) is an error the operator sees at once;
  // later losses are retried for as long as the server runs. Throws what
  // connect() throws.
  void connect_now();
  void start();
  void stop();

 private:
  void subscribe_loop();
  void poll_loop();
  void poll_once(v1::Acomms::Stub& stub);
  std::shared_ptr<v1::Acomms::Stub> stub();
  void drop_stub(const std::string& why);
  void say(const std::string& line);
  bool wait_for_stop(double seconds);

  GlobalOptions options_;
  Fleet& fleet_;
  double poll_s_;
  std::mutex mutex_;
  std::condition_variable stop_cv_;
  bool stopping_ = false;
  std::shared_ptr<v1::Acomms::Stub> stub_;
  grpc::ClientContext* stream_context_ = nullptr;
  std::set<int32_t> sources_;  // every vehicle this daemon named
  int32_t own_id_ = -1;
  // The last received seq the stream handled; 0 before the first (then the
  // stream starts live). Subscriber thread only.
  int64_t last_seq_ = 0;
  std::string last_said_;
  std::thread subscriber_;
  std::thread poller_;
};

}  // namespace acomms::cli::geov
