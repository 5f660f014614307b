#include "server/http/http_server.h"

#include <netinet/in.h>
#include <netinet/tcp.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/thread_pool.hpp>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <optional>
#include <thread>

#include "server/http/http_connection.h"
#include "server/http/http_status.h"
#include "server/util/log.h"

namespace soiq::server::http {
namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;

struct Address {
  std::string host;
  int port = 0;
};

Result<Address> parse_listen(const std::string& listen) {
  const size_t colon = listen.rfind(':');
  if (colon == std::string::npos || colon == 0) return invalid_argument("--http '" + listen + "' is not HOST:PORT");
  Address a;
  a.host = listen.substr(0, colon);
  if (a.host.size() > 2 && a.host.front() == '[' && a.host.back() == ']') a.host = a.host.substr(1, a.host.size() - 2);
  const std::string port = listen.substr(colon + 1);
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
      std::stoi(port) > 65535)
    return invalid_argument("--http '" + listen + "': the port must be 0..65535");
  a.port = std::stoi(port);
  return a;
}

// What a connection past --http-max-connections gets on plain HTTP before it is closed (on TLS it
// is closed at once: an answer would need a handshake, which is what the cap saves).
std::string too_many_connections() {
  const std::string body =
      error_body(Status(StatusCode::kUnavailable,
                        "this server has as many connections as it serves (--http-max-connections); "
                        "try again shortly"),
                 503);
  return "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\nConnection: close\r\n"
         "Retry-After: 1\r\nContent-Length: " +
         std::to_string(body.size()) + "\r\n\r\n" + body;
}

}  // namespace

struct HttpServer::Impl {
  HttpServerOptions options;
  std::shared_ptr<ServerShared> shared = std::make_shared<ServerShared>();
  asio::io_context io{1};
  std::optional<asio::ssl::context> tls;
  std::optional<asio::thread_pool> handlers;
  std::optional<tcp::acceptor> acceptor;
  std::thread thread;
  int port = 0;
  std::string scheme = "http";
  bool stopped = false;

  void accept() {
    acceptor->async_accept([this](boost::system::error_code ec, tcp::socket socket) {
      if (ec == asio::error::operation_aborted || !acceptor->is_open()) return;
      if (!ec) admit(std::move(socket));
      accept();
    });
  }

  void admit(tcp::socket socket) {
    size_t live = 0;
    {
      std::lock_guard<std::mutex> lock(shared->mutex);
      live = shared->live.size();
    }
    boost::system::error_code ignored;
    if (live >= size_t(options.limits.max_connections)) {
      if (!tls) {
        socket.non_blocking(true, ignored);
        static const std::string refusal = too_many_connections();
        socket.send(asio::buffer(refusal), 0, ignored);
      }
      log_event("warning", {{"event", "http_refused"}, {"why", "--http-max-connections"}});
      socket.shutdown(tcp::socket::shutdown_both, ignored);
      return;
    }
    // Nagle's algorithm would hold a small answer's last segment for the client's delayed ACK.
    socket.set_option(tcp::no_delay(true), ignored);
    serve_connection(shared, std::move(socket));
  }
};

HttpServer::HttpServer(HttpServerOptions options, Router router) : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  impl_->shared->limits = impl_->options.limits;
  impl_->shared->token = impl_->options.token;
  impl_->shared->cors_origin = impl_->options.cors_origin;
  impl_->shared->router = std::move(router);
}

HttpServer::~HttpServer() { stop(); }

Status HttpServer::start(const std::string& listen) {
  SOIQ_ASSIGN_OR_RETURN(const Address address, parse_listen(listen));
  Impl& m = *impl_;
  if (!m.options.tls_cert.empty()) {
    for (const std::string& f : {m.options.tls_cert, m.options.tls_key}) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(f, ec)) return invalid_argument("cannot read the TLS file '" + f + "'");
    }
    m.tls.emplace(asio::ssl::context::tls_server);
    boost::system::error_code ec;
    m.tls->set_options(asio::ssl::context::default_workarounds | asio::ssl::context::no_sslv2 |
                           asio::ssl::context::no_sslv3 | asio::ssl::context::no_tlsv1 | asio::ssl::context::no_tlsv1_1,
                       ec);
    m.tls->use_certificate_chain_file(m.options.tls_cert, ec);
    if (!ec) m.tls->use_private_key_file(m.options.tls_key, asio::ssl::context::pem, ec);
    if (ec) return invalid_argument("the TLS certificate or key could not be loaded for --http: " + ec.message());
    m.shared->tls = &*m.tls;
    m.scheme = "https";
  }
  boost::system::error_code ec;
  const asio::ip::address ip = asio::ip::make_address(address.host, ec);
  if (ec) return invalid_argument("--http '" + listen + "': '" + address.host + "' is not an IP address");
  m.acceptor.emplace(m.io);
  const tcp::endpoint endpoint(ip, static_cast<unsigned short>(address.port));
  m.acceptor->open(endpoint.protocol(), ec);
  // SO_REUSEADDR, not SO_REUSEPORT: a second soiqd on the same port must fail to start, not share
  // the requests and answer each from its own store.
  if (!ec) m.acceptor->set_option(tcp::acceptor::reuse_address(true), ec);
  if (!ec) m.acceptor->bind(endpoint, ec);
  if (!ec) m.acceptor->listen(asio::socket_base::max_listen_connections, ec);
  if (ec)
    return Status(StatusCode::kUnavailable,
                  "cannot listen for DICOMweb on " + listen + " (in use, or not an address here): " + ec.message());
  m.port = m.acceptor->local_endpoint().port();
  m.handlers.emplace(size_t(std::max(1, m.options.handler_threads)));
  m.shared->handlers = &*m.handlers;
  m.accept();
  m.thread = std::thread([&m] { m.io.run(); });
  return ok_status();
}

int HttpServer::port() const { return impl_->port; }

const std::string& HttpServer::scheme() const { return impl_->scheme; }

void HttpServer::stop() {
  Impl& m = *impl_;
  if (m.stopped || !m.thread.joinable()) return;
  m.stopped = true;
  {
    std::lock_guard<std::mutex> lock(m.shared->mutex);
    m.shared->stopping = true;
  }
  asio::post(m.io, [&m] {
    boost::system::error_code ignored;
    m.acceptor->close(ignored);
    std::lock_guard<std::mutex> lock(m.shared->mutex);
    for (auto& [id, weak] : m.shared->live) {
      // Closing runs on this thread, later: a connection's lock on `live` in its destructor must
      // not meet this one.
      asio::post(m.io, [weak = weak] {
        if (const std::shared_ptr<Connection> c = weak.lock()) c->close_if_idle();
      });
    }
  });
  // Requests under way finish and close their connections (they see `stopping`); wait for them,
  // at most one --http-timeout.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(m.options.limits.timeout_seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(m.shared->mutex);
      if (m.shared->live.empty()) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  m.handlers->join();
  m.io.stop();
  m.thread.join();
}

}  // namespace soiq::server::http
