#pragma once
// Test support: the plumbing of tests that run real servers as child processes (a PACS, a
// database): find a tool, pick a free loopback port, run a tool to completion, stop a server's
// process group. Header-only, POSIX.

#include <arpa/inet.h>
#include <fcntl.h>
#include <grp.h>
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
#include <utility>
#include <vector>

namespace soiq::testing {

// The absolute path of `name` on PATH, or "" when it is not there.
inline std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

// A loopback port nobody listens on right now (bind to port 0, read it, close).
inline int free_loopback_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return 0;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof addr;
  int port = 0;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0)
    port = ntohs(addr.sin_port);
  ::close(fd);
  return port;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// How a child runs: as whom (0: as the caller), and what its environment gains.
struct ChildOptions {
  uid_t uid = 0;
  gid_t gid = 0;
  std::vector<std::pair<std::string, std::string>> env;
};

// Starts argv[0] with stdout+stderr into `log`, in its own process group (so a test's kill of a
// server's group never reaches it), as options.uid when it is not 0 (the log is handed to it too).
// Returns its pid, or -1 when it cannot fork.
inline pid_t spawn_in_own_group(const std::vector<std::string>& argv, const std::filesystem::path& log,
                                const ChildOptions& options = {}) {
  const pid_t pid = ::fork();
  if (pid != 0) return pid;
  ::setpgid(0, 0);
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    if (options.uid != 0 && ::fchown(fd, options.uid, options.gid) != 0) ::_exit(126);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
  }
  if (options.uid != 0 && (::setgroups(0, nullptr) != 0 || ::setgid(options.gid) != 0 || ::setuid(options.uid) != 0))
    ::_exit(126);
  for (const auto& [name, value] : options.env) ::setenv(name.c_str(), value.c_str(), 1);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  ::execv(args[0], args.data());
  ::_exit(127);
}

// spawn_in_own_group, then waits: the exit status, or -1 if it could not run.
inline int run_to_exit(const std::vector<std::string>& argv, const std::filesystem::path& log,
                       const ChildOptions& options = {}) {
  const pid_t pid = spawn_in_own_group(argv, log, options);
  if (pid < 0) return -1;
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A DCMTK tool run to completion, with TCP_NODELAY=1 in its environment (DCMTK reads it: Nagle's
// algorithm off).
inline int run_tool(const std::vector<std::string>& argv, const std::filesystem::path& log) {
  return run_to_exit(argv, log, ChildOptions{0, 0, {{"TCP_NODELAY", "1"}}});
}

// Stops a server started in its own process group (`pid` its leader; -1 afterwards): SIGTERM, up to
// `grace` for it to exit, then SIGKILL; and SIGKILL to the group after, for children that outlived
// their parent (dcmqrscp's association processes).
inline void stop_process_group(pid_t& pid, std::chrono::milliseconds grace) {
  if (pid <= 0) return;
  ::kill(-pid, SIGTERM);
  int status = 0;
  bool reaped = false;
  for (auto waited = std::chrono::milliseconds(0); waited < grace && !reaped; waited += std::chrono::milliseconds(20)) {
    reaped = ::waitpid(pid, &status, WNOHANG) == pid;
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!reaped) {
    ::kill(-pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  ::kill(-pid, SIGKILL);
  pid = -1;
}

}  // namespace soiq::testing
