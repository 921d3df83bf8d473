#pragma once
// A raw HTTP client for the map server's tests: the bytes sent are exactly
// the test's (so malformed requests can be sent), the answer is read until
// the server closes, or, for an event stream, until a condition holds.
//
// Thread-safety: one client per thread.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <string>

namespace acomms::cli::geov::testing {

class RawHttp {
 public:
  explicit RawHttp(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
    timeval tv{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  ~RawHttp() { close(); }
  void close() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  bool connected() const { return connected_; }
  bool send(const std::string& bytes) { return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(bytes.size()); }
  // Reads until `done(text so far)` or the server closes or 5 s pass.
  std::string read_until(const std::function<bool(const std::string&)>& done) {
    char chunk[4096];
    while (!done(text_)) {
      const ssize_t n = ::recv(fd_, chunk, sizeof chunk, 0);
      if (n <= 0) break;
      text_.append(chunk, static_cast<std::size_t>(n));
    }
    return text_;
  }
  std::string read_all() {
    return read_until([](const std::string&) { return false; });
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
  std::string text_;
};

inline std::string get(int port, const std::string& target, const std::string& headers = "") {
  RawHttp http(port);
  http.send("GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) + "\r\n" + headers + "\r\n");
  return http.read_all();
}

inline int status_of(const std::string& response) {
  return response.size() > 12 ? std::stoi(response.substr(9, 3)) : 0;
}

inline std::string body_of(const std::string& response) {
  const std::size_t end = response.find("\r\n\r\n");
  return end == std::string::npos ? "" : response.substr(end + 4);
}

}  // namespace acomms::cli::geov::testing
