#pragma once
// soiqd's HTTP front end (soiqd --http): DICOMweb under /dicom-web (QIDO-RS, WADO-RS, STOW-RS;
// docs/INTEROP.md) and soiq's own /soiq/v1/query, on the bounded server of http_server.h, with the
// gRPC side's TLS certificate and bearer token and the same engines (app_engines.h). This file
// holds the routes; http_server.h how a request is read, checked and answered.

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
