#pragma once
// Test support: a real PostgreSQL server (Debian's postgresql-15) in a temporary folder, on a free
// loopback port, for the tests of the PostgreSQL store. Header-only; link libpq.
//
// PostgresProcess::start runs initdb (trust authentication for the user kUser, no fsync: a test
// database need not survive a crash), starts `postgres` in its own process group listening on
// 127.0.0.1 only, with its Unix socket in the folder too, and pings it until it accepts
// connections (bounded). PostgreSQL refuses to run as root: as root, both run as the `postgres`
// system user the Debian package creates, and the folder is handed to it. The destructor asks for a
// fast shutdown (SIGINT), then kills the group.

#include <libpq-fe.h>
#include <pwd.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/child_process.h"
#include "tests/support/temp_dir.h"

namespace soiq::testing {

class PostgresProcess {
 public:
  static constexpr const char* kUser = "soiq";

  PostgresProcess() = default;
  PostgresProcess(const PostgresProcess&) = delete;
  PostgresProcess& operator=(const PostgresProcess&) = delete;
  ~PostgresProcess() { stop(); }

  // "" when running, else why not ("not installed: ..." when the server's binaries are missing).
  std::string start() {
    const std::filesystem::path bin = server_bin_dir();
    if (bin.empty()) return "not installed: no /usr/lib/postgresql/*/bin/postgres (Debian package postgresql-15)";
    const std::filesystem::path root = dir_.path() / "pg";
    std::filesystem::create_directories(root);
    if (::geteuid() == 0) {
      const passwd* pw = ::getpwnam("postgres");
      if (pw == nullptr) return "running as root, and there is no 'postgres' user to run PostgreSQL as";
      uid_ = pw->pw_uid, gid_ = pw->pw_gid;
      // The server's user must reach its folder: traverse the test's folder, own its own.
      std::filesystem::permissions(dir_.path(), std::filesystem::perms::others_exec,
                                   std::filesystem::perm_options::add);
      if (::chown(root.c_str(), uid_, gid_) != 0) return "cannot hand " + root.string() + " to the postgres user";
    }
    const std::filesystem::path data = root / "data";
    const int init = run_to_exit({(bin / "initdb").string(), "-D", data.string(), "-U", kUser, "-A", "trust", "-E",
                                  "UTF8", "--locale=C", "--no-sync"},
                                 root / "initdb.log", as_server_user());
    if (init != 0) return "initdb failed (" + std::to_string(init) + "): " + read_text(root / "initdb.log");
    // The port can be taken between our probe and the server's bind: try a few.
    for (int attempt = 0; attempt < 3; ++attempt) {
      port_ = free_loopback_port();
      pid_ = spawn_in_own_group({(bin / "postgres").string(), "-D", data.string(), "-p", std::to_string(port_), "-k",
                                 root.string(), "-c", "listen_addresses=127.0.0.1", "-c", "fsync=off", "-c",
                                 "synchronous_commit=off", "-c", "full_page_writes=off"},
                                root / "postgres.log", as_server_user());
      if (pid_ < 0) return "cannot start postgres";
      for (int i = 0; i < 400; ++i) {  // up to 20 s
        if (PQping(conninfo("postgres").c_str()) == PQPING_OK) return "";
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) break;  // it exited: the port, most likely
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      stop();
    }
    return "postgres did not start: " + read_text(root / "postgres.log");
  }

  int port() const { return port_; }
  // A libpq connection string for `database` on this server, as kUser over TCP.
  std::string conninfo(const std::string& database) const {
    return "host=127.0.0.1 port=" + std::to_string(port_) + " user=" + kUser + " dbname=" + database +
           " connect_timeout=5";
  }

  void stop() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGINT);  // fast shutdown: ends the sessions, writes a shutdown checkpoint
    int status = 0;
    for (int i = 0; i < 200 && ::waitpid(pid_, &status, WNOHANG) != pid_; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    stop_process_group(pid_, std::chrono::milliseconds(0));  // whatever is left of the group
  }

 private:
  // The newest installed server's bin folder, or "" when none is.
  static std::filesystem::path server_bin_dir() {
    std::vector<std::filesystem::path> found;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator("/usr/lib/postgresql", ec)) {
      if (std::filesystem::exists(e.path() / "bin" / "postgres")) found.push_back(e.path() / "bin");
    }
    std::sort(found.begin(), found.end());
    return found.empty() ? std::filesystem::path() : found.back();
  }

  ChildOptions as_server_user() const { return ChildOptions{uid_, gid_, {}}; }

  TempDir dir_;
  uid_t uid_ = 0;
  gid_t gid_ = 0;
  int port_ = 0;
  pid_t pid_ = -1;
};

// The test process's one PostgreSQL server, started when first asked for and stopped at exit, so
// the tests of a process share one server (each with a database of its own). `why` is "" when it
// runs, else why it does not. Deleted at exit, which removes its data folder too (ctest runs each
// test in a process of its own: kept, the folders of one `make test` filled ~9 GB).
inline PostgresProcess& shared_postgres(std::string& why) {
  static PostgresProcess* server = new PostgresProcess;
  static const std::string started = server->start();
  static const int stop_at_exit = std::atexit([] {
    server->stop();
    delete server;
  });
  (void)stop_at_exit;
  why = started;
  return *server;
}

// Creates the database `name` (letters, digits and '_') on `server` unless it exists; "" or why
// not.
inline std::string ensure_postgres_database(const PostgresProcess& server, const std::string& name) {
  PGconn* c = PQconnectdb(server.conninfo("postgres").c_str());
  std::string why;
  if (PQstatus(c) != CONNECTION_OK) {
    why = PQerrorMessage(c);
  } else {
    PGresult* r = PQexec(c, ("CREATE DATABASE " + name).c_str());
    const char* state = PQresultErrorField(r, PG_DIAG_SQLSTATE);
    // 42P04 duplicate_database: made before (a soiqd restarted on the same store).
    if (PQresultStatus(r) != PGRES_COMMAND_OK && !(state != nullptr && std::string(state) == "42P04"))
      why = PQresultErrorMessage(r);
    PQclear(r);
  }
  PQfinish(c);
  return why;
}

}  // namespace soiq::testing
