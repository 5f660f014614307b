// soiq-admin: what an operator does to soiqd's stores, beside soiqd (they may run while it serves):
//   soiq-admin migrate --from LOCATION --to LOCATION   copy every record into an empty store and
//                                                      verify it (SQLite <-> PostgreSQL)
//   soiq-admin backup --db FILE --to FILE              a consistent copy of a live SQLite store
//   soiq-admin verify --db LOCATION                    scrub every stored blob and cached value
//                                                      (server/app/store_verify.h), reading only
// LOCATION as soiqd's --db takes it (server/app/store_location.h). Exit codes: 0 done (verify: the
// store is sound), 2 a bad command line, 1 anything else (verify: something is damaged, with the
// report); errors are one line on stderr.
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>

#include "server/app/store_admin.h"
#include "server/app/store_verify.h"

namespace {

constexpr char kUsage[] =
    "usage: soiq-admin migrate --from LOCATION --to LOCATION\n"
    "       soiq-admin backup --db FILE --to FILE\n"
    "       soiq-admin verify --db LOCATION\n\n"
    "migrate  copies every record (patients, studies, series and images, structures and surfaces,\n"
    "         stored features, the precompute queue, the feature cache) into an empty store, keys\n"
    "         and ids kept, in one transaction, then compares the two stores table by table (rows\n"
    "         and a sha256 of their bytes). LOCATION: a SQLite file (PATH or sqlite:PATH) or\n"
    "         postgresql://USER@HOST:PORT/DATABASE (the password from PGPASSWORD or ~/.pgpass).\n"
    "backup   copies a SQLite store that soiqd may be using (SQLite's online backup) into FILE.\n"
    "         For PostgreSQL use pg_dump --format=custom (docs/SCALE_OUT.md).\n"
    "verify   reads every stored surface blob (its checksum, that it decodes, that its mesh is the\n"
    "         sha256 it is stored under), every image blob (its checksum, that it decodes, its\n"
    "         sha256) and every cached feature value (its checksum), and reports how many of each\n"
    "         it checked, each damaged one by kind and id with what is wrong and who uses it, and\n"
    "         the blobs an older soiqd stored without a checksum. It only reads, without migrating\n"
    "         the store, so it may run while soiqd serves it.\n\n"
    "Exit codes: 0 done (verify: the store is sound), 2 a bad command line, 1 any other failure\n"
    "(verify: something is damaged; the report says what).\n";

int usage_error(const std::string& why) {
  std::fprintf(stderr, "soiq-admin: %s (soiq-admin --help shows the usage)\n", why.c_str());
  return 2;
}

int fail(const soiq::Status& s) {
  std::fprintf(stderr, "soiq-admin: %s\n", s.to_string().c_str());
  return s.code() == soiq::StatusCode::kInvalidArgument ? 2 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc >= 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (argc < 2) return usage_error("give a command: migrate, backup or verify");
  const std::string command = argv[1];
  std::map<std::string, std::string> flags;
  for (int i = 2; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag.rfind("--", 0) != 0 || i + 1 >= argc) return usage_error("'" + flag + "' needs a value");
    flags[flag] = argv[++i];
  }
  auto location = [&](const char* flag) { return soiq::server::parse_store_location(flags[flag]); };

  if (command == "migrate") {
    for (const auto& [flag, value] : flags)
      if (flag != "--from" && flag != "--to") return usage_error("migrate takes --from and --to, not " + flag);
    if (!flags.count("--from") || !flags.count("--to")) return usage_error("migrate needs --from and --to");
    auto from = location("--from");
    if (!from.ok()) return fail(from.status());
    auto to = location("--to");
    if (!to.ok()) return fail(to.status());
    // Progress on a terminal only: a log gets the summary below.
    const bool terminal = isatty(2) != 0;
    auto digests = soiq::server::migrate_store(*from, *to, [&](const std::string& table, int64_t rows) {
      if (terminal) std::fprintf(stderr, "\r%-18s %lld rows   ", table.c_str(), static_cast<long long>(rows));
    });
    if (terminal) std::fputc('\n', stderr);
    if (!digests.ok()) return fail(digests.status());
    for (const soiq::db::TableDigest& d : *digests)
      std::printf("%-18s %10lld rows  sha256 %s  same in both\n", d.table.c_str(), static_cast<long long>(d.rows),
                  d.sha256.c_str());
    return 0;
  }
  if (command == "backup") {
    for (const auto& [flag, value] : flags)
      if (flag != "--db" && flag != "--to") return usage_error("backup takes --db and --to, not " + flag);
    if (!flags.count("--db") || !flags.count("--to")) return usage_error("backup needs --db and --to");
    auto from = location("--db");
    if (!from.ok()) return fail(from.status());
    const soiq::Status s = soiq::server::backup_store(*from, flags["--to"]);
    if (!s.ok()) return fail(s);
    std::printf("backed up %s to %s\n", from->target.c_str(), flags["--to"].c_str());
    return 0;
  }
  if (command == "verify") {
    for (const auto& [flag, value] : flags)
      if (flag != "--db") return usage_error("verify takes --db, not " + flag);
    if (!flags.count("--db")) return usage_error("verify needs --db");
    auto at = location("--db");
    if (!at.ok()) return fail(at.status());
    const bool terminal = isatty(2) != 0;
    auto report = soiq::server::verify_store(*at, [&](const std::string& kind, int64_t done) {
      if (terminal && done % 100 == 0)
        std::fprintf(stderr, "\r%-14s %lld checked   ", kind.c_str(), static_cast<long long>(done));
    });
    if (terminal) std::fputc('\n', stderr);
    if (!report.ok()) return fail(report.status());
    for (const std::string& line : soiq::server::format_verify_report(*report)) std::printf("%s\n", line.c_str());
    return report->sound() ? 0 : 1;
  }
  return usage_error("unknown command '" + command + "'; the commands are migrate, backup and verify");
}
