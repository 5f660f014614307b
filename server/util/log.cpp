#include "server/util/log.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>

namespace soiq::server {
namespace {

// A value as logfmt writes it: quoted when it has a space, a quote or '=', and never with a control
// character (a client's path with %0A in it must not start a log line of its own).
std::string quoted(const std::string& v) {
  const auto control = [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; };
  if (!v.empty() && v.find_first_of(" \"=") == std::string::npos && std::none_of(v.begin(), v.end(), control)) return v;
  std::string q = "\"";
  for (char c : v) {
    if (c == '"' || c == '\\') q += '\\';
    q += control(c) ? ' ' : c;
  }
  return q + "\"";
}

}  // namespace

void log_event(const char* level, const std::vector<std::pair<std::string, std::string>>& fields) {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const int ms = int(std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char ts[96];
  std::snprintf(ts, sizeof ts, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, ms);
  std::string line = std::string("ts=") + ts + " level=" + level;
  for (const auto& [k, v] : fields) line += " " + k + "=" + quoted(v);
  line += "\n";
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  std::fputs(line.c_str(), stderr);
}

}  // namespace soiq::server
