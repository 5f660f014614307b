// The series half of SqlStore::import_batch: the image blob stored once per sha256, the series
// inserted or replaced in place, never moved to another patient, and its instances
// (sql_store_instances.cpp). One write transaction, so any error leaves the database as it was.
#include <algorithm>
#include <optional>
#include <string>
#include <utility>

#include "db/sql/record_sql.h"
#include "db/sql/sql_store.h"
#include "db/sql/sql_store_writes.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

constexpr char kInsertImageBlobSql[] = R"sql(
  INSERT INTO image_blobs(sha256, blob) VALUES (?1, ?2)
  ON CONFLICT(sha256) DO NOTHING)sql";

// A stored blob whose bytes differ is replaced (replace_differing_blob).
Status insert_image_blob(SqlSession& c, const NewSeries& s) {
  SOIQ_ASSIGN_OR_RETURN(const StoredBlob stored,
                        replace_differing_blob(c, "image_blobs", s.series.sha256, s.image_blob));
  if (stored != StoredBlob::kAbsent) return ok_status();
  SOIQ_ASSIGN_OR_RETURN(SqlStatement ins, c.prepare(kInsertImageBlobSql));
  ins.bind(1, s.series.sha256);
  ins.bind_blob(2, s.image_blob);
  return ins.run();
}

constexpr char kSeriesOwnerSql[] = R"sql(
  SELECT se.image_sha256, st.patient_pk, p.patient_id, se.slice_instance_uids
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE se.series_uid = ?1)sql";

// The image and patient of the stored series with s's uid, if any.
struct StoredSeries {
  std::string image_sha256;
  int64_t patient_pk = 0;
  std::string slice_instance_uids;  // as stored (join_uid_list)
};

// What differs between the stored series and `s` ("" when they are the same content).
std::string what_differs(const StoredSeries& old, const NewSeries& s) {
  const std::string sent = join_uid_list(s.series.slice_instance_uids);
  if (old.slice_instance_uids != sent) {
    return "its slices have other SOP Instance UIDs (" +
           std::to_string(split_uid_list(old.slice_instance_uids).size()) + " slices stored, " +
           std::to_string(s.series.slice_instance_uids.size()) + " sent)";
  }
  if (old.image_sha256 != s.series.sha256)
    return "its voxels differ (image sha256 " + old.image_sha256.substr(0, 12) + "... stored, " +
           s.series.sha256.substr(0, 12) + "... sent)";
  return "";
}

// FAILED_PRECONDITION when the series is stored under another patient than `patient_pk`.
Result<std::optional<StoredSeries>> stored_series(SqlSession& c, const NewSeries& s, int64_t patient_pk) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(kSeriesOwnerSql));
  q.bind(1, s.series.series_uid);
  SOIQ_ASSIGN_OR_RETURN(const bool found, q.step());
  if (!found) return std::optional<StoredSeries>();
  StoredSeries stored{q.text(0), q.int64(1), q.text(3)};
  // A series UID is the image's identity: another patient's upload that names it is a mistake
  // (or an attack), never a reason to move the images.
  if (stored.patient_pk != patient_pk) {
    return failed_precondition("series '" + s.series.series_uid + "' belongs to patient '" + q.text(2) + "', not to '" +
                               s.patient.patient_id + "': an upload never moves a series to another patient");
  }
  return std::optional<StoredSeries>(std::move(stored));
}

// An upsert keeps the series' pk stable when it is replaced.
constexpr char kUpsertSeriesSql[] = R"sql(
  INSERT INTO series(series_uid, study_pk, modality, origin_x, origin_y, origin_z, spacing_x, spacing_y, spacing_z,
                     dim_x, dim_y, dim_z, d00, d01, d02, d10, d11, d12, d20, d21, d22, image_sha256,
                     frame_of_reference_uid, sop_class_uid, slice_instance_uids, series_number, description,
                     window_center, window_width, slice_positions)
  VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16, ?17, ?18, ?19, ?20, ?21, ?22,
          ?23, ?24, ?25, ?26, ?27, ?28, ?29, ?30)
  ON CONFLICT(series_uid) DO UPDATE SET
    study_pk = excluded.study_pk, modality = excluded.modality,
    origin_x = excluded.origin_x, origin_y = excluded.origin_y, origin_z = excluded.origin_z,
    spacing_x = excluded.spacing_x, spacing_y = excluded.spacing_y, spacing_z = excluded.spacing_z,
    dim_x = excluded.dim_x, dim_y = excluded.dim_y, dim_z = excluded.dim_z,
    d00 = excluded.d00, d01 = excluded.d01, d02 = excluded.d02,
    d10 = excluded.d10, d11 = excluded.d11, d12 = excluded.d12,
    d20 = excluded.d20, d21 = excluded.d21, d22 = excluded.d22,
    image_sha256 = excluded.image_sha256, frame_of_reference_uid = excluded.frame_of_reference_uid,
    sop_class_uid = excluded.sop_class_uid, slice_instance_uids = excluded.slice_instance_uids,
    series_number = excluded.series_number, description = excluded.description,
    window_center = excluded.window_center, window_width = excluded.window_width,
    slice_positions = excluded.slice_positions)sql";

Status upsert_series_row(SqlSession& c, const SeriesRecord& series, int64_t study_pk) {
  SOIQ_ASSIGN_OR_RETURN(SqlStatement up, c.prepare(kUpsertSeriesSql));
  const ImageGeometry& g = series.geometry;
  up.bind(1, series.series_uid);
  up.bind(2, study_pk);
  up.bind(3, series.modality);
  for (int a = 0; a < 3; ++a) {
    up.bind(4 + a, g.origin_mm[a]);
    up.bind(7 + a, g.spacing_mm[a]);
    up.bind(10 + a, g.dims[a]);
  }
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) up.bind(13 + 3 * r + col, g.direction[r][col]);
  }
  up.bind(22, series.sha256);
  up.bind(23, series.frame_of_reference_uid);
  up.bind(24, series.sop_class_uid);
  up.bind(25, join_uid_list(series.slice_instance_uids));
  up.bind(26, series.series_number);
  up.bind(27, series.description);
  up.bind(28, series.window_center);
  up.bind(29, series.window_width);
  up.bind(30, join_positions(g.slice_positions_mm));
  return up.run();
}

}  // namespace

Result<bool> insert_series(SqlSession& c, const NewSeries& s) {
  SOIQ_ASSIGN_OR_RETURN(const StudyKeys keys, upsert_patient_and_study(c, s.patient, s.study));
  SOIQ_RETURN_IF_ERROR(insert_image_blob(c, s));
  SOIQ_ASSIGN_OR_RETURN(const std::optional<StoredSeries> old, stored_series(c, s, keys.patient_pk));
  if (old && !s.replace_other_content) {
    const std::string differs = what_differs(*old, s);
    if (differs.empty()) {
      // The same content: nothing to write but the instances it lacks.
      SOIQ_RETURN_IF_ERROR(add_instances(c, s));
      return true;
    }
    return Status(StatusCode::kAlreadyExists,
                  "series '" + s.series.series_uid + "' is stored with other content: " + differs +
                      "; a DICOM UID names one content: send the series as stored, or replace it (soiq import "
                      "--replace)");
  }
  SOIQ_RETURN_IF_ERROR(upsert_series_row(c, s.series, keys.study_pk));
  // The same series sent again (an upload, or an import with instances kept where they were not)
  // keeps the instances stored; other content's instances are other instances.
  const bool same_content = old && what_differs(*old, s).empty();
  SOIQ_RETURN_IF_ERROR(same_content ? add_instances(c, s) : replace_instances(c, s));
  if (old && old->image_sha256 != s.series.sha256) SOIQ_RETURN_IF_ERROR(delete_image_if_orphan(c, old->image_sha256));
  // A new image, or new pixels: the study's structures have intensities to compute on it.
  if (!old || old->image_sha256 != s.series.sha256) SOIQ_RETURN_IF_ERROR(queue_precompute_of_study(c, keys.study_pk));
  // The series' modality counts for its study's structures; a series moved from another
  // patient's study changes that patient's rows too.
  SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, keys.patient_pk));
  if (old && old->patient_pk != keys.patient_pk) SOIQ_RETURN_IF_ERROR(refresh_stage1_rows(c, old->patient_pk));
  return old.has_value();
}

}  // namespace soiq::db
