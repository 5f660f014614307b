#pragma once
// What one HTTP connection may cost soiqd, enforced while the bytes arrive and before the bearer
// token is checked (http_request_parser.h, http_connection.cpp). The head of a request (request
// line and headers) is bounded by line, count and total; a body by the route's own limit (STOW:
// --max-upload-bytes; every other route takes none), chunked or not; time by --http-timeout
// (a head must arrive whole within it, a body or a reply may not stall longer); the number of
// connections by --http-max-connections. A client past a bound gets its own status and JSON error
// (414, 431, 413, 408, 503), never 500.
//
// The figures follow the servers that face the internet: Apache's LimitRequestLine and
// LimitRequestFieldSize (8190) and LimitRequestFields (100); nginx's 8 KiB header buffers. With
// 256 connections at 64 KiB of head each, a flood of heads holds at most 16 MiB.

#include <cstddef>
#include <cstdint>

namespace soiq::server::http {

struct HttpLimits {
  size_t max_request_line = 8192;  // method, target and version
  size_t max_header_line = 8192;   // one "Name: value"
  size_t max_header_count = 100;
  size_t max_head_bytes = 65536;  // the request line and every header, with their line ends
  int max_ranges = 1;             // byte ranges in one Range header; more are refused (416)
  int timeout_seconds = 20;       // --http-timeout
  int max_connections = 256;      // --http-max-connections
};

}  // namespace soiq::server::http
