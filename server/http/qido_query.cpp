#include "server/http/qido_query.h"

#include <algorithm>
#include <charconv>
#include <map>

#include "core/base/field_rules.h"
#include "db/age_years.h"
#include "db/validate_records.h"
#include "server/app/structure_object_uids.h"

namespace soiq::server::http {
namespace {

bool has_wildcard(const std::string& v) { return v.find_first_of("*?") != std::string::npos; }

std::vector<std::string> split_list(const std::string& v) {
  std::vector<std::string> out;
  std::string cur;
  for (const char c : v) {
    if (c == ',' || c == '\\') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

Result<int64_t> parse_int(const std::string& name, const std::string& v, int64_t lo, int64_t hi) {
  int64_t n = 0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
  if (v.empty() || ec != std::errc() || end != v.data() + v.size() || n < lo || n > hi)
    return invalid_argument(name + " must be an integer " +
                            (hi >= (int64_t(1) << 40) ? ">= " + std::to_string(lo)
                                                      : "in " + std::to_string(lo) + ".." + std::to_string(hi)) +
                            ", not '" + v + "'");
  return n;
}

// DICOM's date range, by the one rule of dates (core/base/field_rules.h).
Status date_range(const std::string& v, std::string& from, std::string& to) {
  Result<DateRange> range = parse_date_range(v);
  if (!range.ok()) return range.status().in_field("StudyDate");
  from = range->from;
  to = range->to;
  return ok_status();
}

Status exact_only(const DicomAttribute& a, const std::string& v) {
  if (has_wildcard(v))
    return invalid_argument(std::string(a.keyword) + " matches exact values only, not the wildcards in '" + v + "'");
  if (v.find_first_of(",\\") != std::string::npos)
    return invalid_argument(std::string(a.keyword) + " takes one value, not the list '" + v + "'");
  return ok_status();
}

// The words of a fuzzy name: split at spaces, ^ and =, wildcards dropped.
std::vector<std::string> name_words(const std::string& v) {
  std::vector<std::string> words;
  std::string cur;
  for (const char c : v) {
    if (c == ' ' || c == '^' || c == '=' || c == '*' || c == '?') {
      if (!cur.empty()) words.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) words.push_back(cur);
  return words;
}

const char* level_name(QidoLevel l) {
  return l == QidoLevel::kStudy ? "studies" : l == QidoLevel::kSeries ? "series" : "instances";
}

// The keys a level matches on: the study level's at /studies; the series level's own and the
// patient and study keys the store's series search takes below it.
bool matches_at(QidoLevel level, uint32_t tag) {
  switch (tag) {
    case tags::kStudyInstanceUid:
    case tags::kPatientId:
      return true;
    case tags::kPatientName:
    case tags::kStudyDate:
    case tags::kAccessionNumber:
    case tags::kStudyId:
    case tags::kModalitiesInStudy:
      return level == QidoLevel::kStudy;
    case tags::kModality:
    case tags::kSeriesInstanceUid:
      return level != QidoLevel::kStudy;
    case tags::kSopInstanceUid:
      return level == QidoLevel::kInstance;
    default:
      return false;
  }
}

std::string keys_at(QidoLevel level) {
  std::string out;
  for (const DicomAttribute& a : dicomweb_attributes()) {
    if (a.matchable && matches_at(level, a.tag)) out += (out.empty() ? "" : ", ") + std::string(a.keyword);
  }
  return out;
}

}  // namespace

std::string dicom_wildcards_to_glob(const std::string& value) {
  std::string out;
  for (const char c : value) {
    if (c == '[') {
      out += "[[]";
    } else {
      out += c;
    }
  }
  return out;
}

Result<QidoQuery> parse_qido(QidoLevel level, const std::string& path_study_uid, const std::string& path_series_uid,
                             const QueryParams& params, bool names_kept) {
  QidoQuery q;
  q.level = level;
  bool fuzzy = false;
  std::map<uint32_t, std::string> keys;  // matching keys with a value, by tag
  std::set<std::string> seen;
  for (const auto& [name, value] : params) {
    if (name == "includefield") {
      for (const std::string& id : split_list(value)) {
        if (id == "all") {
          q.include_all = true;
        } else if (const DicomAttribute* a = find_attribute(id)) {
          q.include.insert(a->tag);
        }
      }
      continue;
    }
    if (!seen.insert(name).second) return invalid_argument("query parameter '" + name + "' is given twice");
    if (name == "limit") {
      SOIQ_ASSIGN_OR_RETURN(q.limit, parse_int("limit", value, 1, int64_t(1) << 40));
      if (q.limit > db::kMaxSearchLimit) {
        q.limit = db::kMaxSearchLimit;
        q.limit_clamped = true;
      }
    } else if (name == "offset") {
      SOIQ_ASSIGN_OR_RETURN(q.offset, parse_int("offset", value, 0, int64_t(1) << 40));
    } else if (name == "fuzzymatching") {
      if (value != "true" && value != "false")
        return invalid_argument("fuzzymatching must be true or false, not '" + value + "'");
      fuzzy = value == "true";
    } else {
      const DicomAttribute* a = find_attribute(name);
      if (a == nullptr)
        return invalid_argument("unknown query key '" + name + "'; soiq matches " + level_name(level) + " on " +
                                keys_at(level) + " (and takes limit, offset, includefield, fuzzymatching)");
      if (value.empty()) {
        q.include.insert(a->tag);  // a return key
        continue;
      }
      if (!a->matchable || !matches_at(level, a->tag))
        return invalid_argument("soiq cannot match " + std::string(level_name(level)) + " on " + a->keyword +
                                "; it matches on " + keys_at(level) + " (includefield=" + a->keyword + " returns it)");
      if (value == "*") continue;  // universal matching
      keys[a->tag] = value;
    }
  }

  // Where the path names a study or series, a query key naming another one matches nothing; the
  // path's is the one kept (a key that agrees changes nothing).
  std::vector<std::string> study_uids;
  if (auto it = keys.find(tags::kStudyInstanceUid); it != keys.end()) {
    if (has_wildcard(it->second)) return invalid_argument("StudyInstanceUID takes UIDs, not wildcards");
    study_uids = split_list(it->second);
    if (study_uids.size() > size_t(db::kMaxSearchLimit))
      return invalid_argument("StudyInstanceUID lists more than " + std::to_string(db::kMaxSearchLimit) + " UIDs");
  }
  if (!path_study_uid.empty()) {
    if (!study_uids.empty() && std::find(study_uids.begin(), study_uids.end(), path_study_uid) == study_uids.end()) {
      q.matches_nothing = true;
    } else {
      study_uids = {path_study_uid};
    }
  }
  for (const std::string& uid : study_uids)
    SOIQ_RETURN_IF_ERROR(db::validate_text(uid, "StudyInstanceUID", db::kMaxIdBytes));
  std::string patient_id;
  if (auto it = keys.find(tags::kPatientId); it != keys.end()) patient_id = dicom_wildcards_to_glob(it->second);

  if (level == QidoLevel::kStudy) {
    db::StudySearch& s = q.studies;
    s.study_uids = study_uids;
    s.patient_id = patient_id;
    if (auto it = keys.find(tags::kPatientName); it != keys.end()) {
      if (!names_kept)
        return invalid_argument(
            "soiqd keeps no patient names (it was started without --keep-patient-names): match on PatientID");
      if (fuzzy) {
        s.patient_name_words = name_words(it->second);
        if (s.patient_name_words.empty()) s.patient_name_glob = "*";
      } else {
        s.patient_name_glob = dicom_wildcards_to_glob(it->second);
      }
    }
    if (auto it = keys.find(tags::kStudyDate); it != keys.end())
      SOIQ_RETURN_IF_ERROR(date_range(it->second, s.study_date_from, s.study_date_to));
    for (const auto& [tag, field] :
         {std::pair{tags::kAccessionNumber, &s.accession_number}, std::pair{tags::kStudyId, &s.study_id},
          std::pair{tags::kModalitiesInStudy, &s.modality}}) {
      if (auto it = keys.find(tag); it != keys.end()) {
        SOIQ_RETURN_IF_ERROR(exact_only(*find_attribute(tag_key(tag)), it->second));
        *field = it->second;
      }
    }
    s.offset = q.offset;
    s.limit = q.limit;
    return q;
  }

  db::SeriesSearch& s = q.series;
  s.study_uids = study_uids;
  s.patient_id = patient_id;
  std::string series_uid = path_series_uid;
  if (auto it = keys.find(tags::kSeriesInstanceUid); it != keys.end()) {
    SOIQ_RETURN_IF_ERROR(exact_only(*find_attribute("SeriesInstanceUID"), it->second));
    if (!series_uid.empty() && series_uid != it->second) q.matches_nothing = true;
    series_uid = it->second;
  }
  if (!series_uid.empty()) {
    SOIQ_RETURN_IF_ERROR(db::validate_text(series_uid, "SeriesInstanceUID", db::kMaxIdBytes));
    q.series_uid_asked = series_uid;
    // A structure's SEG or RT Structure Set series is found by the structure id and object its
    // UID carries (the handler checks the whole UID); any other UID names an image series.
    if (const auto parsed = parse_structure_object_uid(series_uid); parsed && !parsed->instance) {
      s.structure_id = parsed->structure_id;
      s.object = parsed->object;
    } else {
      s.series_uid = series_uid;
    }
  }
  if (auto it = keys.find(tags::kModality); it != keys.end()) {
    SOIQ_RETURN_IF_ERROR(exact_only(*find_attribute("Modality"), it->second));
    s.modality = it->second;
  }
  if (auto it = keys.find(tags::kSopInstanceUid); it != keys.end()) {
    SOIQ_RETURN_IF_ERROR(exact_only(*find_attribute("SOPInstanceUID"), it->second));
    q.sop_instance_uid = it->second;
  }
  if (level == QidoLevel::kSeries) {
    s.offset = q.offset;
    s.limit = q.limit;
  }
  return q;
}

}  // namespace soiq::server::http
