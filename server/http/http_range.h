#pragma once
// Byte ranges of an answer (RFC 9110 section 14): soiqd serves one range of a 200 answer as a 206
// with Content-Range. A Range header that does not parse is ignored, as the RFC allows, and the
// whole answer goes out; more ranges than `max_ranges` are refused with 416, since each range
// would cost a copy of its bytes (one client asked for thousands, each of the whole answer); a
// range past the end is 416 with Content-Range: bytes */LENGTH.

#include <string>

#include "server/http/http_reply.h"

namespace soiq::server::http {

void apply_range(const std::string& range_header, int max_ranges, HttpReply& reply);

}  // namespace soiq::server::http
