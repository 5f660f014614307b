#pragma once
// A real soiqd for integration tests and benchmarks: started as a child process on a free loopback
// port (port 0, read back from --port-file) with its own temporary directory and SQLite file, stopped with
// SIGTERM (graceful shutdown, which the tests also check) or killed with SIGKILL.
//
// With SOIQ_TEST_STORE=postgresql in the environment (ctest runs the integration tests once so,
// as postgresql.*), the store is a PostgreSQL database instead, on the test process's own server
// (postgres_process.h), one database per SQLite path a test names: a soiqd started again on the
// same path finds the same records.

#include <sys/types.h>

#include <string>
#include <vector>

#include "tests/support/temp_dir.h"

namespace soiq::testing {

// Whether this test process runs soiqd on PostgreSQL (SOIQ_TEST_STORE=postgresql).
bool soiqd_on_postgres();
// The --db a soiqd started for `db_path` gets: the path, or its PostgreSQL database's URI (made
// when missing); "" when PostgreSQL could not start (`why` says why).
std::string soiqd_store(const std::string& db_path, std::string& why);

class SoiqdProcess {
 public:
  // Starts `binary` (empty: this build's soiqd) with `--db db_path --listen 127.0.0.1:0` plus
  // `extra_args` (and --precompute off unless they say otherwise); waits (up to 60 s: a benchmark's database can be
  // large) for the port. On failure address() is empty and log() says why.
  SoiqdProcess(const std::string& db_path, const std::vector<std::string>& extra_args = {},
               const std::string& binary = "");
  ~SoiqdProcess();  // SIGTERM, then SIGKILL after 30 s
  SoiqdProcess(const SoiqdProcess&) = delete;
  SoiqdProcess& operator=(const SoiqdProcess&) = delete;

  bool running() const { return pid_ > 0; }
  const std::string& address() const { return address_; }
  int port() const { return port_; }
  // DICOMweb's port when extra_args had --http HOST:PORT (its port file is added), else 0.
  int http_port() const { return http_port_; }
  // Sends SIGTERM and waits up to 30 s (the shutdown checkpoints the WAL); returns the exit status
  // (0 for a clean shutdown), -1 on timeout.
  int terminate();
  // SIGKILL: a crash, nothing flushed by the server itself.
  void kill_hard();
  std::string log() const;  // the server's stderr so far
  // The server's peak resident memory so far (VmHWM from /proc), in bytes; -1 when unreadable.
  long long peak_rss_bytes() const;

 private:
  pid_t pid_ = -1;
  int port_ = 0;
  int http_port_ = 0;
  std::string address_;
  std::string log_path_;
  std::string port_path_;
};

}  // namespace soiq::testing
