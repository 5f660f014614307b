#pragma once
// Cross-origin access (the Fetch standard's CORS protocol) for one configured origin (soiqd
// --http-cors-origin), so that a web viewer served from another site (OHIF on its own port) reads
// soiqd's DICOMweb. Off by default: a browser then lets no other site read soiqd.
//
// Why the preflight is answered before the token is checked: browsers send it without the
// Authorization header by design, and it reveals nothing but which methods and headers soiqd
// takes. Every actual request still needs the token.
//
// cors_preflight   an OPTIONS request from the allowed origin that asks for a method
//                  (Access-Control-Request-Method): 204 with the methods, headers and a 10-minute
//                  max age; nullopt for anything else (the request goes on to the token and routes).
// add_cors_headers the headers every answer to an allowed origin carries (errors included, so a
//                  viewer can read soiqd's message): Allow-Origin, Expose-Headers, Vary: Origin.
// `allowed` is the configured origin, "*" for any, "" for none. Thread-safe; no allocation beyond
// the headers.

#include <map>
#include <optional>
#include <string>

#include "server/http/http_reply.h"
#include "server/http/http_request.h"

namespace soiq::server::http {

std::optional<HttpReply> cors_preflight(const std::string& allowed, const HttpRequest& req);

void add_cors_headers(const std::string& allowed, const HttpRequest& req,
                      std::multimap<std::string, std::string>& headers);

}  // namespace soiq::server::http
