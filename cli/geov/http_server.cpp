#include "http_server.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>

namespace acomms::cli::geov {
namespace {

void set_timeout(int fd, int option, double seconds) {
  timeval tv{};
  tv.tv_sec = static_cast<time_t>(seconds);
  tv.tv_usec = static_cast<suseconds_t>((seconds - static_cast<double>(tv.tv_sec)) * 1e6);
  ::setsockopt(fd, SOL_SOCKET, option, &tv, sizeof tv);
}

bool write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
  return true;
}

bool is_loopback(const sockaddr* address) {
  if (address->sa_family == AF_INET) {
    const auto* in = reinterpret_cast<const sockaddr_in*>(address);
    return (ntohl(in->sin_addr.s_addr) >> 24) == 127;
  }
  if (address->sa_family == AF_INET6) {
    const auto* in6 = reinterpret_cast<const sockaddr_in6*>(address);
    return IN6_IS_ADDR_LOOPBACK(&in6->sin6_addr);
  }
  return false;
}

// Reads until the blank line that ends the head; the head without it, or
// a refusal (too long, timed out, closed). The whole head must come within
// `timeout_s`: a deadline, not a wait per read, or a client sending a byte
// now and then would hold its connection (and, with enough of them, every
// connection) for hours before its token is even checked.
HttpParseResult read_request(int fd, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::string buffer;
  char chunk[2048];
  while (true) {
    const std::size_t end = buffer.find("\r\n\r\n");
    if (end != std::string::npos) return parse_http_request(std::string_view(buffer).substr(0, end));
    if (buffer.size() > kMaxHeadBytes) {
      return {std::nullopt, {431, "request head longer than " + std::to_string(kMaxHeadBytes) + " bytes"}};
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd ready{fd, POLLIN, 0};
    if (left.count() <= 0 || ::poll(&ready, 1, static_cast<int>(left.count())) == 0) {
      return {std::nullopt, {408, "no whole request head within the read timeout"}};
    }
    const ssize_t n = ::recv(fd, chunk, sizeof chunk, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) return {std::nullopt, {0, "closed before a whole request head"}};
    if (n < 0) return {std::nullopt, {408, "no whole request head within the read timeout"}};
    buffer.append(chunk, static_cast<std::size_t>(n));
  }
}

}  // namespace

std::string_view reason_phrase(int status) {
  switch (status) {
    case 200: return "OK";
    case 400: return "Bad Request";
    case 401: return "Unauthorized";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 408: return "Request Timeout";
    case 409: return "Conflict";
    case 413: return "Payload Too Large";
    case 422: return "Unprocessable Content";
    case 431: return "Request Header Fields Too Large";
    case 502: return "Bad Gateway";
    case 503: return "Service Unavailable";
    case 504: return "Gateway Timeout";
    case 505: return "HTTP Version Not Supported";
    default: return status < 500 ? "Client Error" : "Server Error";
  }
}

void HttpResponder::send(int status, std::string_view content_type, std::string_view body,
                         std::string_view extra_headers) {
  if (sent_) return;
  sent_ = true;
  std::string head = "HTTP/1.1 " + std::to_string(status) + " " + std::string(reason_phrase(status)) +
                     "\r\nContent-Type: " + std::string(content_type) +
                     "\r\nContent-Length: " + std::to_string(body.size()) +
                     "\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n" +
                     std::string(extra_headers) + "\r\n";
  if (!write_all(fd_, head)) return;
  if (!head_only_) write_all(fd_, body);
}

bool HttpResponder::start_stream(std::string_view content_type) {
  if (sent_) return false;
  sent_ = true;
  return write_all(fd_, "HTTP/1.1 200 OK\r\nContent-Type: " + std::string(content_type) +
                            "\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: close\r\n\r\n") &&
         !head_only_;
}

bool HttpResponder::write(std::string_view bytes) { return write_all(fd_, bytes); }

HttpServer::HttpServer(const HttpServerOptions& options, HttpHandler handler)
    : options_(options), handler_(std::move(handler)) {
  const std::size_t colon = options.listen.rfind(':');
  if (colon == std::string::npos || colon == 0) {
    throw std::runtime_error("--listen " + options.listen + ": want HOST:PORT, e.g. 127.0.0.1:8080");
  }
  std::string host = options.listen.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  const std::string port = options.listen.substr(colon + 1);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  if (int rc = ::getaddrinfo(host.c_str(), port.c_str(), &hints, &found); rc != 0) {
    throw std::runtime_error("--listen " + options.listen + ": " + ::gai_strerror(rc));
  }
  listen_fd_ = ::socket(found->ai_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  int one = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  loopback_ = is_loopback(found->ai_addr);
  const bool bound = listen_fd_ >= 0 && ::bind(listen_fd_, found->ai_addr, found->ai_addrlen) == 0 &&
                     ::listen(listen_fd_, 64) == 0;
  const int error = errno;
  ::freeaddrinfo(found);
  if (!bound) {
    if (listen_fd_ >= 0) ::close(listen_fd_);
    throw std::runtime_error("--listen " + options.listen + ": " + std::strerror(error));
  }
  sockaddr_storage local{};
  socklen_t length = sizeof local;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&local), &length);
  port_ = ntohs(local.ss_family == AF_INET6 ? reinterpret_cast<sockaddr_in6*>(&local)->sin6_port
                                            : reinterpret_cast<sockaddr_in*>(&local)->sin_port);
}

HttpServer::~HttpServer() {
  stop();
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return active_.load() == 0; });
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

void HttpServer::stop() {
  stopping_ = true;
  if (listen_fd_ >= 0) ::shutdown(listen_fd_, SHUT_RDWR);
  std::lock_guard lock(mutex_);
  for (int fd : open_fds_) ::shutdown(fd, SHUT_RDWR);
}

void HttpServer::run() {
  while (!stopping_) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      if (errno == EMFILE || errno == ENFILE) {
        // Out of descriptors: wait for some to close rather than spin.
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        continue;
      }
      break;  // shut down by stop()
    }
    set_timeout(fd, SO_RCVTIMEO, options_.read_timeout_s);
    set_timeout(fd, SO_SNDTIMEO, options_.write_timeout_s);
    if (active_.load() >= options_.max_connections) {
      ++refused_busy_;
      HttpResponder(fd, false).send(503, "text/plain; charset=utf-8",
                                    "busy: " + std::to_string(options_.max_connections) +
                                        " connections already open (acommsctl geov serve --max-connections)\n");
      ::close(fd);
      continue;
    }
    {
      std::lock_guard lock(mutex_);
      open_fds_.insert(fd);
      const int now = ++active_;
      int peak = peak_.load();
      while (now > peak && !peak_.compare_exchange_weak(peak, now)) {
      }
    }
    std::thread([this, fd] { serve(fd); }).detach();
  }
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return active_.load() == 0; });
}

void HttpServer::serve(int fd) {
  HttpParseResult parsed = read_request(fd, options_.read_timeout_s);
  if (parsed.request) {
    HttpResponder responder(fd, parsed.request->method == "HEAD");
    try {
      handler_(*parsed.request, responder);
    } catch (const std::exception& e) {
      responder.send(500, "text/plain; charset=utf-8", std::string("internal error: ") + e.what() + "\n");
    }
    if (!responder.sent()) responder.send(500, "text/plain; charset=utf-8", "no response\n");
  } else if (parsed.refusal.status != 0) {
    ++bad_requests_;
    HttpResponder(fd, false).send(parsed.refusal.status, "text/plain; charset=utf-8", parsed.refusal.reason + "\n");
  }
  {
    std::lock_guard lock(mutex_);
    open_fds_.erase(fd);
    ::close(fd);
    --active_;
    idle_.notify_all();  // under the lock: the destructor may run once it is released
  }
}

}  // namespace acomms::cli::geov
