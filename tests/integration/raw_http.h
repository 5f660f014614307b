#pragma once
// A raw TCP client for the HTTP limit tests: it sends exactly the bytes a hostile or broken client
// would (floods, half-sent heads, lies about lengths), which no HTTP library lets one send, and
// reads the answer as the bytes the server wrote.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

namespace soiq::testing {

struct RawResponse {
  int status = 0;    // 0: no status line arrived
  std::string head;  // status line and headers
  std::string body;
  std::vector<std::string> chunks;  // a chunked answer's pieces, as sent (body is them joined)
  bool closed = false;              // the server closed the connection after it
  std::string header(const std::string& name) const {
    std::string lower_head = head, lower_name = name + ":";
    for (char& c : lower_head) c = char(std::tolower(static_cast<unsigned char>(c)));
    for (char& c : lower_name) c = char(std::tolower(static_cast<unsigned char>(c)));
    const size_t at = lower_head.find("\r\n" + lower_name);
    if (at == std::string::npos) return "";
    const size_t from = at + 2 + lower_name.size();
    std::string v = head.substr(from, head.find("\r\n", from) - from);
    v.erase(0, v.find_first_not_of(' '));
    return v;
  }
};

class RawConnection {
 public:
  explicit RawConnection(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~RawConnection() {
    if (fd_ >= 0) ::close(fd_);
  }
  RawConnection(const RawConnection&) = delete;
  RawConnection& operator=(const RawConnection&) = delete;

  bool connected() const { return connected_; }

  // False once the server has closed or reset the connection.
  bool send(std::string_view bytes) {
    while (!bytes.empty()) {
      const ssize_t n = ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL);
      if (n <= 0) return false;
      bytes.remove_prefix(size_t(n));
    }
    return true;
  }

  // Sends `bytes` again and again until `total` bytes went, the server answered (then what it
  // wrote is kept for read_response) or it stopped reading; returns what was sent.
  size_t flood(std::string_view bytes, size_t total) {
    size_t sent = 0;
    while (sent < total && send(bytes)) {
      sent += bytes.size();
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 0) > 0) break;
    }
    return sent;
  }

  void close() {
    ::close(fd_);
    fd_ = -1;
  }

  // Closes our sending side only (the server sees the end of the request stream).
  void shutdown_send() { ::shutdown(fd_, SHUT_WR); }

  // One answer: its head, then its Content-Length of body, or everything until the server closes;
  // waits at most `timeout_s` for each piece.
  RawResponse read_response(int timeout_s = 60) {
    RawResponse r;
    size_t head_end = std::string::npos;
    while ((head_end = buffer_.find("\r\n\r\n")) == std::string::npos)
      if (!receive(timeout_s)) break;
    if (head_end == std::string::npos) {
      r.closed = eof_;
      r.head = buffer_;
      buffer_.clear();
      return r;
    }
    r.head = buffer_.substr(0, head_end);
    buffer_.erase(0, head_end + 4);
    if (r.head.rfind("HTTP/1.", 0) == 0) r.status = std::atoi(r.head.c_str() + 9);
    const std::string length = r.header("Content-Length");
    if (r.status / 100 == 1) {
      // An interim answer (100 Continue) has no body.
    } else if (r.header("Transfer-Encoding") == "chunked") {
      // size in hex CRLF, bytes CRLF, ..., then 0 CRLF CRLF (no trailers from soiqd).
      while (true) {
        size_t line_end;
        while ((line_end = buffer_.find("\r\n")) == std::string::npos)
          if (!receive(timeout_s)) break;
        if (line_end == std::string::npos) break;
        const size_t n = std::stoul(buffer_.substr(0, line_end), nullptr, 16);
        while (buffer_.size() < line_end + 2 + n + 2)
          if (!receive(timeout_s)) break;
        if (buffer_.size() < line_end + 2 + n + 2) break;
        if (n == 0) {
          buffer_.erase(0, line_end + 4);
          break;
        }
        r.chunks.push_back(buffer_.substr(line_end + 2, n));
        r.body += r.chunks.back();
        buffer_.erase(0, line_end + 2 + n + 2);
      }
    } else if (!length.empty()) {
      const size_t n = std::stoul(length);
      while (buffer_.size() < n)
        if (!receive(timeout_s)) break;
      r.body = buffer_.substr(0, n);
      buffer_.erase(0, std::min(n, buffer_.size()));
    } else {
      while (receive(timeout_s)) {
      }
      r.body = buffer_;
      buffer_.clear();
    }
    r.closed = eof_;
    return r;
  }

  // True when the server closes the connection (or resets it) within `timeout_s`; what it sends
  // before is kept for read_response.
  bool closed_within(int timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
    while (std::chrono::steady_clock::now() < deadline) {
      if (!receive(1) && eof_) return true;
    }
    return false;
  }

  // True once the server has sent `text` (kept for read_response), within `timeout_s`.
  bool received(const std::string& text, int timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
    while (buffer_.find(text) == std::string::npos && std::chrono::steady_clock::now() < deadline)
      if (!receive(1) && eof_) return false;
    return buffer_.find(text) != std::string::npos;
  }

  // True when nothing arrived and the connection is still open after `ms` milliseconds.
  bool open_after(int ms) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, ms) == 0) return true;
    return receive(0) || !eof_;
  }

 private:
  bool receive(int timeout_s) {
    if (eof_) return false;
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, timeout_s * 1000) <= 0) return false;
    char chunk[65536];
    const ssize_t n = ::recv(fd_, chunk, sizeof chunk, 0);
    if (n <= 0) {
      eof_ = true;
      return false;
    }
    buffer_.append(chunk, size_t(n));
    return true;
  }

  int fd_ = -1;
  bool connected_ = false;
  bool eof_ = false;
  std::string buffer_;
};

}  // namespace soiq::testing
