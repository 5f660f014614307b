#pragma once
// soiqd's structured log: one logfmt line per event on stderr
//   ts=2026-11-22T03:04:05.123Z level=info event=rpc method=Query code=OK ms=812.4
// Values are quoted when they contain spaces. Patient names are never logged (soiq does not even
// store them); ids and codes are.

#include <string>
#include <utility>
#include <vector>

namespace soiq::server {

void log_event(const char* level, const std::vector<std::pair<std::string, std::string>>& fields);

}  // namespace soiq::server
