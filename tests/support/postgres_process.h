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
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <mutex>
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
      if (launch()) return "";
    }
    return "postgres did not start: " + read_text(root / "postgres.log");
  }

  // Starts the server again after stop(), on the same data and port (a server that went down and
  // came back, as its clients see it). "" when it answers, else why not.
  std::string restart() {
    if (pid_ > 0 || port_ == 0 || attached_) return "restart: not a stopped server of this process";
    return launch() ? "" : "postgres did not restart: " + read_text(dir_.path() / "pg" / "postgres.log");
  }
  // Uses the server tests/support/shared_postgres.sh started in `dir` (its port in dir/port) instead
  // of one of its own; stop() then leaves it running. "" when it answers, else why not.
  std::string attach(const std::filesystem::path& dir) {
    const std::string port = read_text(dir / "port");
    try {
      port_ = std::stoi(port);
    } catch (const std::exception&) {
      return "no shared PostgreSQL in " + dir.string() +
             " (the fixture test postgres.start failed?): " + read_text(dir / "start.log");
    }
    attached_ = true;
    if (PQping(conninfo("postgres").c_str()) != PQPING_OK)
      return "the shared PostgreSQL on port " + port + " does not answer: " + read_text(dir / "postgres.log");
    return "";
  }
  bool attached() const { return attached_; }

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
    pid_ = -1;
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

  // Starts `postgres` on the data folder start() made and port_; true once it answers (bounded).
  bool launch() {
    const std::filesystem::path root = dir_.path() / "pg";
    pid_ = spawn_in_own_group({(server_bin_dir() / "postgres").string(), "-D", (root / "data").string(), "-p",
                               std::to_string(port_), "-k", root.string(), "-c", "listen_addresses=127.0.0.1", "-c",
                               "fsync=off", "-c", "synchronous_commit=off", "-c", "full_page_writes=off"},
                              root / "postgres.log", as_server_user());
    if (pid_ < 0) return false;
    for (int i = 0; i < 400; ++i) {  // up to 20 s
      if (PQping(conninfo("postgres").c_str()) == PQPING_OK) return true;
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) break;  // it exited: the port, most likely
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    stop();
    return false;
  }

  TempDir dir_;
  uid_t uid_ = 0;
  gid_t gid_ = 0;
  int port_ = 0;
  pid_t pid_ = -1;
  bool attached_ = false;
};

// A database name no other test process uses: `prefix`, this process's id and a counter. Test
// processes share one server under ctest (shared_postgres), so a name must not be per process only.
inline std::string unique_postgres_database_name(const std::string& prefix) {
  static std::atomic<int> next{0};
  return prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(next++);
}

namespace detail {
// The databases this process created on a server it shares with others, dropped at exit.
inline std::vector<std::string>& databases_to_drop() {
  static auto* names = new std::vector<std::string>;
  return *names;
}
inline std::mutex& databases_to_drop_mutex() {
  static auto* m = new std::mutex;
  return *m;
}
inline void drop_databases(const PostgresProcess& server) {
  std::lock_guard<std::mutex> lock(databases_to_drop_mutex());
  if (databases_to_drop().empty()) return;
  PGconn* c = PQconnectdb(server.conninfo("postgres").c_str());
  if (PQstatus(c) == CONNECTION_OK) {
    for (const std::string& name : databases_to_drop()) {
      // FORCE: a soiqd the test left behind must not keep its database, and the server, busy.
      PQclear(PQexec(c, ("DROP DATABASE IF EXISTS " + name + " WITH (FORCE)").c_str()));
    }
  }
  PQfinish(c);
  databases_to_drop().clear();
}
}  // namespace detail

// The test process's PostgreSQL server. Under ctest it is the one server every test shares,
// started once by the fixture test postgres.start (tests/support/shared_postgres.sh) in the folder
// SOIQ_TEST_POSTGRES names in the temporary directory: an initdb and a start per test process cost
// more than the tests of the PostgreSQL store themselves. Run alone (a test binary started by
// hand), the process starts a server of its own when first asked and stops it at exit. Either way
// each test uses databases of its own (unique_postgres_database_name). `why` is "" when it runs,
// else why it does not. An own server is deleted at exit, which removes its data folder too (kept,
// the folders of one `make test` filled ~9 GB); on the shared server, the databases this process
// made are dropped at exit instead.
inline PostgresProcess& shared_postgres(std::string& why) {
  static PostgresProcess* server = new PostgresProcess;
  static const std::string started = [] {
    const char* shared = std::getenv("SOIQ_TEST_POSTGRES");
    return shared != nullptr && *shared != '\0' ? server->attach(std::filesystem::temp_directory_path() / shared)
                                                : server->start();
  }();
  static const int stop_at_exit = std::atexit([] {
    if (server->attached()) detail::drop_databases(*server);
    server->stop();
    delete server;
  });
  (void)stop_at_exit;
  why = started;
  return *server;
}

// Creates the database `name` (letters, digits and '_') on `server` unless it exists; "" or why
// not. On a shared server it is dropped when this process exits.
inline std::string ensure_postgres_database(const PostgresProcess& server, const std::string& name) {
  PGconn* c = PQconnectdb(server.conninfo("postgres").c_str());
  std::string why;
  if (PQstatus(c) != CONNECTION_OK) {
    why = PQerrorMessage(c);
  } else {
    PGresult* r = PQexec(c, ("CREATE DATABASE " + name).c_str());
    const char* state = PQresultErrorField(r, PG_DIAG_SQLSTATE);
    // 42P04 duplicate_database: made before (a soiqd restarted on the same store).
    const bool duplicate = state != nullptr && std::string(state) == "42P04";
    if (PQresultStatus(r) != PGRES_COMMAND_OK && !duplicate) why = PQresultErrorMessage(r);
    if (PQresultStatus(r) == PGRES_COMMAND_OK && server.attached()) {
      std::lock_guard<std::mutex> lock(detail::databases_to_drop_mutex());
      detail::databases_to_drop().push_back(name);
    }
    PQclear(r);
  }
  PQfinish(c);
  return why;
}

}  // namespace soiq::testing
