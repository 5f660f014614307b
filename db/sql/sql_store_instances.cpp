// The original DICOM instances of image series (InstanceRecord): written with their series
// (sql_store_series.cpp calls add_instances or replace_instances inside its transaction), read by
// list_instances and get_blob(kInstanceFile). A file is stored once per sha256 and removed when no
// instance refers to it any more. Every read checks what it reads: a row by its CRC-32
// (instance_row_crc32), a file by recomputing its sha256; importing the series again repairs both.
#include <optional>
#include <set>
#include <string>

#include "db/crc32.h"
#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"
#include "db/surface_blob.h"

namespace soiq::db {

uint32_t instance_row_crc32(const InstanceRecord& r) {
  // NUL separates the fields: none of them holds one (UIDs and the sha256 are validated), and the
  // metadata, which might, comes last.
  std::string head;
  for (const std::string& field :
       {r.sop_instance_uid, r.series_uid, std::to_string(r.slice), r.file_sha256, std::to_string(r.file_bytes)}) {
    head += field;
    head += '\0';
  }
  return crc32_of(r.metadata, crc32_of(head));
}

namespace {

// An instance's row as stored, with whether its checksum holds. Columns in this order, the series
// uid last ('' when the row's series is gone: a damaged series_pk).
constexpr char kInstanceRowColumns[] = R"sql(
  SELECT i.sop_instance_uid, i.slice, i.file_sha256, i.file_bytes, i.metadata, i.metadata_crc32,
         coalesce(se.series_uid, '')
  FROM instances i
  LEFT JOIN series se ON se.pk = i.series_pk)sql";

struct InstanceRow {
  InstanceRecord record;
  bool sound = false;
};

InstanceRow read_instance_row(const SqlStatement& q) {
  InstanceRow row;
  InstanceRecord& r = row.record;
  r.sop_instance_uid = q.text(0);
  r.slice = q.int64(1);
  r.file_sha256 = q.text(2);
  r.file_bytes = q.int64(3);
  r.metadata = q.text(4);
  r.series_uid = q.text(6);
  row.sound = q.int64(5) == int64_t(instance_row_crc32(r));
  return row;
}

Result<std::optional<InstanceRow>> stored_instance(SqlSession& c, const std::string& sop_instance_uid) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(std::string(kInstanceRowColumns) + " WHERE i.sop_instance_uid = ?1"));
  q.bind(1, sop_instance_uid);
  SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
  if (!found) return std::optional<InstanceRow>();
  return std::optional<InstanceRow>(read_instance_row(q));
}

constexpr char kInsertInstanceFileSql[] = R"sql(
  INSERT INTO instance_files(sha256, blob) VALUES (?1, ?2)
  ON CONFLICT(sha256) DO NOTHING)sql";

// A stored file whose bytes differ from the ones sent is damaged (the sha256 of those was checked)
// and is replaced by them (replace_differing_blob).
Status store_instance_file(SqlSession& c, const NewInstance& i) {
  SOIQ_ASSIGN_OR_RETURN(const StoredBlob stored,
                        replace_differing_blob(c, "instance_files", i.record.file_sha256, i.file));
  if (stored != StoredBlob::kAbsent) return ok_status();
  SOIQ_ASSIGN_OR_RETURN(SqlStatement ins, c.prepare(kInsertInstanceFileSql));
  ins.bind(1, i.record.file_sha256);
  ins.bind_blob(2, i.file);
  return ins.run();
}

// Inserts the row, or rewrites a damaged one in full.
constexpr char kUpsertInstanceSql[] = R"sql(
  INSERT INTO instances(sop_instance_uid, series_pk, slice, file_sha256, file_bytes, metadata, metadata_crc32)
  VALUES (?1, (SELECT pk FROM series WHERE series_uid = ?2), ?3, ?4, ?5, ?6, ?7)
  ON CONFLICT(sop_instance_uid) DO UPDATE SET
    series_pk = excluded.series_pk, slice = excluded.slice, file_sha256 = excluded.file_sha256,
    file_bytes = excluded.file_bytes, metadata = excluded.metadata, metadata_crc32 = excluded.metadata_crc32)sql";

Status upsert_instance_row(SqlSession& c, const InstanceRecord& r) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare(kUpsertInstanceSql));
  up.bind(1, r.sop_instance_uid);
  up.bind(2, r.series_uid);
  up.bind(3, r.slice);
  up.bind(4, r.file_sha256);
  up.bind(5, r.file_bytes);
  up.bind(6, r.metadata);
  up.bind(7, int64_t(instance_row_crc32(r)));
  return up.run();
}

// One instance of the series `s` whose row is written: stored unless it is stored already. A stored
// one is kept as it is (a DICOM UID names one instance: another encoding of it, with another
// sha256, is the same instance), its file repaired if damaged, and its row rewritten if damaged.
Status put_instance(SqlSession& c, const NewSeries& s, const NewInstance& i) {
  const InstanceRecord& r = i.record;
  SOIQ_ASSIGN_OR_RETURN(const std::optional<InstanceRow> stored, stored_instance(c, r.sop_instance_uid));
  if (stored && stored->sound && stored->record.series_uid != s.series.series_uid) {
    return failed_precondition("instance '" + r.sop_instance_uid + "' belongs to series '" + stored->record.series_uid +
                               "', not to '" + s.series.series_uid +
                               "': a SOP Instance UID names one instance of one series");
  }
  if (stored && stored->sound && stored->record.file_sha256 != r.file_sha256) return ok_status();
  SOIQ_RETURN_IF_ERROR(store_instance_file(c, i));
  if (stored && stored->sound) return ok_status();
  SOIQ_RETURN_IF_ERROR(upsert_instance_row(c, r));
  // A damaged row named a file that may now be nobody's.
  if (stored && stored->record.file_sha256 != r.file_sha256)
    return delete_instance_file_if_orphan(c, stored->record.file_sha256);
  return ok_status();
}

constexpr char kDeleteInstancesOfSeriesSql[] = R"sql(
  DELETE FROM instances WHERE series_pk = (SELECT pk FROM series WHERE series_uid = ?1)
  RETURNING file_sha256)sql";

}  // namespace

Status add_instances(SqlSession& c, const NewSeries& s) {
  for (const NewInstance& i : s.instances) SOIQ_RETURN_IF_ERROR(put_instance(c, s, i));
  return ok_status();
}

Status replace_instances(SqlSession& c, const NewSeries& s) {
  std::set<std::string> old_files;
  {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement del, c.prepare(kDeleteInstancesOfSeriesSql));
    del.bind(1, s.series.series_uid);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, del.step());
      if (!row) break;
      old_files.insert(del.text(0));
    }
  }
  SOIQ_RETURN_IF_ERROR(add_instances(c, s));
  for (const std::string& sha : old_files) SOIQ_RETURN_IF_ERROR(delete_instance_file_if_orphan(c, sha));
  return ok_status();
}

namespace {

constexpr char kInstanceSeriesExistsSql[] = R"sql(
  SELECT 1 FROM series WHERE series_uid = ?1)sql";

constexpr char kInstancesOfSeriesOrderSql[] = R"sql(
  WHERE se.series_uid = ?1
  ORDER BY i.slice, i.sop_instance_uid)sql";

}  // namespace

Result<std::vector<InstanceRecord>> SqlStore::list_instances(const std::string& series_uid) {
  std::vector<InstanceRecord> out;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    out.clear();
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kInstanceSeriesExistsSql));
      q.bind(1, series_uid);
      SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
      if (!found) return not_found("series '" + series_uid + "' not found");
    }
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(std::string(kInstanceRowColumns) + kInstancesOfSeriesOrderSql));
    q.bind(1, series_uid);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) return ok_status();
      InstanceRow got = read_instance_row(q);
      if (!got.sound) {
        return data_loss("instance '" + got.record.sop_instance_uid + "' of series '" + series_uid +
                         "' is damaged: its stored record no longer matches its checksum; import the series "
                         "again to repair it");
      }
      out.push_back(std::move(got.record));
    }
  }));
  return out;
}

namespace {

constexpr char kInstanceFileSql[] = R"sql(
  SELECT blob FROM instance_files WHERE sha256 = ?1)sql";

}  // namespace

Result<std::string> SqlStore::instance_file(const std::string& sha256) {
  std::string file;
  SOIQ_RETURN_IF_ERROR(read_one([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kInstanceFileSql));
    q.bind(1, sha256);
    SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
    if (!row) return not_found("instance file " + sha256 + " not found");
    file = q.blob(0);
    return ok_status();
  }));
  // Outside the transaction: hashing a large file holds no snapshot.
  if (sha256_hex(file.data(), file.size()) != sha256) {
    return data_loss("instance file " + sha256 +
                     " is damaged: its bytes no longer hash to their key; import the series again to repair it");
  }
  return file;
}

}  // namespace soiq::db
