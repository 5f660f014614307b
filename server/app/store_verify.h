#pragma once
// soiq-admin verify: a scrub of every stored byte of a store (a SQLite file or a PostgreSQL
// database, store_location.h), reading only, so it may run beside a running soiqd:
//   surfaces       each blob's checksum (version 3), that it decodes, and that its mesh's sha256
//                  is the key it is stored under (which checks a blob without a checksum too);
//   images         that each blob decodes on its series' grid (checked by its Adler-32: version
//                  2's own, version 1's zlib stream's), and that the image's sha256 is its key;
//   cached values  each value's checksum (db/cached_value.h);
//   instance files that each kept DICOM file's sha256 is its key;
//   instances      each kept instance's record by its checksum (db::instance_row_crc32).
// The store is opened read only: not migrated (a store of an older schema is scrubbed as it is),
// and nothing is written.
//
// Output   per kind, how many items were checked, how many are damaged and how many carry no
//          checksum of their own (stored by an older soiqd; a surface blob of those is still
//          checked against its sha256); each damaged item, and each blob without a checksum, by
//          kind and id with what is wrong, naming the structures or series that use it.
//          format_verify_report gives it as the lines soiq-admin prints.
// Errors   the store's, opening or reading it. Damage is not an error: it is the report.
// Cost     every blob read and decoded once, one at a time (memory: the largest blob and its
//          decoded form); the feature cache a page at a time.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "server/app/store_location.h"

namespace soiq::server {

struct VerifyCounts {
  int64_t checked = 0;
  int64_t damaged = 0;
  int64_t without_checksum = 0;
};

struct VerifyFinding {
  std::string kind;     // "surface", "image", "cached value", "instance file" or "instance"
  std::string id;       // a blob's sha256; a cached value's "'<entry>' under key '<key>'"
  std::string users;    // "structures 4, 7", "series 1.2.3", "surface <sha256>, structures 4"
  std::string problem;  // what is wrong
};

struct VerifyReport {
  VerifyCounts surfaces, images, cached_values, instance_files, instances;
  std::vector<VerifyFinding> damaged;
  std::vector<VerifyFinding> without_checksum;  // blobs only: cached values are counted
  bool sound() const { return damaged.empty(); }
};

// `progress(kind, items done)` as it goes (kind "surfaces", "images", "cached values", "instance
// files", "instances").
Result<VerifyReport> verify_store(const StoreLocation& at,
                                  const std::function<void(const std::string&, int64_t)>& progress);

// The counts, one line per kind, then one line per damaged item and per blob without a checksum,
// then a last line that says whether the store is sound and, if not, what to do.
std::vector<std::string> format_verify_report(const VerifyReport& r);

}  // namespace soiq::server
