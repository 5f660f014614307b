#pragma once
// Test support: a real PACS on loopback, DCMTK's dcmqrscp, in a temporary folder, and DCMTK's
// storescu to load it. Header-only so the tests/dicom glob (*_test.cpp) needs no CMake change.
//
// DcmqrscpProcess::start picks a free loopback port, writes a dcmqrscp.cfg with one AE
// (kAeTitle) whose storage area is in the folder and whose peers are ANY, starts dcmqrscp in
// its own process group and polls C-ECHO until it answers (bounded). The destructor sends
// SIGTERM, then SIGKILL, to the whole group (dcmqrscp forks one child per association).
// Both tools get TCP_NODELAY=1: with Nagle's algorithm each small DIMSE response waits for a
// delayed ACK, 98 files then take 9 s to load instead of 0.5 s.

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "dicom/pacs_echo.h"
#include "dicom/pacs_peer.h"
#include "tests/support/child_process.h"
#include "tests/support/temp_dir.h"

namespace soiq::dicom::testing {

using soiq::testing::TempDir;

using soiq::testing::find_on_path;
using soiq::testing::free_loopback_port;
using soiq::testing::read_text;
using soiq::testing::run_tool;
using soiq::testing::stop_process_group;

class DcmqrscpProcess {
 public:
  static constexpr const char* kAeTitle = "SOIQTEST";

  DcmqrscpProcess() = default;
  DcmqrscpProcess(const DcmqrscpProcess&) = delete;
  DcmqrscpProcess& operator=(const DcmqrscpProcess&) = delete;
  ~DcmqrscpProcess() { stop(); }

  // "" when running, else why not (binary missing: starts with "not installed"). `extra_args` go
  // to dcmqrscp before the port, e.g. {"+xt"}: accept (and store) JPEG-LS lossless.
  std::string start(const std::vector<std::string>& extra_args = {}) {
    const std::string binary = find_on_path("dcmqrscp");
    if (binary.empty()) return "not installed: dcmqrscp is not on PATH (Debian package dcmtk)";
    const std::filesystem::path storage = dir_.path() / "db" / kAeTitle;
    std::filesystem::create_directories(storage);
    // The port can be taken between our probe and dcmqrscp's bind: try a few.
    for (int attempt = 0; attempt < 3; ++attempt) {
      port_ = free_loopback_port();
      const std::filesystem::path cfg = dir_.path() / "dcmqrscp.cfg";
      std::ofstream(cfg) << "NetworkTCPPort = " << port_ << "\nMaxPDUSize = 65536\nMaxAssociations = 16\n"
                         << "HostTable BEGIN\nHostTable END\nVendorTable BEGIN\nVendorTable END\n"
                         << "AETable BEGIN\n"
                         // Quota: dcmqrscp deletes the oldest studies beyond it; keep it far away.
                         << kAeTitle << " " << storage.string() << " RW (1000, 1024mb) ANY\n"
                         << "AETable END\n";
      pid_ = ::fork();
      if (pid_ < 0) return "fork failed";
      if (pid_ == 0) {
        ::setpgid(0, 0);
        const int fd = ::open(log_path().c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) {
          ::dup2(fd, 1);
          ::dup2(fd, 2);
        }
        ::setenv("TCP_NODELAY", "1", 1);
        std::vector<std::string> argv = {binary, "-c", cfg.string()};
        argv.insert(argv.end(), extra_args.begin(), extra_args.end());
        argv.push_back(std::to_string(port_));
        std::vector<char*> args;
        for (std::string& a : argv) args.push_back(a.data());
        args.push_back(nullptr);
        ::execv(binary.c_str(), args.data());
        ::_exit(127);
      }
      ::setpgid(pid_, pid_);  // also from here, so a kill right after fork reaches the group
      // Bounded wait for the first C-ECHO: 10 s at 20 ms steps.
      PacsPeer probe = peer();
      probe.timeout_seconds = 2;
      for (int i = 0; i < 500; ++i) {
        if (pacs_echo(probe).ok()) return "";
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) {
          pid_ = -1;
          break;  // exited (port taken?): next attempt
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      stop();
    }
    return "dcmqrscp did not answer C-ECHO on port " + std::to_string(port_) + "; its output:\n" +
           read_text(log_path());
  }

  PacsPeer peer() const {
    PacsPeer p;
    p.called_ae = kAeTitle;
    p.host = "127.0.0.1";
    p.port = port_;
    p.calling_ae = "SOIQ";
    p.timeout_seconds = 10;
    return p;
  }
  int port() const { return port_; }

  // Loads files or folders (recursively) with DCMTK's storescu; "" or its output on failure.
  // `extra_args` go to storescu, e.g. {"-xt"}: propose JPEG-LS lossless (send as stored).
  std::string load(const std::vector<std::string>& paths, const std::vector<std::string>& extra_args = {}) {
    const std::string binary = find_on_path("storescu");
    if (binary.empty()) return "storescu is not on PATH";
    std::vector<std::string> argv = {binary, "-aet", "SOIQLOAD", "-aec",      kAeTitle,
                                     "-to",  "10",   "-ta",      "10",        "-td",
                                     "10",   "+sd",  "+r",       "127.0.0.1", std::to_string(port_)};
    argv.insert(argv.end() - 2, extra_args.begin(), extra_args.end());  // options before host and port
    argv.insert(argv.end(), paths.begin(), paths.end());
    const std::filesystem::path log = dir_.path() / "storescu.log";
    const int rc = run_tool(argv, log);
    return rc == 0 ? "" : "storescu exited with " + std::to_string(rc) + ":\n" + read_text(log);
  }

  // SIGKILL to dcmqrscp and its association children at once: the association breaks mid-flight.
  void kill_now() {
    if (pid_ > 0) ::kill(-pid_, SIGKILL);
  }

  void stop() { stop_process_group(pid_, std::chrono::seconds(2)); }

  std::string output() const { return read_text(log_path()); }

 private:
  std::filesystem::path log_path() const { return dir_.path() / "dcmqrscp.log"; }

  TempDir dir_;
  pid_t pid_ = -1;
  int port_ = 0;
};

}  // namespace soiq::dicom::testing
