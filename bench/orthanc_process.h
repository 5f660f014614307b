#pragma once
// A real Orthanc (Debian's `orthanc` package, /usr/sbin/Orthanc) for `soiq-bench pacs` and
// `dicomweb`: its own configuration, storage and index in a temporary folder, DICOM on a free
// loopback port (HTTP off, or on with the DICOMweb plugin for `dicomweb`),
// every peer allowed to echo, store, find and C-GET, started and waited for (C-ECHO), stopped with
// SIGTERM (then SIGKILL). Not installed is not an error of the benchmark: start() says so and the
// caller leaves Orthanc's rows out.

#include <sys/types.h>

#include <string>

#include "dicom/pacs_peer.h"
#include "tests/support/temp_dir.h"

namespace soiq::bench {

class OrthancProcess {
 public:
  static constexpr const char* kAeTitle = "ORTHANC";

  OrthancProcess() = default;
  OrthancProcess(const OrthancProcess&) = delete;
  OrthancProcess& operator=(const OrthancProcess&) = delete;
  ~OrthancProcess() { stop(); }

  // "" when Orthanc answers C-ECHO, else why not ("not installed: ..." when the binary or, with
  // `dicomweb`, the plugin (orthanc-dicomweb) is missing). `dicomweb`: also HTTP on a free loopback
  // port (http_port()) with DICOMweb under /dicom-web.
  std::string start(bool dicomweb = false);
  int http_port() const { return http_port_; }
  void stop();
  dicom::PacsPeer peer() const;

 private:
  testing::TempDir dir_;
  pid_t pid_ = -1;
  int port_ = 0;
  int http_port_ = 0;
};

}  // namespace soiq::bench
