#pragma once
// A cached feature's value as stored by every backend: its float64s, little-endian, back to back
// (db/store.h, CachedFeature). One encoding, so a value reads back bit for bit on any backend.
//
// cached_value_bytes  the bytes to store (a view of `value`'s own memory).
// set_cached_value    `f.value` from stored bytes; DATA_LOSS naming the key and entry when they are
//                     not a whole number of float64s.

#include <string_view>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"

namespace soiq::db {

std::string_view cached_value_bytes(const std::vector<double>& value);
Status set_cached_value(CachedFeature& f, std::string_view bytes);

}  // namespace soiq::db
