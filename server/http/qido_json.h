#pragma once
// QIDO-RS results as the DICOM JSON Model (PS3.18 F.2): one object per study, series or instance,
// keyed by tag ("0020000D": {"vr": "UI", "Value": [...]}); an attribute without a value has no
// "Value"; person names as {"Alphabetic": ...} (with Ideographic and Phonetic when the name has
// '=' groups); IS and US as numbers. Text is UTF-8 (SpecificCharacterSet ISO_IR 192); bytes that
// are not become U+FFFD when serialised (nlohmann's replace handler), so an old record stored raw
// never breaks the answer.
//
// Inputs   hits from the store's searches; base_url: "http://host:port/dicom-web" for RetrieveURL;
//          the query's includefield choice.
// Output   what the query's level returns by default (dicomweb_attributes.h), plus what was asked
//          for; series results also carry StudyInstanceUID and PatientID, instance results the
//          Study and Series UIDs and the Modality.
//          A structure's SEG and RT Structure Set series are Modality SEG and RTSTRUCT with their
//          stable UIDs (structure_object_uids.h), SOP class, number and description as written
//          (server/app/structure_object.h); an image series, whose DICOM instances soiq does not
//          keep, has InstanceAvailability UNAVAILABLE and no RetrieveURL.
// Cost     linear in the hits; thread-safe.

#include <nlohmann/json.hpp>
#include <string>

#include "db/store.h"
#include "server/http/qido_query.h"

namespace soiq::server::http {

nlohmann::json study_json(const db::StudyHit& h, const std::string& base_url, const QidoQuery& q);
nlohmann::json series_json(const db::SeriesHit& h, const std::string& base_url, const QidoQuery& q);

// One instance of a series: an image series' slice k (0-based), or a structure's object (k = 0).
struct InstanceRef {
  const db::SeriesHit* series = nullptr;
  int64_t k = 0;
};
nlohmann::json instance_json(const InstanceRef& i, const std::string& base_url, const QidoQuery& q);

// The series' and its instances' UIDs as DICOMweb gives them (the object's stable ones for a
// structure).
std::string series_uid_of(const db::SeriesHit& h);
std::string instance_uid_of(const InstanceRef& i);
int64_t instance_count_of(const db::SeriesHit& h);

}  // namespace soiq::server::http
