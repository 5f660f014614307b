// QIDO-RS results as the DICOM JSON Model (server/http/qido_json.h): values, empty attributes, person
// name groups, what includefield adds, what an image series (no DICOM kept) says of itself, and a
// structure's SEG and RT Structure Set series and instances.
#include "server/http/qido_json.h"

#include <gtest/gtest.h>

namespace soiq::server::http {
namespace {

using nlohmann::json;

db::StudyHit study(const std::string& name) {
  db::StudyHit h;
  h.study.study_uid = "1.2";
  h.study.study_date = "20200102";
  h.study.age_years = 61.7;
  h.patient.patient_id = "P1";
  h.patient.patient_name = name;
  h.modalities = {"CT", "SEG"};
  h.series_count = 2;
  h.instance_count = 49;
  return h;
}

TEST(QidoJson, AStudyWithItsDefaultsAndNoValueWhereThereIsNone) {
  const json j = study_json(study("Doe^John"), "http://h/dicom-web", QidoQuery{});
  EXPECT_EQ(j["0020000D"], json({{"vr", "UI"}, {"Value", {"1.2"}}}));
  EXPECT_EQ(j["00100010"], json({{"vr", "PN"}, {"Value", {{{"Alphabetic", "Doe^John"}}}}}));
  EXPECT_EQ(j["00080061"]["Value"], json({"CT", "SEG"}));
  EXPECT_EQ(j["00201208"]["Value"], json({49}));   // IS as a number
  EXPECT_EQ(j["00080050"], json({{"vr", "SH"}}));  // Type 2, empty: no "Value"
  EXPECT_EQ(j["00081190"]["Value"][0], "http://h/dicom-web/studies/1.2");
  EXPECT_FALSE(j.contains("00101010"));  // PatientAge: asked for only
  QidoQuery all;
  all.include_all = true;
  EXPECT_EQ(study_json(study(""), "", all)["00101010"]["Value"][0], "061Y");
}

TEST(QidoJson, PersonNameGroupsAndEmptyNames) {
  const json j = study_json(
      study("Yamada^Tarou=\xE5\xB1\xB1\xE7\x94\xB0^\xE5\xA4\xAA\xE9\x83\x8E=\xE3\x82\x84\xE3\x81\xBE\xE3\x81\xA0"), "",
      {});
  const json& pn = j["00100010"]["Value"][0];
  EXPECT_EQ(pn["Alphabetic"], "Yamada^Tarou");
  EXPECT_EQ(pn["Ideographic"], "\xE5\xB1\xB1\xE7\x94\xB0^\xE5\xA4\xAA\xE9\x83\x8E");
  EXPECT_EQ(pn["Phonetic"], "\xE3\x82\x84\xE3\x81\xBE\xE3\x81\xA0");
  EXPECT_EQ(study_json(study(""), "", {})["00100010"], json({{"vr", "PN"}}));
}

TEST(QidoJson, ImageSeriesAreUnavailableAndStructuresAreSegs) {
  db::SeriesHit image;
  image.study.study_uid = "1.2";
  image.series.series_uid = "1.2.3";
  image.series.modality = "CT";
  image.series.slice_instance_uids = {"1.2.3.1", "1.2.3.2"};
  image.series.series_number = 4;
  const json i = series_json(image, "http://h/dicom-web", {});
  EXPECT_EQ(i["00080056"]["Value"][0], "UNAVAILABLE");
  EXPECT_FALSE(i.contains("00081190"));  // nothing to retrieve
  EXPECT_EQ(i["00201209"]["Value"][0], 2);
  EXPECT_EQ(i["00200011"]["Value"][0], 4);
  db::SeriesHit seg = image;
  seg.structure = db::StructureRecord{};
  seg.structure->id = 5;
  seg.structure->name = "GTV";
  const json s = series_json(seg, "http://h/dicom-web", {});
  EXPECT_EQ(s["00080060"]["Value"][0], "SEG");
  EXPECT_EQ(s["00201209"]["Value"][0], 1);
  EXPECT_EQ(s["00080056"]["Value"][0], "ONLINE");
  EXPECT_EQ(s["0020000E"]["Value"][0], series_uid_of(seg));
  EXPECT_EQ(s["00081190"]["Value"][0], "http://h/dicom-web/studies/1.2/series/" + series_uid_of(seg));
}

TEST(QidoJson, AStructuresRtStructureSetIsItsOwnSeriesAndInstance) {
  db::SeriesHit seg;
  seg.study.study_uid = "1.2";
  seg.series.series_uid = "1.2.3";
  seg.series.geometry.dims = {4, 3, 2};
  seg.structure = db::StructureRecord{};
  seg.structure->id = 5;
  seg.structure->name = "GTV";
  db::SeriesHit rt = seg;
  rt.object = db::StructureObject::kRtStruct;
  QidoQuery all;
  all.include_all = true;  // SeriesDescription too
  const json s = series_json(rt, "http://h/dicom-web", all);
  EXPECT_EQ(s["00080060"]["Value"][0], "RTSTRUCT");
  EXPECT_EQ(s["0008103E"]["Value"][0], "GTV");
  EXPECT_EQ(s["00200011"]["Value"][0], 901);
  EXPECT_EQ(s["00201209"]["Value"][0], 1);
  EXPECT_EQ(s["00080056"]["Value"][0], "ONLINE");
  EXPECT_NE(series_uid_of(rt), series_uid_of(seg));
  EXPECT_EQ(s["0020000E"]["Value"][0], series_uid_of(rt));
  EXPECT_EQ(s["00081190"]["Value"][0], "http://h/dicom-web/studies/1.2/series/" + series_uid_of(rt));

  const json ri = instance_json({&rt, 0}, "http://h/dicom-web", {});
  EXPECT_EQ(ri["00080060"]["Value"][0], "RTSTRUCT");
  EXPECT_EQ(ri["00080016"]["Value"][0], "1.2.840.10008.5.1.4.1.1.481.3");
  EXPECT_EQ(ri["00080018"]["Value"][0], instance_uid_of({&rt, 0}));
  EXPECT_FALSE(ri.contains("00280010"));  // no Rows: an RT Structure Set has no pixels
  const json si = instance_json({&seg, 0}, "http://h/dicom-web", {});
  EXPECT_EQ(si["00080016"]["Value"][0], "1.2.840.10008.5.1.4.1.1.66.4");
  EXPECT_EQ(si["00280010"]["Value"][0], 3);
  EXPECT_NE(instance_uid_of({&rt, 0}), instance_uid_of({&seg, 0}));
}

}  // namespace
}  // namespace soiq::server::http
