#pragma once
// A consistent copy of a live SQLite store file (soiq-admin backup), by SQLite's online backup API:
// soiqd may go on reading and writing meanwhile; the copy is one committed snapshot, written to a
// temporary file beside `to_path` and renamed over it only when whole.
//
// Errors: FAILED_PRECONDITION naming the file when the source is not a SQLite database or the
// target cannot be written; UNAVAILABLE when the source stayed locked past the busy timeout.

#include <string>

#include "core/base/status.h"

namespace soiq::db {

Status sqlite_backup(const std::string& from_path, const std::string& to_path);

}  // namespace soiq::db
