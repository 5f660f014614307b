#pragma once
// A real Orthanc (Debian's `orthanc` package, /usr/sbin/Orthanc) for `soiq-bench pacs`: its own
// configuration, storage and index in a temporary folder, DICOM on a free loopback port (HTTP off),
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

  // "" when Orthanc answers C-ECHO, else why not ("not installed: ..." when the binary is missing).
  std::string start();
  void stop();
  dicom::PacsPeer peer() const;

 private:
  testing::TempDir dir_;
  pid_t pid_ = -1;
  int port_ = 0;
};

}  // namespace soiq::bench
