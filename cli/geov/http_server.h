#pragma once
// The map's HTTP server: a small HTTP/1.1 server on POSIX sockets, one
// thread per connection, one request per connection.
//
// Why our own and not cpp-httplib:
// Debian 12's libcpp-httplib-dev ships the library compiled as a shared
// object only (libcpp-httplib.so, with a declarations-only httplib.h and
// no static archive), and acommsctl links every third-party library
// statically (tests/integration/check_static_linking.sh). The map needs
// little of HTTP: GET of built-in assets, JSON and PNG, and long-lived
// server-sent event streams, so the server is these two files.
//
// Bounds, so that whoever reaches the port cannot hurt the operator's
// display: at most max_connections at once (the next is answered 503 and
// closed), a request head of at most kMaxHeadBytes read within
// read_timeout_s, no body, and writes that stall longer than
// write_timeout_s end the connection (a viewer that went away costs a
// thread only until its next write fails).
//
// Thread-safety: run() on one thread; stop(), port() and the counters from
// any. The handler is called on connection threads, concurrently.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <string_view>

#include "http_request.h"

namespace acomms::cli::geov {

// What a handler answers with: either one whole response, or a stream.
class HttpResponder {
 public:
  HttpResponder(int fd, bool head_only) : fd_(fd), head_only_(head_only) {}
  // A whole response; extra_headers are complete lines ending in "\r\n".
  void send(int status, std::string_view content_type, std::string_view body,
            std::string_view extra_headers = {});
  // The head of an open-ended response (text/event-stream); then write().
  bool start_stream(std::string_view content_type);
  // False once the peer is gone (or stalled past the write timeout).
  bool write(std::string_view bytes);
  bool sent() const { return sent_; }

 private:
  int fd_;
  bool head_only_;
  bool sent_ = false;
};

using HttpHandler = std::function<void(const HttpRequest&, HttpResponder&)>;

struct HttpServerOptions {
  std::string listen = "127.0.0.1:8080";  // HOST:PORT; port 0: any free port
  int max_connections = 64;
  double read_timeout_s = 10;
  double write_timeout_s = 10;
};

class HttpServer {
 public:
  // Binds and listens now; throws std::runtime_error naming the address.
  HttpServer(const HttpServerOptions& options, HttpHandler handler);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  int port() const { return port_; }
  // True when the listening address is a loopback one (127/8, ::1).
  bool loopback() const { return loopback_; }
  // Accepts until stop(); returns once every connection has ended.
  void run();
  void stop();

  int active_connections() const { return active_.load(); }
  int peak_connections() const { return peak_.load(); }
  uint64_t refused_busy() const { return refused_busy_.load(); }
  uint64_t bad_requests() const { return bad_requests_.load(); }

 private:
  void serve(int fd);

  HttpServerOptions options_;
  HttpHandler handler_;
  int listen_fd_ = -1;
  int port_ = 0;
  bool loopback_ = false;
  std::atomic<bool> stopping_{false};
  std::atomic<int> active_{0};
  std::atomic<int> peak_{0};
  std::atomic<uint64_t> refused_busy_{0};
  std::atomic<uint64_t> bad_requests_{0};
  std::mutex mutex_;
  std::condition_variable idle_;
  std::set<int> open_fds_;
};

// "Not Found" for 404, ...: the reason phrase of a status this server uses.
std::string_view reason_phrase(int status);

}  // namespace acomms::cli::geov
