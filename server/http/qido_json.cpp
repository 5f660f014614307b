#include "server/http/qido_json.h"

#include <cmath>
#include <cstdio>

#include "server/app/structure_object.h"
#include "server/app/structure_object_uids.h"

namespace soiq::server::http {
namespace {

using nlohmann::json;

// Builds one result object, adding an attribute only when the query's level returns it by default
// or the query asked for it.
class QidoResultObject {
 public:
  QidoResultObject(const QidoQuery& q, QidoLevel level) : q_(q), level_(level) {}

  bool wanted(uint32_t tag) const {
    if (q_.include_all || q_.include.count(tag) > 0) return true;
    const DicomAttribute* a = find_attribute(tag_key(tag));
    return a != nullptr && a->default_return && a->level == level_;
  }
  // Added whether asked or not (identifiers a result of this level always carries).
  void always(uint32_t tag, const char* vr, const std::string& v) {
    put(tag, vr, v.empty() ? json() : json::array({v}));
  }
  void text(uint32_t tag, const char* vr, const std::string& v) {
    if (wanted(tag)) put(tag, vr, v.empty() ? json() : json::array({v}));
  }
  void texts(uint32_t tag, const char* vr, const std::vector<std::string>& vs) {
    if (wanted(tag)) put(tag, vr, vs.empty() ? json() : json(vs));
  }
  void number(uint32_t tag, const char* vr, int64_t v, bool known = true) {
    if (wanted(tag)) put(tag, vr, known ? json::array({v}) : json());
  }
  void person(uint32_t tag, const std::string& name) {
    if (!wanted(tag)) return;
    if (name.empty()) {
      put(tag, "PN", json());
      return;
    }
    // PS3.18 F.2.2: the component groups of a PN, split at '='.
    json pn = json::object();
    const char* groups[] = {"Alphabetic", "Ideographic", "Phonetic"};
    size_t from = 0;
    for (int g = 0; g < 3 && from <= name.size(); ++g) {
      const size_t eq = name.find('=', from);
      const std::string part = name.substr(from, eq == std::string::npos ? std::string::npos : eq - from);
      if (!part.empty()) pn[groups[g]] = part;
      if (eq == std::string::npos) break;
      from = eq + 1;
    }
    put(tag, "PN", json::array({pn}));
  }
  json take() { return std::move(out_); }

 private:
  void put(uint32_t tag, const char* vr, json value) {
    json a = {{"vr", vr}};
    if (!value.is_null()) a["Value"] = std::move(value);
    out_[tag_key(tag)] = std::move(a);
  }

  const QidoQuery& q_;
  QidoLevel level_;
  json out_ = json::object();
};

// PatientAge (AS): whole years as "nnnY".
std::string age_string(const std::optional<double>& years) {
  if (!years || !std::isfinite(*years) || *years < 0 || *years > 999) return "";
  char out[8];
  std::snprintf(out, sizeof out, "%03dY", int(std::floor(*years)));
  return out;
}

void study_attributes(QidoResultObject& r, const db::StudyRecord& st, const db::PatientRecord& p) {
  r.text(tags::kSpecificCharacterSet, "CS", "ISO_IR 192");
  r.text(tags::kStudyDate, "DA", st.study_date);
  r.text(tags::kStudyTime, "TM", st.study_time);
  r.text(tags::kAccessionNumber, "SH", st.accession_number);
  r.text(tags::kReferringPhysicianName, "PN", "");
  r.text(tags::kStudyDescription, "LO", st.description);
  r.person(tags::kPatientName, p.patient_name);
  r.text(tags::kPatientBirthDate, "DA", p.birth_date);
  r.text(tags::kPatientSex, "CS", p.sex);
  r.text(tags::kPatientAge, "AS", age_string(st.age_years));
  r.text(tags::kStudyId, "SH", st.study_id);
}

}  // namespace

std::string series_uid_of(const db::SeriesHit& h) {
  return h.structure ? structure_object_uids(*h.structure, h.object).series_uid : h.series.series_uid;
}

int64_t instance_count_of(const db::SeriesHit& h) {
  if (h.structure) return 1;
  return int64_t(h.series.slice_instance_uids.size());
}

std::string instance_uid_of(const InstanceRef& i) {
  const db::SeriesHit& h = *i.series;
  if (h.structure) return structure_object_uids(*h.structure, h.object).sop_instance_uid;
  return i.k >= 0 && i.k < int64_t(h.series.slice_instance_uids.size()) ? h.series.slice_instance_uids[size_t(i.k)]
                                                                        : "";
}

json study_json(const db::StudyHit& h, const std::string& base_url, const QidoQuery& q) {
  QidoResultObject r(q, QidoLevel::kStudy);
  study_attributes(r, h.study, h.patient);
  r.always(tags::kStudyInstanceUid, "UI", h.study.study_uid);
  r.always(tags::kPatientId, "LO", h.patient.patient_id);
  r.texts(tags::kModalitiesInStudy, "CS", h.modalities);
  r.number(tags::kNumberOfStudyRelatedSeries, "IS", h.series_count);
  r.number(tags::kNumberOfStudyRelatedInstances, "IS", h.instance_count);
  // Some of a study's series may be images soiq keeps only as voxels: PARTIAL would say so per
  // series; the study is ONLINE when its SEGs are there to retrieve.
  r.text(tags::kInstanceAvailability, "CS", h.series_count > 0 ? "ONLINE" : "UNAVAILABLE");
  r.text(tags::kRetrieveUrl, "UR", base_url + "/studies/" + h.study.study_uid);
  return r.take();
}

json series_json(const db::SeriesHit& h, const std::string& base_url, const QidoQuery& q) {
  QidoResultObject r(q, QidoLevel::kSeries);
  study_attributes(r, h.study, h.patient);
  const std::string uid = series_uid_of(h);
  r.always(tags::kStudyInstanceUid, "UI", h.study.study_uid);
  r.always(tags::kPatientId, "LO", h.patient.patient_id);
  r.always(tags::kSeriesInstanceUid, "UI", uid);
  if (h.structure) {
    const StructureObjectListing listed = structure_object_listing(*h.structure, h.object);
    r.always(tags::kModality, "CS", listed.modality);
    r.number(tags::kSeriesNumber, "IS", listed.series_number);
    r.text(tags::kSeriesDescription, "LO", listed.series_description);
  } else {
    r.always(tags::kModality, "CS", h.series.modality);
    r.number(tags::kSeriesNumber, "IS", h.series.series_number, h.series.series_number > 0);
    r.text(tags::kSeriesDescription, "LO", h.series.description);
  }
  r.text(tags::kFrameOfReferenceUid, "UI", h.series.frame_of_reference_uid);
  r.number(tags::kNumberOfSeriesRelatedInstances, "IS", instance_count_of(h));
  r.always(tags::kInstanceAvailability, "CS", h.structure ? "ONLINE" : "UNAVAILABLE");
  if (h.structure) r.always(tags::kRetrieveUrl, "UR", base_url + "/studies/" + h.study.study_uid + "/series/" + uid);
  return r.take();
}

json instance_json(const InstanceRef& i, const std::string& base_url, const QidoQuery& q) {
  const db::SeriesHit& h = *i.series;
  QidoResultObject r(q, QidoLevel::kInstance);
  study_attributes(r, h.study, h.patient);
  const std::string series_uid = series_uid_of(h);
  const std::string uid = instance_uid_of(i);
  r.always(tags::kStudyInstanceUid, "UI", h.study.study_uid);
  r.always(tags::kSeriesInstanceUid, "UI", series_uid);
  if (h.structure) {
    const StructureObjectListing listed = structure_object_listing(*h.structure, h.object);
    r.always(tags::kModality, "CS", listed.modality);
    r.text(tags::kSopClassUid, "UI", listed.sop_class_uid);
  } else {
    r.always(tags::kModality, "CS", h.series.modality);
    r.text(tags::kSopClassUid, "UI", h.series.sop_class_uid);
  }
  r.always(tags::kSopInstanceUid, "UI", uid);
  r.number(tags::kInstanceNumber, "IS", i.k + 1);
  if (!h.structure || h.object == db::StructureObject::kSeg) {  // an RT Structure Set has no pixels
    r.number(tags::kRows, "US", h.series.geometry.dims[1]);
    r.number(tags::kColumns, "US", h.series.geometry.dims[0]);
  }
  r.always(tags::kInstanceAvailability, "CS", h.structure ? "ONLINE" : "UNAVAILABLE");
  if (h.structure)
    r.always(tags::kRetrieveUrl, "UR",
             base_url + "/studies/" + h.study.study_uid + "/series/" + series_uid + "/instances/" + uid);
  return r.take();
}

}  // namespace soiq::server::http
