#include "server/util/listen_check.h"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace soiq::server {
namespace {

struct HostPort {
  std::string host, port;
};

// "h:p" or "[v6]:p"; an empty host when there is no colon (the caller's message names the text).
HostPort split(const std::string& address) {
  if (address.starts_with("[")) {
    const size_t close = address.find("]:");
    if (close != std::string::npos) return {address.substr(1, close - 1), address.substr(close + 2)};
  }
  const size_t colon = address.rfind(':');
  if (colon == std::string::npos) return {"", ""};
  return {address.substr(0, colon), address.substr(colon + 1)};
}

// errno of binding a fresh stream socket to `a`, 0 on success.
int bind_errno(const addrinfo& a) {
  const int fd = ::socket(a.ai_family, a.ai_socktype, a.ai_protocol);
  if (fd < 0) return errno;
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  const int err = ::bind(fd, a.ai_addr, a.ai_addrlen) == 0 ? 0 : errno;
  ::close(fd);
  return err;
}

}  // namespace

std::string why_cannot_listen(const std::string& address) {
  const HostPort hp = split(address);
  if (hp.host.empty() || hp.port.empty()) return "'" + address + "' is not HOST:PORT";
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  const int gai = ::getaddrinfo(hp.host.c_str(), hp.port.c_str(), &hints, &found);
  if (gai != 0) return "cannot resolve '" + hp.host + "' with port '" + hp.port + "': " + ::gai_strerror(gai);
  int err = 0;
  for (const addrinfo* a = found; a != nullptr && err == 0; a = a->ai_next) err = bind_errno(*a);
  ::freeaddrinfo(found);
  switch (err) {
    case 0:
      return "";
    case EADDRINUSE:
      return address + " is already in use: is another soiqd running? Stop it, or give this one another --listen port";
    case EADDRNOTAVAIL:
      return "cannot listen on " + address + ": " + hp.host + " is not an address of this machine";
    case EACCES:
      return "cannot listen on " + address + ": port " + hp.port + " needs more privileges (ports below 1024)";
    default:
      return "cannot listen on " + address + ": " + std::strerror(err);
  }
}

}  // namespace soiq::server
