#pragma once
// soiqd's address as people write it, turned into the target gRPC dials. Accepted:
//   HOST                       HOST:50051 (soiqd's default port)
//   HOST:PORT, [IPV6]:PORT     as is; a bare IPv6 address (::1) gets the default port
//   http://HOST[:PORT][/]      plaintext HOST:PORT (default 50051): soiqd speaks gRPC, and a URL
//   https://HOST[:PORT][/]     copied from a browser or a config means that host and port; https
//                              asks for TLS (verified against --tls-ca, else the system's roots)
//   unix:PATH, unix:///PATH, dns:///HOST[:PORT], ipv4:..., ipv6:...
//                              gRPC target URIs, as is (dns:/// gets port 50051 when it has none,
//                              where gRPC would pick 443)
// Errors  INVALID_ARGUMENT naming the text and the forms above: an empty address, another scheme
//         (grpc://, ftp://), a URL with a path, a port that is not a number in 1..65535.
// Cost    O(length). Pure: no name lookup (gRPC resolves when it connects).

#include <string>

#include "core/base/status.h"

namespace soiq::client {

inline constexpr int kDefaultPort = 50051;

struct ServerTarget {
  std::string grpc_target;  // for grpc::CreateChannel
  std::string shown;        // how messages name the server: HOST:PORT, or the URI
  bool tls = false;         // https:// was asked for
};

Result<ServerTarget> server_target(const std::string& address);

}  // namespace soiq::client
