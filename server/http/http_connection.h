#pragma once
// One connection of http_server.h, and what every connection shares with the server. Internal to
// server/http: the server creates connections as it accepts sockets; each drives itself on the
// server's Asio thread until the client goes, a limit or a timeout ends it, or the server stops.

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/asio/thread_pool.hpp>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "server/http/http_limits.h"
#include "server/http/http_router.h"

namespace soiq::server::http {

class Connection {
 public:
  virtual ~Connection() = default;
  // On the Asio thread, when the server stops: closes the connection unless a request is under way.
  virtual void close_if_idle() = 0;
};

struct ServerShared {
  HttpLimits limits;
  std::string token;
  std::string cors_origin;  // cors.h; "": none
  Router router;
  boost::asio::thread_pool* handlers = nullptr;
  boost::asio::ssl::context* tls = nullptr;  // nullptr: plain HTTP

  std::mutex mutex;  // guards what follows: connections end on whichever thread lets them go
  bool stopping = false;
  uint64_t next_id = 0;
  std::map<uint64_t, std::weak_ptr<Connection>> live;
};

// Starts serving `socket` (its TLS handshake first when shared->tls is set). The connection
// registers itself in shared->live and leaves it when it goes.
void serve_connection(const std::shared_ptr<ServerShared>& shared, boost::asio::ip::tcp::socket socket);

}  // namespace soiq::server::http
