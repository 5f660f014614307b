// SqlStore's DICOMweb searches (store.h "DICOMweb's view"): a page of keys in the store's order
// first, then the page's records and counts by key, so a search costs the page, not the matches.
#include <algorithm>
#include <map>

#include "db/age_years.h"
#include "db/sql/glob_range.h"
#include "db/sql/record_sql.h"
#include "db/sql/sql_conditions.h"
#include "db/sql/sql_store.h"
#include "db/validate_records.h"

namespace soiq::db {
namespace {

// A DICOM series of a study: an image series imported from DICOM (it has a SOP class), or one of
// the objects of a structure converted on one (structure_object.h).
constexpr char kDicomImage[] = "se.sop_class_uid <> ''";

Status validate_paging(int64_t offset, int64_t limit) {
  if (offset < 0) return invalid_argument("offset " + std::to_string(offset) + " is negative");
  if (limit < 1 || limit > kMaxSearchLimit)
    return invalid_argument("limit " + std::to_string(limit) + " is outside 1.." + std::to_string(kMaxSearchLimit));
  return ok_status();
}

Status validate_uids(const std::vector<std::string>& uids, const char* what) {
  if (uids.size() > size_t(kMaxSearchLimit))
    return invalid_argument(std::string("more than ") + std::to_string(kMaxSearchLimit) + " " + what + "s");
  for (const std::string& uid : uids) SOIQ_RETURN_IF_ERROR(validate_text(uid, what, kMaxIdBytes));
  return ok_status();
}

Status validate_study_search(const StudySearch& s) {
  SOIQ_RETURN_IF_ERROR(validate_paging(s.offset, s.limit));
  SOIQ_RETURN_IF_ERROR(validate_uids(s.study_uids, "study uid"));
  SOIQ_RETURN_IF_ERROR(validate_text(s.patient_id, "patient id", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.patient_name_glob, "patient name pattern", kMaxNameBytes));
  if (s.patient_name_words.size() > 16) return invalid_argument("more than 16 words in a patient name");
  for (const std::string& w : s.patient_name_words) SOIQ_RETURN_IF_ERROR(validate_text(w, "name word", kMaxNameBytes));
  SOIQ_RETURN_IF_ERROR(check_date(s.study_date_from).in_field("study date"));
  SOIQ_RETURN_IF_ERROR(check_date(s.study_date_to).in_field("study date"));
  SOIQ_RETURN_IF_ERROR(validate_text(s.accession_number, "accession number", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.study_id, "study id", kMaxIdBytes));
  return validate_text(s.modality, "modality", kMaxIdBytes);
}

bool is_glob(const std::string& v) { return v.find_first_of("*?[") != std::string::npos; }

void patient_id_condition(SqlConditions& where, const std::string& patient_id) {
  if (patient_id.empty()) return;
  if (is_glob(patient_id)) {
    where.glob("p.patient_id", patient_id);
  } else {
    where.equal("p.patient_id", patient_id);
  }
}

// A word as a glob that matches it literally: the glob specials become one-character sets.
std::string literal_glob(const std::string& word) {
  std::string out;
  for (const char ch : word) {
    if (ch == '*' || ch == '?' || ch == '[') {
      out += '[';
      out += ch;
      out += ']';
    } else {
      out += ch;
    }
  }
  return out;
}

void study_conditions(SqlConditions& where, const StudySearch& s) {
  if (!s.study_uids.empty()) where.any_equal("st.study_uid", s.study_uids);
  patient_id_condition(where, s.patient_id);
  if (!s.patient_name_glob.empty()) where.glob("lower(p.patient_name)", ascii_lower(s.patient_name_glob));
  for (const std::string& word : s.patient_name_words) {
    const std::string w = literal_glob(ascii_lower(word));
    where.any_glob("lower(p.patient_name)", {w + "*", "*^" + w + "*", "* " + w + "*"});
  }
  if (!s.study_date_from.empty()) where.compare("st.study_date", ">=", s.study_date_from);
  if (!s.study_date_to.empty()) {
    where.compare("st.study_date", "<=", s.study_date_to);
    where.compare("st.study_date", "<>", std::string());  // an unknown date is in no range
  }
  if (!s.accession_number.empty()) where.equal("st.accession_number", s.accession_number);
  if (!s.study_id.empty()) where.equal("st.study_id", s.study_id);
  if (structure_object_of_modality(s.modality)) {
    where.literal(
        "EXISTS (SELECT 1 FROM structures ms JOIN series se ON se.series_uid = ms.source_series_uid "
        "WHERE ms.study_pk = st.pk AND " +
        std::string(kDicomImage) + ")");
  } else if (!s.modality.empty()) {
    where.with_values("EXISTS (SELECT 1 FROM series se WHERE se.study_pk = st.pk AND se.modality = {} AND " +
                          std::string(kDicomImage) + ")",
                      {s.modality});
  }
}

constexpr char kStudyPageFromSql[] = R"sql(
  FROM studies st
  JOIN patients p ON p.pk = st.patient_pk
  WHERE true)sql";

// A study's image series by modality, and its structures (each a series per object), for a page of
// studies.
constexpr char kStudyImageCountsSql[] = R"sql(
  SELECT se.study_pk, se.modality, count(*), CAST(sum(se.dim_z) AS bigint)
  FROM series se
  WHERE se.sop_class_uid <> '' AND se.study_pk IN ()sql";
constexpr char kStudySegCountsSql[] = R"sql(
  SELECT ms.study_pk, count(*)
  FROM structures ms
  JOIN series se ON se.series_uid = ms.source_series_uid
  WHERE se.sop_class_uid <> '' AND ms.study_pk IN ()sql";

}  // namespace

Result<std::vector<StudyHit>> SqlStore::search_studies(const StudySearch& s) {
  SOIQ_RETURN_IF_ERROR(validate_study_search(s));
  std::vector<StudyHit> hits;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    hits.clear();
    SqlConditions where(c.dialect());
    study_conditions(where, s);
    std::vector<int64_t> keys;
    std::map<int64_t, size_t> index;
    {
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q,
                            c.prepare(select_sql({kStudyColumns, kPatientColumns, "st.pk"},
                                                 {kStudyPageFromSql, where.sql(), "ORDER BY st.pk LIMIT",
                                                  std::to_string(s.limit), "OFFSET", std::to_string(s.offset)})));
      where.bind(q);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        StudyHit h;
        h.study = read_study(q, 0);
        h.patient = read_patient(q, kStudyColumnCount);
        keys.push_back(q.int64(kStudyColumnCount + kPatientColumnCount));
        index[keys.back()] = hits.size();
        hits.push_back(std::move(h));
      }
    }
    if (keys.empty()) return ok_status();
    for (const char* sql : {kStudyImageCountsSql, kStudySegCountsSql}) {
      const bool images = sql == kStudyImageCountsSql;
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q,
                            c.prepare(sql + parameter_list(keys.size()) +
                                      (images ? ") GROUP BY se.study_pk, se.modality" : ") GROUP BY ms.study_pk")));
      for (size_t i = 0; i < keys.size(); ++i) q.bind(int(i + 1), keys[i]);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        StudyHit& h = hits[index.at(q.int64(0))];
        if (images) {
          h.modalities.push_back(q.text(1));
          h.series_count += q.int64(2);
          h.instance_count += q.int64(3);
          continue;
        }
        for (const StructureObject o : kStructureObjects) {
          h.modalities.push_back(structure_object_modality(o));
          h.series_count += q.int64(1);
          h.instance_count += q.int64(1);
        }
      }
    }
    return ok_status();
  }));
  for (StudyHit& h : hits) {
    std::sort(h.modalities.begin(), h.modalities.end());
    h.modalities.erase(std::unique(h.modalities.begin(), h.modalities.end()), h.modalities.end());
  }
  return hits;
}

namespace {

Status validate_series_search(const SeriesSearch& s) {
  SOIQ_RETURN_IF_ERROR(validate_paging(s.offset, s.limit));
  SOIQ_RETURN_IF_ERROR(validate_uids(s.study_uids, "study uid"));
  SOIQ_RETURN_IF_ERROR(validate_text(s.patient_id, "patient id", kMaxIdBytes));
  SOIQ_RETURN_IF_ERROR(validate_text(s.series_uid, "series uid", kMaxIdBytes));
  return validate_text(s.modality, "modality", kMaxIdBytes);
}

// The keys of a page of DICOM series: kind 0 an image series' pk, kind 1 or 2 (object_kind) one
// of a structure's objects by the structure's id, a row per object. Each half of the UNION takes
// its own conditions (" AND …") after its WHERE; `part` puts a study's images before its
// structures, whose objects stay together.
constexpr char kSeriesKeysImagesSql[] = R"sql(
  SELECT st.pk AS study_pk, CAST(0 AS bigint) AS part, se.pk AS item, CAST(0 AS bigint) AS kind
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE se.sop_class_uid <> '')sql";
constexpr char kSeriesKeysStructuresSql[] = R"sql(
  UNION ALL
  SELECT st.pk, CAST(1 AS bigint), s.id, k.kind
  FROM structures s
  CROSS JOIN (SELECT CAST(1 AS bigint) AS kind UNION ALL SELECT CAST(2 AS bigint)) k
  JOIN series se ON se.series_uid = s.source_series_uid
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE se.sop_class_uid <> '')sql";

constexpr char kImageSeriesByPkSql[] = R"sql(
  FROM series se
  JOIN studies st ON st.pk = se.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  WHERE se.pk IN ()sql";
constexpr char kStructureSeriesByIdSql[] = R"sql(
  FROM structures s
  JOIN studies st ON st.pk = s.study_pk
  JOIN patients p ON p.pk = st.patient_pk
  JOIN surfaces sf ON sf.sha256 = s.surface_sha256
  JOIN series se ON se.series_uid = s.source_series_uid
  WHERE s.id IN ()sql";

// A structure object's kind in the keys' rows (kSeriesKeysStructuresSql), and back.
int64_t object_kind(StructureObject o) { return o == StructureObject::kSeg ? 1 : 2; }
StructureObject object_of_kind(int64_t kind) { return kind == 1 ? StructureObject::kSeg : StructureObject::kRtStruct; }

}  // namespace

Result<std::vector<SeriesHit>> SqlStore::search_series(const SeriesSearch& s) {
  SOIQ_RETURN_IF_ERROR(validate_series_search(s));
  std::vector<SeriesHit> hits;
  SOIQ_RETURN_IF_ERROR(read([&](SqlSession& c) -> Status {
    hits.clear();
    SqlConditions where(c.dialect());
    const std::optional<StructureObject> modality_object = structure_object_of_modality(s.modality);
    const bool images = !s.structure_id && !s.object && !modality_object;
    const bool structures = s.series_uid.empty() && (s.modality.empty() || modality_object);
    auto common = [&] {
      if (!s.study_uids.empty()) where.any_equal("st.study_uid", s.study_uids);
      patient_id_condition(where, s.patient_id);
    };
    common();
    if (!images) where.literal("false");
    if (!s.series_uid.empty()) where.equal("se.series_uid", s.series_uid);
    if (!s.modality.empty() && !modality_object) where.equal("se.modality", s.modality);
    const std::string image_conditions = where.take_sql();
    common();
    if (!structures) where.literal("false");
    if (s.structure_id) where.literal("s.id = " + std::to_string(*s.structure_id));  // a number, not text
    for (const std::optional<StructureObject>& o : {modality_object, s.object})
      if (o) where.literal("k.kind = " + std::to_string(object_kind(*o)));
    const std::string structure_conditions = where.take_sql();

    std::vector<std::pair<int, int64_t>> keys;  // (kind, key) in the page's order
    {
      SOIQ_ASSIGN_OR_RETURN(
          SqlStatement q, c.prepare("SELECT h.kind, h.item FROM (" + std::string(kSeriesKeysImagesSql) +
                                    image_conditions + kSeriesKeysStructuresSql + structure_conditions +
                                    ") h ORDER BY h.study_pk, h.part, h.item, h.kind LIMIT " + std::to_string(s.limit) +
                                    " OFFSET " + std::to_string(s.offset)));
      where.bind(q);
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        keys.emplace_back(int(q.int64(0)), q.int64(1));
      }
    }
    hits.resize(keys.size());
    // Images, then structures: a structure with both objects on the page is read once for both.
    for (const bool structure : {false, true}) {
      std::vector<int64_t> ks;
      std::map<int64_t, std::vector<size_t>> at;
      for (size_t i = 0; i < keys.size(); ++i) {
        if ((keys[i].first != 0) != structure) continue;
        std::vector<size_t>& places = at[keys[i].second];
        if (places.empty()) ks.push_back(keys[i].second);
        places.push_back(i);
        if (structure) hits[i].object = object_of_kind(keys[i].first);
      }
      if (ks.empty()) continue;
      const std::string sql =
          !structure ? select_sql({kSeriesColumns, kStudyColumns, kPatientColumns, "se.pk"},
                                  {kImageSeriesByPkSql, parameter_list(ks.size()), ")"})
                     : select_sql({kSeriesColumns, kStudyColumns, kPatientColumns, "s.id", kStructureColumns},
                                  {kStructureSeriesByIdSql, parameter_list(ks.size()), ")"});
      SOIQ_ASSIGN_OR_RETURN(SqlStatement q, c.prepare(sql));
      for (size_t i = 0; i < ks.size(); ++i) q.bind(int(i + 1), ks[i]);
      constexpr int kKey = kSeriesColumnCount + kStudyColumnCount + kPatientColumnCount;
      while (true) {
        SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
        if (!row) break;
        for (const size_t i : at.at(q.int64(kKey))) {
          SeriesHit& h = hits[i];
          h.series = read_series(q, 0);
          h.study = read_study(q, kSeriesColumnCount);
          h.patient = read_patient(q, kSeriesColumnCount + kStudyColumnCount);
          if (structure) h.structure = read_structure(q, kKey + 1);
        }
      }
    }
    return ok_status();
  }));
  return hits;
}

}  // namespace soiq::db
