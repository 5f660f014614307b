#pragma once
// A QIDO-RS request's query parameters (PS3.18 8.3.4 and 10.6.1) as store searches, checked whole
// before anything is read. Pure: no HTTP, no store; tests/server/http covers every rule.
//
// Inputs   level: what the path lists (studies, series, instances). path_study_uid,
//          path_series_uid: from /studies/{uid}/series/{uid}/…, "" when absent. params: the query
//          string's pairs, URL-decoded, in order. names_kept: soiqd keeps patient names.
// Output   QidoQuery: the search at the level asked, what to include, offset and limit.
//          Matching, as PS3.4 C.2.2.2 defines it for the keys soiq matches on:
//          - StudyInstanceUID, SeriesInstanceUID, SOPInstanceUID: one UID, or a list separated by
//            commas or backslashes (StudyInstanceUID only).
//          - PatientID: exact, or wildcards (* and ?; any other character literal).
//          - PatientName: wildcards, ignoring ASCII case; with fuzzymatching=true each word of the
//            value starts a component or word of the name ("ann" finds "Smith^Anna").
//          - StudyDate: YYYYMMDD, or a range A-B, -B, A- (inclusive).
//          - AccessionNumber, StudyID, Modality, ModalitiesInStudy: one exact value.
//          A value of "*" alone matches everything. A key with an empty value is a return key
//          (as includefield). includefield: attribute IDs separated by commas, or "all", any
//          number of times; IDs soiq does not have are ignored (nothing to return).
//          limit: 1..kMaxSearchLimit, default kMaxSearchLimit; a larger one is clamped and
//          `limit_clamped` set (the answer carries a Warning header). offset: >= 0, default 0.
// Errors   INVALID_ARGUMENT naming the parameter and what it accepts: an unknown key, a key soiq
//          cannot match on or not at this level, a key given twice, a malformed date, UID list,
//          limit, offset or fuzzymatching, wildcards where only exact values work, a PatientName
//          key when soiqd keeps no names.

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "server/http/dicomweb_attributes.h"
#include "server/http/http_request.h"  // QueryParams

namespace soiq::server::http {

struct QidoQuery {
  QidoLevel level = QidoLevel::kStudy;
  db::StudySearch studies;       // level kStudy
  db::SeriesSearch series;       // levels kSeries and kInstance (the series to expand)
  std::string series_uid_asked;  // the SeriesInstanceUID of the path or the query, "" none
  std::string sop_instance_uid;  // level kInstance: only this instance
  std::set<uint32_t> include;    // attributes asked for beyond the defaults
  bool include_all = false;
  int64_t offset = 0;
  int64_t limit = db::kMaxSearchLimit;
  bool limit_clamped = false;
  // The path names one study or series and a query key another: the answer is empty.
  bool matches_nothing = false;
};

Result<QidoQuery> parse_qido(QidoLevel level, const std::string& path_study_uid, const std::string& path_series_uid,
                             const QueryParams& params, bool names_kept);

// DICOM wildcards (* ?) as a store GLOB: '[' is literal in DICOM and becomes "[[]".
std::string dicom_wildcards_to_glob(const std::string& value);

}  // namespace soiq::server::http
