#include "tests/support/soiqd_process.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

#include "tests/support/postgres_process.h"

namespace soiq::testing {
namespace {

int wait_exit(pid_t pid, std::chrono::seconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    int status = 0;
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return -1;
}

}  // namespace

bool soiqd_on_postgres() {
  const char* store = std::getenv("SOIQ_TEST_STORE");
  return store != nullptr && std::string(store) == "postgresql";
}

std::string soiqd_store(const std::string& db_path, std::string& why) {
  why.clear();
  if (!soiqd_on_postgres()) return db_path;
  PostgresProcess& server = shared_postgres(why);
  if (!why.empty()) return "";
  // A name from the path and the process: the same path, the same database (a restarted soiqd
  // finds its store), and no other test process's.
  char name[48];
  std::snprintf(name, sizeof name, "soiq_%d_%016zx", static_cast<int>(getpid()), std::hash<std::string>{}(db_path));
  why = ensure_postgres_database(server, name);
  if (!why.empty()) return "";
  return "postgresql://" + std::string(PostgresProcess::kUser) + "@127.0.0.1:" + std::to_string(server.port()) + "/" +
         name + "?connect_timeout=5";
}

SoiqdProcess::SoiqdProcess(const std::string& db_path, const std::vector<std::string>& extra_args,
                           const std::string& binary) {
  const std::string dir = std::filesystem::path(db_path).parent_path().string();
  static int counter = 0;
  const std::string tag = std::to_string(getpid()) + "-" + std::to_string(++counter);
  log_path_ = dir + "/soiqd-" + tag + ".log";
  port_path_ = dir + "/soiqd-" + tag + ".port";
  std::string why;
  const std::string store = soiqd_store(db_path, why);
  if (store.empty()) {
    std::ofstream(log_path_) << "soiqd not started: PostgreSQL: " << why << "\n";
    return;
  }
  std::vector<std::string> args = {
      binary.empty() ? SOIQD_BINARY : binary, "--db", store, "--listen", "127.0.0.1:0", "--port-file", port_path_};
  // Precompute off unless asked: a test that counts what a query computed, or a process's peak
  // memory, must not race soiqd's background worker. Precompute's own tests turn it on.
  const bool precompute_given = std::any_of(extra_args.begin(), extra_args.end(),
                                            [](const std::string& a) { return a.rfind("--precompute", 0) == 0; });
  if (!precompute_given) args.insert(args.end(), {"--precompute", "off"});
  // DICOMweb's port too, when asked for (soiqd writes it before the gRPC port file).
  const bool http = std::any_of(extra_args.begin(), extra_args.end(),
                                [](const std::string& a) { return a == "--http" || a.rfind("--http=", 0) == 0; });
  const std::string http_port_path = dir + "/soiqd-" + tag + ".http-port";
  if (http) args.insert(args.end(), {"--http-port-file", http_port_path});
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  pid_ = fork();
  if (pid_ == 0) {
    const int fd = open(log_path_.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    dup2(fd, 2);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < until) {
    std::ifstream in(port_path_);
    if (in >> port_ && port_ > 0) {
      address_ = "127.0.0.1:" + std::to_string(port_);
      if (http) std::ifstream(http_port_path) >> http_port_;
      return;
    }
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {  // exited early: a startup error, in the log
      pid_ = -1;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

SoiqdProcess::~SoiqdProcess() {
  if (pid_ > 0 && terminate() < 0) kill_hard();
}

int SoiqdProcess::terminate() {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGTERM);
  const int status = wait_exit(pid_, std::chrono::seconds(30));
  if (status >= 0) pid_ = -1;
  return status;
}

void SoiqdProcess::kill_hard() {
  if (pid_ <= 0) return;
  kill(pid_, SIGKILL);
  wait_exit(pid_, std::chrono::seconds(15));
  pid_ = -1;
}

std::string SoiqdProcess::log() const {
  std::ifstream in(log_path_);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace soiq::testing

namespace soiq::testing {

long long SoiqdProcess::peak_rss_bytes() const {
  std::ifstream status("/proc/" + std::to_string(pid_) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6)) * 1024;  // "VmHWM:  1234 kB"
  }
  return -1;
}

}  // namespace soiq::testing
