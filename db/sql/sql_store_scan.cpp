// SqlStore::scan_stored: every stored surface blob, image blob, cached value, instance file or kept
// instance handed out as it is stored, for soiq-admin verify to check (server/app/store_verify.h).
// Each read is a short read transaction of its own: one blob or file at a time (they are large),
// cached values and instances a page at a time, each continuing after the last key seen, so the
// scan never holds a snapshot for long.
#include <string>
#include <vector>

#include "db/sql/record_sql.h"
#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"

namespace soiq::db {
namespace {

constexpr char kNextSurfaceSql[] = R"sql(
  SELECT sha256, blob FROM surfaces WHERE sha256 > ?1 ORDER BY sha256 LIMIT 1)sql";

constexpr char kSurfaceStructuresSql[] = R"sql(
  SELECT id FROM structures WHERE surface_sha256 = ?1 ORDER BY id)sql";

// The image with the first series that holds it, whose grid the blob is decoded on (the sha256
// covers the grid, so every series that holds it has the same). A store of a schema before the
// slice positions (opened read only, not migrated) has only evenly spaced series.
#define SOIQ_NEXT_IMAGE_SQL(slice_positions)                                                                       \
  "SELECT b.sha256, b.blob, se.series_uid, se.origin_x, se.origin_y, se.origin_z, se.spacing_x, se.spacing_y, "    \
  "se.spacing_z, se.dim_x, se.dim_y, se.dim_z, se.d00, se.d01, se.d02, se.d10, se.d11, se.d12, se.d20, se.d21, "   \
  "se.d22, " slice_positions                                                                                       \
  " FROM image_blobs b LEFT JOIN series se ON se.pk = (SELECT min(pk) FROM series WHERE image_sha256 = b.sha256) " \
  "WHERE b.sha256 > ?1 ORDER BY b.sha256 LIMIT 1"
constexpr char kNextImageSql[] = SOIQ_NEXT_IMAGE_SQL("se.slice_positions");
constexpr char kNextImageBeforePositionsSql[] = SOIQ_NEXT_IMAGE_SQL("''");
#undef SOIQ_NEXT_IMAGE_SQL

constexpr char kNextValuesSql[] = R"sql(
  SELECT key, entry, surface_sha256, value FROM feature_cache
  WHERE key > ?1 OR (key = ?1 AND entry > ?2)
  ORDER BY key, entry
  LIMIT 1000)sql";

// An instance file with the first series (by uid) whose instances hold it.
constexpr char kNextInstanceFileSql[] = R"sql(
  SELECT f.sha256, f.blob,
         coalesce((SELECT min(se.series_uid) FROM instances i JOIN series se ON se.pk = i.series_pk
                   WHERE i.file_sha256 = f.sha256), '')
  FROM instance_files f
  WHERE f.sha256 > ?1 ORDER BY f.sha256 LIMIT 1)sql";

constexpr char kNextInstancesSql[] = R"sql(
  SELECT i.sop_instance_uid, i.slice, i.file_sha256, i.file_bytes, i.metadata, i.metadata_crc32,
         coalesce(se.series_uid, '')
  FROM instances i
  LEFT JOIN series se ON se.pk = i.series_pk
  WHERE i.sop_instance_uid > ?1
  ORDER BY i.sop_instance_uid
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
  SOIQ_ASSIGN_OR_RETURN(const bool positions, column_exists(c, "series", "slice_positions"));
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(positions ? kNextImageSql : kNextImageBeforePositionsSql));
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
  g.slice_positions_mm = split_positions(q.text(21));
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

// A store of a schema before the kept instances (opened read only, not migrated) has none.
Status read_instance_file(SqlSession& c, const std::string& after, std::vector<StoredItem>& out) {
  SOIQ_ASSIGN_OR_RETURN(const bool kept, table_exists(c, "instance_files"));
  if (!kept) return ok_status();
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kNextInstanceFileSql));
  q.bind(1, after);
  SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
  if (!row) return ok_status();
  StoredItem& item = out.emplace_back();
  item.kind = StoredKind::kInstanceFile;
  item.key = q.text(0);
  item.bytes = q.blob(1);
  item.series_uid = q.text(2);
  return ok_status();
}

Status read_instances(SqlSession& c, const std::string& after, std::vector<StoredItem>& out) {
  SOIQ_ASSIGN_OR_RETURN(const bool kept, table_exists(c, "instances"));
  if (!kept) return ok_status();
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kNextInstancesSql));
  q.bind(1, after);
  while (true) {
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return ok_status();
    StoredItem& item = out.emplace_back();
    item.kind = StoredKind::kInstance;
    InstanceRecord& r = item.instance;
    r.sop_instance_uid = q.text(0);
    r.slice = q.int64(1);
    r.file_sha256 = q.text(2);
    r.file_bytes = q.int64(3);
    r.metadata = q.text(4);
    item.instance_crc32 = q.int64(5);
    r.series_uid = q.text(6);
    item.key = r.sop_instance_uid;
    item.series_uid = r.series_uid;
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
        case StoredKind::kInstanceFile:
          return read_instance_file(c, last ? last->key : std::string(), next);
        case StoredKind::kInstance:
          return read_instances(c, last ? last->key : std::string(), next);
      }
      return ok_status();
    }));
    if (next.empty()) return ok_status();
    for (const StoredItem& item : next) SOIQ_RETURN_IF_ERROR(visit(item));
    page = std::move(next);
  }
}

}  // namespace soiq::db
