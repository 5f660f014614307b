#include "bench/soiqd_child.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace soiq::bench {
namespace {

int wait_exit(pid_t pid, std::chrono::seconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return -1;
}

}  // namespace

SoiqdChild::SoiqdChild(const std::string& binary, const std::string& db_path,
                       const std::vector<std::string>& extra_args) {
  const std::string base = db_path + "." + std::to_string(getpid());
  log_path_ = base + ".soiqd.log";
  port_path_ = base + ".port";
  std::filesystem::remove(port_path_);
  std::vector<std::string> args = {binary, "--db", db_path, "--listen", "127.0.0.1:0", "--port-file", port_path_};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  pid_ = fork();
  if (pid_ == 0) {
    const int fd = open(log_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < until) {
    int port = 0;
    std::ifstream in(port_path_);
    if (in >> port && port > 0) {
      address_ = "127.0.0.1:" + std::to_string(port);
      return;
    }
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {  // exited early: a start-up error, in the log
      pid_ = -1;
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

SoiqdChild::~SoiqdChild() {
  stop();
  std::error_code ec;
  std::filesystem::remove(port_path_, ec);
  std::filesystem::remove(log_path_, ec);
}

int SoiqdChild::stop() {
  if (pid_ <= 0) return -1;
  kill(pid_, SIGTERM);
  int status = wait_exit(pid_, std::chrono::seconds(30));
  if (status < 0) {
    kill(pid_, SIGKILL);
    status = wait_exit(pid_, std::chrono::seconds(10));
  }
  pid_ = -1;
  return status;
}

std::string SoiqdChild::log() const {
  std::ifstream in(log_path_);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace soiq::bench
