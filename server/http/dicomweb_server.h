#pragma once
// soiqd's HTTP front end (soiqd --http): DICOMweb under /dicom-web (QIDO-RS, WADO-RS, STOW-RS;
// docs/INTEROP.md) on cpp-httplib, with the gRPC side's TLS certificate and bearer token and the
// same engines (app_engines.h). Every request is checked before a handler runs: the token
// (401 with WWW-Authenticate: Bearer), the body size (--max-upload-bytes, 413), the route (404 with
// the JSON error body of http_status.h). Requests are logged by method, path, status and time; the
// query string is not (it may hold a patient's name).
//
// Why cpp-httplib: Debian packages it (libcpp-httplib-dev, built with OpenSSL), it is a server
// with TLS, a thread pool, payload limits and keep-alive in one small library, and its requests
// come parsed (path, query, headers) without a framework around them. Multipart bodies of STOW and
// WADO are soiq's own code (multipart.h): httplib parses only multipart/form-data.

#include <memory>
#include <string>

#include "core/base/status.h"
#include "server/app/app_engines.h"

namespace soiq::server::http {

class DicomwebServer {
 public:
  // `token` empty: no authentication. `tls_cert`/`tls_key`: PEM files (soiqd's own configuration,
  // never a client's choice); empty: plain HTTP.
  DicomwebServer(AppEngines engines, std::string token);
  ~DicomwebServer();
  DicomwebServer(const DicomwebServer&) = delete;
  DicomwebServer& operator=(const DicomwebServer&) = delete;

  // Binds HOST:PORT (port 0: any free one) and serves on threads of its own. UNAVAILABLE when the
  // address cannot be bound; INVALID_ARGUMENT for a malformed address or unreadable certificate.
  Status start(const std::string& listen);
  int port() const;
  // Stops accepting, lets the requests in progress finish, joins. Idempotent.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace soiq::server::http
