#pragma once
// What an HTTP handler answers: a status, a content type, headers and the body's bytes. A body
// made of large pieces (the SEGs of a multipart answer) keeps them as they are, moved in, and the
// connection writes them one after another: an answer is built once, not copied per layer.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace soiq::server::http {

struct HttpReply {
  int status = 200;
  std::string content_type;  // "" for application/json
  std::string body;          // the body's bytes; then `pieces`, back to back
  std::multimap<std::string, std::string> headers;
  std::vector<std::string> pieces;

  int64_t size() const {
    int64_t n = int64_t(body.size());
    for (const std::string& p : pieces) n += int64_t(p.size());
    return n;
  }
};

}  // namespace soiq::server::http
