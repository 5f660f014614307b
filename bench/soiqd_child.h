#pragma once
// A real soiqd for `soiq-bench query`, as a child process on a free loopback port (port 0, read
// back from --port-file), on a given SQLite file; stopped with SIGTERM (a graceful shutdown that
// checkpoints the WAL, so the file can be copied afterwards). The same approach as
// tests/integration/soiqd_process, kept separate so bench/ does not depend on tests/.

#include <sys/types.h>

#include <string>
#include <vector>

namespace soiq::bench {

class SoiqdChild {
 public:
  // Starts `binary --db db_path --listen 127.0.0.1:0 --port-file ... extra_args`; waits up to 60 s
  // for the port. On failure address() is empty and log() says why.
  SoiqdChild(const std::string& binary, const std::string& db_path, const std::vector<std::string>& extra_args);
  ~SoiqdChild();  // stop()
  SoiqdChild(const SoiqdChild&) = delete;
  SoiqdChild& operator=(const SoiqdChild&) = delete;

  const std::string& address() const { return address_; }
  // SIGTERM and wait (SIGKILL after 30 s); returns the exit status, 0 for a clean shutdown.
  int stop();
  std::string log() const;  // the server's stderr

 private:
  pid_t pid_ = -1;
  std::string address_;
  std::string log_path_;
  std::string port_path_;
};

}  // namespace soiq::bench
