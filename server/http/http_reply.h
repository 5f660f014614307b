#pragma once
// What an HTTP handler answers: a status, a content type, headers and the body's bytes. A body
// made of large pieces (the SEGs of a multipart answer) keeps them as they are, moved in, and the
// connection writes them one after another: an answer is built once, not copied per layer.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "server/app/memory_budget.h"

namespace soiq::server::http {

struct HttpReply {
  HttpReply() = default;
  HttpReply(int status, std::string content_type, std::string body,
            std::multimap<std::string, std::string> headers = {})
      : status(status), content_type(std::move(content_type)), body(std::move(body)), headers(std::move(headers)) {}

  int status = 200;
  std::string content_type;  // "" for application/json
  std::string body;          // the body's bytes; then `pieces`, back to back
  std::multimap<std::string, std::string> headers;
  std::vector<std::string> pieces;
  // The memory budget's share of the body's bytes, given back once the answer is written.
  std::vector<MemoryBudget::Reservation> held;
  // The handler sent its answer itself through HttpRequest::send_chunk; the rest of this is unused.
  bool chunked = false;

  int64_t size() const {
    int64_t n = int64_t(body.size());
    for (const std::string& p : pieces) n += int64_t(p.size());
    return n;
  }
};

}  // namespace soiq::server::http
