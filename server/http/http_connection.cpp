#include "server/http/http_connection.h"

#include <fcntl.h>
#include <openssl/crypto.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <chrono>
#include <future>
#include <memory>
#include <optional>

#include "server/http/cors.h"
#include "server/http/http_range.h"
#include "server/http/http_request_parser.h"
#include "server/http/http_status.h"
#include "server/http/pieces_body.h"
#include "server/util/log.h"
#include "server/util/temp_file.h"

namespace soiq::server::http {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace bhttp = boost::beast::http;
using tcp = asio::ip::tcp;

constexpr size_t kDrainBytes = size_t{1} << 20;  // read and dropped after refusing a body, at most
constexpr int kDrainSeconds = 2;

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\r' || c == '\n') c = ' ';
  return s;
}

HttpReply error_reply(int status, const Status& why) {
  return HttpReply{status, "application/json", error_body(why, status), {}};
}

// A file the body is written to as it arrives (STOW-RS: a request costs disk, not memory).
struct BodyFile {
  explicit BodyFile(TempFile f) : file(std::move(f)) {}
  BodyFile(const BodyFile&) = delete;
  BodyFile& operator=(const BodyFile&) = delete;
  TempFile file;
  int fd = -1;
  ~BodyFile() {
    if (fd >= 0) ::close(fd);
  }
};

template <class Stream>
class ConnectionOf : public Connection, public std::enable_shared_from_this<ConnectionOf<Stream>> {
 public:
  static constexpr bool kTls = !std::is_same_v<Stream, beast::tcp_stream>;

  template <class... Args>
  ConnectionOf(std::shared_ptr<ServerShared> shared, Args&&... args)
      : shared_(std::move(shared)),
        limits_(shared_->limits),
        stream_(std::forward<Args>(args)...),
        buffer_(limits_.max_head_bytes + 8192),
        read_deadline_(stream_.get_executor()) {}

  ~ConnectionOf() override {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    shared_->live.erase(id_);
  }

  void start() {
    {
      std::lock_guard<std::mutex> lock(shared_->mutex);
      id_ = shared_->next_id++;
      shared_->live[id_] = this->weak_from_this();
    }
    if constexpr (kTls) {
      lowest().expires_after(std::chrono::seconds(limits_.timeout_seconds));
      stream_.async_handshake(asio::ssl::stream_base::server, [self = this->shared_from_this()](beast::error_code ec) {
        if (ec) return self->close();
        self->read_head();
      });
    } else {
      read_head();
    }
  }

  void close_if_idle() override {
    if (phase_ == Phase::kHandshake || (phase_ == Phase::kIdle && !(parser_ && parser_->got_some()))) close();
  }

 private:
  enum class Phase { kHandshake, kIdle, kReading, kHandling, kWriting, kClosed };

  beast::tcp_stream& lowest() { return beast::get_lowest_layer(stream_); }
  std::chrono::seconds timeout() const { return std::chrono::seconds(limits_.timeout_seconds); }

  // Reads have a deadline of their own, not the stream's: the stream closes the socket when its
  // deadline passes, and a client whose head or body stalls is owed a 408 first. When this one
  // passes, the read is cancelled and its handler sees read_timed_out_.
  void arm_read_deadline() {
    lowest().expires_never();
    read_timed_out_ = false;
    const uint64_t generation = ++read_generation_;
    read_deadline_.expires_after(timeout());
    read_deadline_.async_wait([weak = this->weak_from_this(), generation](beast::error_code ec) {
      const auto self = weak.lock();
      if (ec || !self || self->read_generation_ != generation) return;
      self->read_timed_out_ = true;
      self->lowest().cancel();
    });
  }
  // Called first by every read's handler.
  void read_done() {
    ++read_generation_;
    read_deadline_.cancel();
  }
  bool stopping() const {
    std::lock_guard<std::mutex> lock(shared_->mutex);
    return shared_->stopping;
  }

  void read_head() {
    if (stopping()) return close();
    phase_ = Phase::kIdle;
    parser_.emplace(limits_);
    request_ = HttpRequest{};
    route_ = nullptr;
    body_.reset();
    body_pending_ = false;
    arm_read_deadline();
    bhttp::async_read_header(stream_, buffer_, *parser_,
                             [self = this->shared_from_this()](beast::error_code ec, size_t) { self->on_head(ec); });
  }

  void on_head(beast::error_code ec) {
    read_done();
    started_ = std::chrono::steady_clock::now();
    if (ec) {
      // A client that stayed silent is not owed an answer.
      if (read_timed_out_ && !parser_->got_some()) return close();
      return on_read_error(ec, "the request's head did not arrive whole within");
    }
    phase_ = Phase::kReading;
    const HttpRequestHead& head = parser_->head();
    request_.method = head.method;
    request_.target = head.target;
    request_.headers = head.headers;
    const bool has_body = parser_->chunked() || parser_->content_length().value_or(0) > 0;
    body_pending_ = has_body;
    if (Status s = parse_target(request_.target, request_.path, request_.params); !s.ok()) {
      request_.path = request_.target.substr(0, request_.target.find('?'));
      return refuse(400, s);
    }
    route_ = shared_->router.find(request_.method, request_.path, request_.matches);
    if (std::optional<HttpReply> preflight = cors_preflight(shared_->cors_origin, request_)) {
      if (has_body) close_after_ = true;
      return write(std::move(*preflight));
    }
    if (!authorized() && !(route_ != nullptr && route_->open)) {
      HttpReply r = error_reply(
          401, Status(StatusCode::kUnauthenticated, request_.has_header("Authorization")
                                                        ? "the bearer token is not valid for this server"
                                                        : "this server needs 'Authorization: Bearer TOKEN'"));
      r.headers.emplace("WWW-Authenticate", "Bearer");
      return write(std::move(r));
    }
    if (route_ == nullptr)  // the connection stays open unless a body was sent with the request
      return write(error_reply(404, not_found("no such resource: " + request_.method + " " + request_.path)));
    if (!has_body) return dispatch();
    const std::uint64_t announced = parser_->content_length().value_or(0);
    if (route_->max_body_bytes == 0 || announced > std::uint64_t(route_->max_body_bytes)) {
      parser_->accept_body(route_->max_body_bytes, route_->body_limit_name, nullptr);
      return refuse(413, parser_->body_refusal());
    }
    return receive_body();
  }

  // A read of the head or the body that failed: 408 when it ran out of time (`stalled` says how),
  // the parser's refusal for a request past a limit or not HTTP, else the client went: close.
  void on_read_error(beast::error_code ec, const char* stalled) {
    // On TLS a cancelled read leaves the session unusable: the connection just closes.
    if (read_timed_out_ && kTls) return close();
    if (read_timed_out_)
      return refuse(
          408, Status(StatusCode::kDeadlineExceeded,
                      std::string(stalled) + " " + std::to_string(limits_.timeout_seconds) + " s (--http-timeout)"));
    const auto data = buffer_.data();
    const std::string_view buffered(static_cast<const char*>(data.data()), data.size());
    if (const std::optional<Refusal> r = refusal_of(*parser_, ec, buffered, limits_))
      return refuse(r->http_status, r->why);
    return close();
  }

  // The body into a temporary file, as it arrives; then the handler.
  void receive_body() {
    Result<TempFile> file = TempFile::create(".body");
    if (!file.ok()) return refuse(500, file.status());
    body_.emplace(std::move(*file));
    body_->fd = ::open(body_->file.path().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (body_->fd < 0) return refuse(500, internal_error("cannot write a request body to soiqd's temporary folder"));
    const int fd = body_->fd;
    parser_->accept_body(route_->max_body_bytes, route_->body_limit_name, [fd](std::string_view piece) -> Status {
      while (!piece.empty()) {
        const ssize_t n = ::write(fd, piece.data(), piece.size());
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
          return errno == ENOSPC ? resource_exhausted("soiqd's temporary folder is full; try again later")
                                 : internal_error("cannot write a request body to soiqd's temporary folder");
        piece.remove_prefix(size_t(n));
      }
      return ok_status();
    });
    std::string expect = request_.header("Expect");
    for (char& c : expect) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (expect != "100-continue") return read_body();
    lowest().expires_after(timeout());
    asio::async_write(stream_, asio::buffer(kContinue, sizeof kContinue - 1),
                      [self = this->shared_from_this()](beast::error_code ec, size_t) {
                        if (ec) return self->close();
                        self->read_body();
                      });
  }

  void read_body() {
    arm_read_deadline();  // per piece: a large body may take long, but may not stall
    bhttp::async_read_some(stream_, buffer_, *parser_,
                           [self = this->shared_from_this()](beast::error_code ec, size_t) { self->on_body(ec); });
  }

  void on_body(beast::error_code ec) {
    read_done();
    if (ec) return on_read_error(ec, "the request body stalled for more than");
    if (!parser_->is_done()) return read_body();
    body_pending_ = false;
    ::close(body_->fd);
    body_->fd = -1;
    request_.body_path = body_->file.path();
    request_.body_bytes = parser_->body_bytes();
    dispatch();
  }

  bool authorized() const {
    if (shared_->token.empty()) return true;
    const std::string given = request_.header("Authorization");
    const std::string expected = "Bearer " + shared_->token;
    // Constant time: a wrong token must not leak how much of it was right.
    return given.size() == expected.size() && CRYPTO_memcmp(given.data(), expected.data(), given.size()) == 0;
  }

  // The handler on the handler pool; its answer comes back to this connection's thread.
  void dispatch() {
    phase_ = Phase::kHandling;
    lowest().expires_never();
    const int fd = lowest().socket().native_handle();
    request_.client_gone = [fd] {
      // The peer's FIN (POLLRDHUP) or a reset; data it may still send does not count.
      pollfd p{fd, POLLRDHUP, 0};
      return ::poll(&p, 1, 0) > 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR)) != 0;
    };
    if (request_.method == "GET") set_chunk_writers();
    asio::post(*shared_->handlers, [self = this->shared_from_this()] {
      Result<HttpReply> reply = self->run_handler();
      asio::post(self->stream_.get_executor(),
                 [self, reply = std::move(reply)]() mutable { self->answer(std::move(reply)); });
    });
  }

  Result<HttpReply> run_handler() {
    try {
      return route_->handle(request_);
    } catch (const std::exception& e) {
      return internal_error(std::string("an unexpected error: ") + e.what());
    } catch (...) {
      return internal_error("an unexpected error");
    }
  }

  // HEAD gets the whole answer's head from the plain path: only GET streams.
  void set_chunk_writers() {
    request_.start_chunks = [weak = this->weak_from_this()](const std::string& content_type) {
      return on_io(weak, [content_type](ConnectionOf& c, Done done) { c.write_chunked_head(content_type, done); });
    };
    request_.send_chunk = [weak = this->weak_from_this()](std::string piece) {
      return on_io(weak, [piece = std::make_shared<std::string>(std::move(piece))](ConnectionOf& c, Done done) {
        c.write_chunk(piece, done);
      });
    };
  }

  // A step of a chunked answer, run on the connection's thread while the handler's thread waits
  // for `done`: the handler never touches the socket, and each piece is written before the next
  // is made.
  using Done = std::function<void(Status)>;
  template <typename Step>
  static Status on_io(const std::weak_ptr<ConnectionOf>& weak, Step step) {
    const auto self = weak.lock();
    if (!self) return Status(StatusCode::kCancelled, "the HTTP client closed its connection");
    auto promise = std::make_shared<std::promise<Status>>();
    std::future<Status> result = promise->get_future();
    asio::post(self->stream_.get_executor(), [self, step, promise] {
      if (self->phase_ == Phase::kClosed) {
        promise->set_value(Status(StatusCode::kCancelled, "the HTTP client closed its connection"));
        return;
      }
      step(*self, [promise](Status s) { promise->set_value(std::move(s)); });
    });
    // A server that stops no longer runs its I/O thread's work: the wait is bounded by the write
    // timeout, and the step's late completion only sets a promise nobody reads.
    if (result.wait_for(self->timeout() + std::chrono::seconds(5)) != std::future_status::ready)
      return Status(StatusCode::kDeadlineExceeded, "a piece of the answer was not written within --http-timeout");
    return result.get();
  }

  static Status write_status(beast::error_code ec) {
    if (!ec) return ok_status();
    return Status(StatusCode::kCancelled, "the HTTP client closed its connection (" + ec.message() + ")");
  }

  void write_chunked_head(const std::string& content_type, const Done& done) {
    phase_ = Phase::kWriting;
    chunked_started_ = true;
    chunked_head_.emplace();
    bhttp::response<bhttp::empty_body>& res = *chunked_head_;
    res.version(11);
    res.result(bhttp::status::ok);
    res.set(bhttp::field::content_type, content_type);
    res.set(bhttp::field::cache_control, "no-store");
    std::multimap<std::string, std::string> cors;
    add_cors_headers(shared_->cors_origin, request_, cors);
    for (const auto& [name, value] : cors) res.insert(name, value);
    keep_alive_ = !close_after_ && parser_ && parser_->keep_alive() && !stopping();
    res.keep_alive(keep_alive_);
    res.chunked(true);
    chunked_serializer_.emplace(res);
    lowest().expires_after(timeout());
    bhttp::async_write_header(stream_, *chunked_serializer_,
                              [self = this->shared_from_this(), done](beast::error_code ec, size_t) {
                                if (ec) self->close();
                                done(write_status(ec));
                              });
  }

  void write_chunk(const std::shared_ptr<std::string>& piece, const Done& done) {
    if (piece->empty()) return done(ok_status());  // an empty chunk would end the answer
    chunked_bytes_ += int64_t(piece->size());
    lowest().expires_after(timeout());
    asio::async_write(stream_, bhttp::make_chunk(asio::buffer(*piece)),
                      [self = this->shared_from_this(), piece, done](beast::error_code ec, size_t) {
                        if (ec) self->close();
                        done(write_status(ec));
                      });
  }

  // The last chunk, then the next request or the end, as write_some does for a whole answer.
  void finish_chunked(int status) {
    log_answer(status, chunked_bytes_);
    lowest().expires_after(timeout());
    asio::async_write(stream_, bhttp::make_chunk_last(),
                      [self = this->shared_from_this()](beast::error_code ec, size_t) {
                        self->chunked_serializer_.reset();
                        self->chunked_head_.reset();
                        self->chunked_started_ = false;
                        self->chunked_bytes_ = 0;
                        if (ec || !self->keep_alive_ || self->body_pending_) return self->close();
                        self->read_head();
                      });
  }

  void log_answer(int status, int64_t size) {
    const auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started_).count();
    log_event("info", {{"event", "http"},
                       {"method", request_.method.empty() ? "-" : request_.method},
                       {"path", request_.path.empty() ? "-" : request_.path},
                       {"status", std::to_string(status)},
                       {"bytes", std::to_string(size)},
                       {"ms", std::to_string(int64_t(ms))}});
  }

  void answer(Result<HttpReply> r) {
    if (chunked_started_) {
      if (phase_ == Phase::kClosed) return;
      // Its status line went out as 200: a failure can only cut the answer short.
      if (!r.ok() || !r->chunked) {
        log_answer(r.ok() ? 500 : http_status_of(r.status().code()), chunked_bytes_);
        return close();
      }
      return finish_chunked(200);
    }
    if (!r.ok()) return write(error_reply(http_status_of(r.status().code()), r.status()));
    HttpReply reply = std::move(*r);
    if (reply.status == 406 && reply.body.empty() && reply.pieces.empty()) {
      const std::string type = reply.content_type.empty() ? "JSON" : reply.content_type;
      reply = error_reply(406, invalid_argument("not acceptable: this resource is answered as " + type));
    }
    if (request_.method == "GET") apply_range(request_.header("Range"), limits_.max_ranges, reply);
    write(std::move(reply));
  }

  // An error answer after which the connection closes (what the client sent may be unread).
  void refuse(int status, const Status& why) {
    close_after_ = true;
    write(error_reply(status, why));
  }

  void write(HttpReply reply) {
    phase_ = Phase::kWriting;
    if (body_pending_) close_after_ = true;
    response_.emplace();
    bhttp::response<PiecesBody>& res = *response_;
    res.version(parser_ && parser_->head().version == 10 ? 10 : 11);
    res.result(unsigned(reply.status));
    res.set(bhttp::field::content_type, reply.content_type.empty() ? "application/json" : reply.content_type);
    add_cors_headers(shared_->cors_origin, request_, reply.headers);
    for (const auto& [name, value] : reply.headers) res.insert(one_line(name), one_line(value));
    if (reply.status == 200 && request_.method == "GET") res.set(bhttp::field::accept_ranges, "bytes");
    const int64_t size = reply.size();
    held_ = std::move(reply.held);  // given back once the answer is out
    res.body().push_back(std::move(reply.body));
    for (std::string& p : reply.pieces) res.body().push_back(std::move(p));
    keep_alive_ = !close_after_ && parser_ && parser_->is_header_done() && parser_->keep_alive() && !stopping();
    res.keep_alive(keep_alive_);
    res.content_length(std::uint64_t(size));
    if (request_.method == "HEAD") res.body().clear();  // the head says the size; no body follows
    log_answer(reply.status, size);
    serializer_.emplace(res);
    write_some();
  }

  void write_some() {
    lowest().expires_after(timeout());  // per step: a large answer to a slow reader may take longer
    bhttp::async_write_some(stream_, *serializer_, [self = this->shared_from_this()](beast::error_code ec, size_t) {
      if (ec) return self->close();
      if (!self->serializer_->is_done()) return self->write_some();
      self->serializer_.reset();
      self->response_.reset();
      self->held_.clear();
      if (self->body_pending_) return self->drain();
      if (!self->keep_alive_) return self->close();
      self->read_head();
    });
  }

  // After refusing a body the client may still be sending: our side is shut, and what arrives is
  // read and dropped (1 MiB, 2 s at most), so the client reads the answer instead of a reset.
  void drain() {
    beast::error_code ignored;
    lowest().socket().shutdown(tcp::socket::shutdown_send, ignored);
    lowest().expires_after(std::chrono::seconds(kDrainSeconds));
    drain_some();
  }

  void drain_some() {
    lowest().async_read_some(asio::buffer(scratch_), [self = this->shared_from_this()](beast::error_code ec, size_t n) {
      self->drained_ += n;
      if (ec || self->drained_ >= kDrainBytes) return self->close();
      self->drain_some();
    });
  }

  void close() {
    if (phase_ == Phase::kClosed) return;
    phase_ = Phase::kClosed;
    beast::error_code ignored;
    lowest().socket().shutdown(tcp::socket::shutdown_both, ignored);
    lowest().close();
  }

  static constexpr char kContinue[] = "HTTP/1.1 100 Continue\r\n\r\n";

  std::shared_ptr<ServerShared> shared_;
  const HttpLimits limits_;
  Stream stream_;
  beast::flat_buffer buffer_;
  uint64_t id_ = 0;
  Phase phase_ = Phase::kHandshake;
  std::optional<HttpRequestParser> parser_;
  HttpRequest request_;
  const Route* route_ = nullptr;
  std::optional<BodyFile> body_;
  bool body_pending_ = false;  // the client sent a body this connection has not read
  bool close_after_ = false;
  bool keep_alive_ = false;
  std::optional<bhttp::response<PiecesBody>> response_;
  std::optional<bhttp::response_serializer<PiecesBody>> serializer_;
  std::vector<MemoryBudget::Reservation> held_;
  std::optional<bhttp::response<bhttp::empty_body>> chunked_head_;
  std::optional<bhttp::response_serializer<bhttp::empty_body>> chunked_serializer_;
  bool chunked_started_ = false;
  int64_t chunked_bytes_ = 0;
  asio::steady_timer read_deadline_;
  uint64_t read_generation_ = 0;
  bool read_timed_out_ = false;
  std::array<char, 16384> scratch_{};
  size_t drained_ = 0;
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace

void serve_connection(const std::shared_ptr<ServerShared>& shared, tcp::socket socket) {
  if (shared->tls != nullptr) {
    std::make_shared<ConnectionOf<beast::ssl_stream<beast::tcp_stream>>>(shared, std::move(socket), *shared->tls)
        ->start();
  } else {
    std::make_shared<ConnectionOf<beast::tcp_stream>>(shared, std::move(socket))->start();
  }
}

}  // namespace soiq::server::http
