#pragma once
// A cached feature's value as stored by every backend (db/store.h, CachedFeature): its float64s,
// little-endian, back to back, then a CRC-32 (crc32.h) over the entry's key, its name and those
// bytes. One encoding, so a value reads back bit for bit on any backend; and checked, so a flipped
// bit in a stored value, or in the key or name it is stored under (a value answering for another
// grid or feature), is refused instead of read as another number.
//
// A value stored before the checksum (schema versions before SQLite's 9 and PostgreSQL's 5) is
// its float64s alone: its length is a multiple of 8, where a checked one's is 4 more, so the two
// cannot be confused, and it still reads. The migrations give every stored value its checksum
// (db/sql/checksum_stored_bytes.h).
//
// cached_value_bytes         the bytes to store for `f`.
// set_cached_value           `f.value` from stored bytes, given `f.key` and `f.entry`; DATA_LOSS
//                            naming the key and entry when the checksum differs ("checksum
//                            mismatch") or the length is neither form's.
// cached_value_damage        what is wrong with stored bytes as `f`'s value ("" when nothing):
//                            "checksum mismatch (…)" or a length of neither form.
// cached_value_has_checksum  whether stored bytes are of the checked form (by their length).
// Cost O(bytes). Thread-safe.

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "db/store.h"

namespace soiq::db {

std::string cached_value_bytes(const CachedFeature& f);
Status set_cached_value(CachedFeature& f, std::string_view bytes);
std::string cached_value_damage(const CachedFeature& f, std::string_view bytes);
bool cached_value_has_checksum(std::string_view bytes);

}  // namespace soiq::db
