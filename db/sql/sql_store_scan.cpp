// SqlStore::scan_stored: every stored surface blob, image blob or cached value handed out as it is
// stored, for soiq-admin verify to check (server/app/store_verify.h). Each read is a short read
// transaction of its own: one blob at a time (blobs are large), cached values a page at a time,
// each continuing after the last key seen, so the scan never holds a snapshot for long.
#include <string>
#include <vector>

#include "db/sql/sql_store.h"

namespace soiq::db {
namespace {

constexpr char kNextSurfaceSql[] = R"sql(
  SELECT sha256, blob FROM surfaces WHERE sha256 > ?1 ORDER BY sha256 LIMIT 1)sql";

constexpr char kSurfaceStructuresSql[] = R"sql(
  SELECT id FROM structures WHERE surface_sha256 = ?1 ORDER BY id)sql";

// The image with the first series that holds it, whose grid the blob is decoded on (the sha256
// covers the grid, so every series that holds it has the same).
constexpr char kNextImageSql[] = R"sql(
  SELECT b.sha256, b.blob, se.series_uid,
         se.origin_x, se.origin_y, se.origin_z, se.spacing_x, se.spacing_y, se.spacing_z,
         se.dim_x, se.dim_y, se.dim_z, se.d00, se.d01, se.d02, se.d10, se.d11, se.d12, se.d20, se.d21, se.d22
  FROM image_blobs b
  LEFT JOIN series se ON se.pk = (SELECT min(pk) FROM series WHERE image_sha256 = b.sha256)
  WHERE b.sha256 > ?1 ORDER BY b.sha256 LIMIT 1)sql";

constexpr char kNextValuesSql[] = R"sql(
  SELECT key, entry, surface_sha256, value FROM feature_cache
  WHERE key > ?1 OR (key = ?1 AND entry > ?2)
  ORDER BY key, entry
  LIMIT 1000)sql";

Status read_surface(SqlSession& c, const std::string& after, std::vector<StoredItem>& out) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kNextSurfaceSql));
  q.bind(1, after);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return ok_status();
  StoredItem& item = out.emplace_back();
  item.kind = StoredKind::kSurface;
  item.key = q.text(0);
  item.bytes = q.blob(1);
  SOIQ_ASSIGN_OR_RETURN(SqlStatement ids, c.prepare(kSurfaceStructuresSql));
  ids.bind(1, item.key);
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const bool more, ids.step());
    if (!more) return ok_status();
    item.structure_ids.push_back(ids.int64(0));
  }
}

Status read_image(SqlSession& c, const std::string& after, std::vector<StoredItem>& out) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kNextImageSql));
  q.bind(1, after);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return ok_status();
  StoredItem& item = out.emplace_back();
  item.kind = StoredKind::kImage;
  item.key = q.text(0);
  item.bytes = q.blob(1);
  if (q.is_null(2)) return ok_status();
  item.series_uid = q.text(2);
  ImageGeometry& g = item.geometry;
  for (int a = 0; a < 3; ++a) {
    g.origin_mm[a] = q.real(3 + a);
    g.spacing_mm[a] = q.real(6 + a);
    g.dims[a] = q.int64(9 + a);
    for (int b = 0; b < 3; ++b) g.direction[a][b] = q.real(12 + 3 * a + b);
  }
  return ok_status();
}

Status read_values(SqlSession& c, const StoredItem* last, std::vector<StoredItem>& out) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kNextValuesSql));
  q.bind(1, last ? last->key : std::string());
  q.bind(2, last ? last->entry : std::string());
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return ok_status();
    StoredItem& item = out.emplace_back();
    item.kind = StoredKind::kCachedValue;
    item.key = q.text(0);
    item.entry = q.text(1);
    item.surface_sha256 = q.text(2);
    item.bytes = q.blob(3);
  }
}

}  // namespace

Status SqlStore::scan_stored(StoredKind kind, const std::function<Status(const StoredItem&)>& visit) {
  std::vector<StoredItem> page;
  while (true) {
    std::vector<StoredItem> next;
    const StoredItem* last = page.empty() ? nullptr : &page.back();
    SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
      next.clear();
      switch (kind) {
        case StoredKind::kSurface:
          return read_surface(c, last ? last->key : std::string(), next);
        case StoredKind::kImage:
          return read_image(c, last ? last->key : std::string(), next);
        case StoredKind::kCachedValue:
          return read_values(c, last, next);
      }
      return ok_status();
    }));
    if (next.empty()) return ok_status();
    for (const StoredItem& item : next) SOIQ_RETURN_IF_ERROR(visit(item));
    page = std::move(next);
  }
}

}  // namespace soiq::db
