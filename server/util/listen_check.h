#pragma once
// Why soiqd could not listen on an address, in words a person can act on. gRPC's BuildAndStart only
// says that it failed; this binds a TCP socket to the same address the way soiqd's server does
// (SO_REUSEADDR, so a closed connection in TIME_WAIT does not count; no SO_REUSEPORT, so a port a
// live process listens on does) and reports the reason the kernel gives.
//
// Input    HOST:PORT or [IPV6]:PORT, as soiqd's --listen takes it.
// Output   "" when the address can be bound now (the failure was elsewhere, e.g. TLS), else one
//          line: "127.0.0.1:50051 is already in use: is another soiqd running? ...", "HOST is not an
//          address of this machine", "port N needs root (below 1024)", "cannot resolve HOST: ...".
// Cost     one name lookup and one bind per address HOST resolves to. Thread-safe.
// Caveat   A probe, run after the real bind failed: another process may bind or release the port in
//          between. The refusal itself comes from the real bind.

#include <string>

namespace soiq::server {

std::string why_cannot_listen(const std::string& address);

}  // namespace soiq::server
