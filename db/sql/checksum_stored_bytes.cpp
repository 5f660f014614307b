#include "db/sql/checksum_stored_bytes.h"

#include <string>
#include <vector>

#include "db/cached_value.h"
#include "db/surface_blob.h"

namespace soiq::db {
namespace {

Status checksum_surfaces(SqlSession& c) {
  std::vector<std::string> shas;
  {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare("SELECT sha256 FROM surfaces ORDER BY sha256"));
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      shas.push_back(q.text(0));
    }
  }
  for (const std::string& sha : shas) {
    std::string blob;
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement read, c.prepare("SELECT blob FROM surfaces WHERE sha256 = ?1"));
      read.bind(1, sha);
      SOIQ_ASSIGN_OR_RETURN(const bool found, read.step());
      if (!found) continue;
      if (surface_blob_version(read.blob_view(0)) == 3) continue;
      blob = read.blob(0);
    }
    Result<TriangleMesh> mesh = decode_surface(blob);
    if (!mesh.ok() || surface_sha256(*mesh) != sha) continue;  // damaged: left for soiqd to refuse
    SOIQ_ASSIGN_OR_RETURN(const EncodedSurface encoded, encode_surface(*mesh));
    SOIQ_ASSIGN_OR_RETURN(SqlStatement write, c.prepare("UPDATE surfaces SET blob = ?2 WHERE sha256 = ?1"));
    write.bind(1, sha);
    write.bind_blob(2, encoded.blob);
    SOIQ_RETURN_IF_ERROR(write.run());
  }
  return ok_status();
}

// The values without a checksum (a length that is whole float64s), a page at a time in key order
// from the last one seen, so neither engine holds the whole cache in memory.
constexpr char kUncheckedValuesSql[] = R"sql(
  SELECT key, entry, value FROM feature_cache
  WHERE (key > ?1 OR (key = ?1 AND entry > ?2)) AND length(value) % 8 = 0
  ORDER BY key, entry
  LIMIT 1000)sql";

Status checksum_cached_values(SqlSession& c) {
  CachedFeature last;
  while (true) {
    std::vector<CachedFeature> page;
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kUncheckedValuesSql));
      q.bind(1, last.key);
      q.bind(2, last.entry);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        CachedFeature& f = page.emplace_back(CachedFeature{q.text(0), q.text(1), {}});
        SOIQ_RETURN_IF_ERROR(set_cached_value(f, q.blob_view(2)));
      }
    }
    if (page.empty()) return ok_status();
    for (const CachedFeature& f : page) {
      const std::string value = cached_value_bytes(f);
      SOIQ_ASSIGN_OR_RETURN(SqlStatement write,
                            c.prepare("UPDATE feature_cache SET value = ?3 WHERE key = ?1 AND entry = ?2"));
      write.bind(1, f.key);
      write.bind(2, f.entry);
      write.bind_blob(3, value);
      SOIQ_RETURN_IF_ERROR(write.run());
    }
    last = std::move(page.back());
  }
}

}  // namespace

Status checksum_stored_bytes(SqlSession& c) {
  SOIQ_RETURN_IF_ERROR(checksum_surfaces(c));
  return checksum_cached_values(c);
}

}  // namespace soiq::db
