#include "client/server_target.h"

#include <algorithm>
#include <cctype>

namespace soiq::client {
namespace {

const char* const kForms =
    "write HOST, HOST:PORT, [IPV6]:PORT, http://HOST:PORT, https://HOST:PORT or unix:PATH "
    "(default port 50051)";

Status bad(const std::string& address, const std::string& why) {
  return invalid_argument("server address '" + address + "' " + why + ": " + kForms);
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// HOST, HOST:PORT, [V6], [V6]:PORT or a bare V6 address -> "host:port" with the port checked.
Result<std::string> host_and_port(const std::string& address, const std::string& authority) {
  std::string host = authority, port;
  if (authority.starts_with("[")) {
    const size_t close = authority.find(']');
    if (close == std::string::npos) return bad(address, "has an unclosed '['");
    host = authority.substr(0, close + 1);
    const std::string rest = authority.substr(close + 1);
    if (!rest.empty() && !rest.starts_with(":")) return bad(address, "has text after ']' that is not :PORT");
    if (!rest.empty()) port = rest.substr(1);
  } else if (std::count(authority.begin(), authority.end(), ':') > 1) {
    host = "[" + authority + "]";  // a bare IPv6 address: its colons are not a port
  } else if (const size_t colon = authority.rfind(':'); colon != std::string::npos) {
    host = authority.substr(0, colon);
    port = authority.substr(colon + 1);
  }
  if (host.empty() || host == "[]") return bad(address, "has no host");
  if (port.empty()) return host + ":" + std::to_string(kDefaultPort);
  if (!all_digits(port) || port.size() > 5 || std::stoi(port) < 1 || std::stoi(port) > 65535) {
    return bad(address, "has port '" + port + "', not a number in 1..65535");
  }
  return host + ":" + port;
}

}  // namespace

Result<ServerTarget> server_target(const std::string& address) {
  if (address.empty()) return bad(address, "is empty");
  if (std::any_of(address.begin(), address.end(), [](unsigned char c) { return std::isspace(c) || c < 0x20; })) {
    return bad(address, "contains spaces or control characters");
  }
  for (const char* uri : {"unix:", "unix-abstract:", "ipv4:", "ipv6:"}) {
    if (address.starts_with(uri)) return ServerTarget{address, address, false};
  }
  if (address.starts_with("dns:")) {
    // dns:HOST[:PORT] or dns://[AUTHORITY]/HOST[:PORT]: the name is after the last '/'.
    const size_t slash = address.find_last_of('/');
    const std::string prefix = slash == std::string::npos ? "dns:" : address.substr(0, slash + 1);
    SOIQ_ASSIGN_OR_RETURN(const std::string hp, host_and_port(address, address.substr(prefix.size())));
    return ServerTarget{prefix + hp, prefix + hp, false};
  }
  bool tls = false;
  std::string authority = address;
  if (const size_t scheme = address.find("://"); scheme != std::string::npos) {
    const std::string name = address.substr(0, scheme);
    if (name != "http" && name != "https")
      return bad(address, "has scheme '" + name + "://', which soiq does not speak");
    tls = name == "https";
    authority = address.substr(scheme + 3);
    if (const size_t slash = authority.find('/'); slash != std::string::npos) {
      if (slash + 1 != authority.size()) return bad(address, "has a path; soiqd is reached at the host and port alone");
      authority.resize(slash);
    }
  }
  SOIQ_ASSIGN_OR_RETURN(const std::string hp, host_and_port(address, authority));
  return ServerTarget{hp, hp, tls};
}

}  // namespace soiq::client
