#pragma once
// The random store of the stage-1 tests (store_stage1_test.cpp on every backend, the SQLite plans
// in sqlite_store_stage1_test.cpp): the structures it holds, as the brute-force oracle
// (stage1_oracle.h) sees them, and the values of each filter field worth trying.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "db/age_years.h"
#include "db/store.h"
#include "tests/db/stage1_oracle.h"
#include "tests/db/temp_store.h"

namespace soiq::db::testing {

inline std::string random_date(std::mt19937_64& rng, int from_year, int to_year) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04d%02d%02d", from_year + int(rng() % (to_year - from_year + 1)),
                1 + int(rng() % 12), 1 + int(rng() % 28));
  return buf;
}

template <typename T>
const T& pick(std::mt19937_64& rng, const std::vector<T>& v) {
  return v[rng() % v.size()];
}

inline const std::vector<std::string> kSexes = {"", "M", "F", "O"};
inline const std::vector<std::string> kModalities = {"", "MR", "CT", "PT"};
inline const std::vector<std::string> kDescriptions = {"", "Brain MRI", "brain MRI follow-up", "CT thorax",
                                                       "PET/CT [FDG]"};
inline const std::vector<std::string> kNames = {"Hippocampus", "hippocampus", "HIPPO_tail",
                                                "Amygdala",    "Insula",      "Tumour 1"};
inline const std::vector<std::string> kLateralities = {"", "L", "R"};

// One random store of the backend for the whole suite: building it is most of the time (a durable
// commit per write), and every test of the suite only reads. Suites derive from
// Stage1Store<Backend>; its statics are the backend's instantiation's, so each backend has its own.
template <typename Backend>
class Stage1Store : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    rows_ = new std::vector<Row>();
    patients_ = new std::set<std::string>();
    store_ = Backend::open(*dir_).release();
    ASSERT_NE(store_, nullptr);
    std::mt19937_64 rng(20240501);
    int surface = 0;
    for (int p = 0; p < 120; ++p) {
      PatientRecord patient;
      char id[16];
      std::snprintf(id, sizeof id, "%c%04d", "PQR"[p % 3], p);
      patient.patient_id = id;
      patient.sex = pick(rng, kSexes);
      patient.birth_date = rng() % 5 == 0 ? "" : random_date(rng, 1930, 1990);
      const int studies = 1 + int(rng() % 3);
      for (int s = 0; s < studies; ++s) {
        StudyRecord study;
        study.study_uid = std::string("1.2.") + std::to_string(p) + std::string(".") + std::to_string(s);
        study.study_date = rng() % 6 == 0 ? "" : random_date(rng, 1995, 2024);
        study.description = pick(rng, kDescriptions);
        study.modality = pick(rng, kModalities);
        if (rng() % 7 == 0) study.age_years = double(rng() % 900) / 10.0;
        std::set<std::string> series_modalities;
        const int series = int(rng() % 3);
        for (int se = 0; se < series; ++se) {
          NewSeries ns = testing::new_series(patient.patient_id, study.study_uid,
                                             study.study_uid + std::string(".") + std::to_string(se), float(se));
          ns.patient = patient;
          ns.study = study;
          ns.series.modality = pick(rng, std::vector<std::string>{"MR", "CT", "PT", "RTSTRUCT"});
          series_modalities.insert(ns.series.modality);
          ASSERT_TRUE(store_->put_series(ns).ok());
          patients_->insert(patient.patient_id);
        }
        StudyRecord expected = study;
        if (!expected.age_years) expected.age_years = *age_years(patient.birth_date, study.study_date);
        const int structures = int(rng() % 4);
        for (int k = 0; k < structures; ++k) {
          NewStructure ns = new_structure(patient.patient_id, study.study_uid, pick(rng, kNames), surface++ % 40);
          ns.patient = patient;
          ns.study = study;
          ns.laterality = pick(rng, kLateralities);
          auto added = store_->add_structure(ns);
          ASSERT_TRUE(added.ok()) << added.status().to_string();
          patients_->insert(patient.patient_id);
          Row row{added->structure.id, patient, expected, series_modalities, ns.name, ns.laterality, std::nullopt};
          // Two structures in three get precomputed values (some unknown, some NaN), right away,
          // so that the patient's later writes must carry them over into its stage-1 rows.
          if (rng() % 3 != 0) {
            Precomputed p;
            p.structure_id = row.id;
            p.surface_sha256 = added->structure.surface.sha256;
            p.definitions_version = 1;
            for (size_t v = 0; v < stored_feature_names().size(); ++v) {
              const uint64_t kind = rng() % 10;
              p.values.push_back(kind == 0   ? std::nullopt
                                 : kind == 1 ? std::optional<double>(std::nan(""))
                                             : std::optional<double>(double(rng() % 1000) / 10.0));
            }
            ASSERT_TRUE(store_->put_precomputed(p).ok());
            row.stored = p.values;
          }
          rows_->push_back(std::move(row));
        }
      }
    }
  }

  static void TearDownTestSuite() {
    delete store_;
    delete rows_;
    delete patients_;
    delete dir_;
    store_ = nullptr;
    rows_ = nullptr;
    patients_ = nullptr;
    dir_ = nullptr;
  }

  std::vector<int64_t> expected_ids(const Stage1Filter& f) const {
    std::vector<int64_t> ids;
    for (const Row& r : *rows_) {
      if (matches(r, f)) ids.push_back(r.id);
    }
    return ids;
  }

  void expect_same(const Stage1Filter& f, const std::string& label) {
    auto got = store_->stage1(f, 1'000'000);
    ASSERT_TRUE(got.ok()) << label << ": " << got.status().to_string();
    std::vector<int64_t> ids;
    for (const Candidate& c : *got) ids.push_back(c.structure.id);
    EXPECT_EQ(ids, expected_ids(f)) << label;
  }

  // A test of a suite whose store did not open (or whose building failed) has nothing to read.
  void SetUp() override { ASSERT_NE(store_, nullptr); }

  static inline TempDir* dir_ = nullptr;
  static inline Store* store_ = nullptr;
  static inline std::vector<Row>* rows_ = nullptr;           // in id order
  static inline std::set<std::string>* patients_ = nullptr;  // those with a structure or a series
};

// Values of each filter field worth trying, including ones that match nothing.
inline std::vector<std::pair<std::string, std::function<void(Stage1Filter&)>>> single_filters() {
  std::vector<std::pair<std::string, std::function<void(Stage1Filter&)>>> out;
  for (std::string g : {"P*", "Q00[0-4]*", "*7", "?0*1", "[^P]*", "R0012", "X*"}) {
    out.push_back({"patient glob " + g, [g](Stage1Filter& f) { f.patient_id_glob = g; }});
  }
  for (std::string s : {"M", "F", "O"}) out.push_back({"sex " + s, [s](Stage1Filter& f) { f.sex = s; }});
  out.push_back({"min age 50", [](Stage1Filter& f) { f.min_age_years = 50.0; }});
  out.push_back({"max age 40.5", [](Stage1Filter& f) { f.max_age_years = 40.5; }});
  out.push_back({"age 30..60", [](Stage1Filter& f) { f.min_age_years = 30.0, f.max_age_years = 60.0; }});
  out.push_back({"birth from", [](Stage1Filter& f) { f.birth_date_from = "19600101"; }});
  out.push_back({"birth to", [](Stage1Filter& f) { f.birth_date_to = "19551231"; }});
  out.push_back({"birth range", [](Stage1Filter& f) { f.birth_date_from = "19400615", f.birth_date_to = "19700615"; }});
  out.push_back({"study from", [](Stage1Filter& f) { f.study_date_from = "20150101"; }});
  out.push_back({"study to", [](Stage1Filter& f) { f.study_date_to = "20051231"; }});
  out.push_back({"study range", [](Stage1Filter& f) { f.study_date_from = "20000101", f.study_date_to = "20101231"; }});
  for (std::string m : {"MR", "CT", "PT", "RTSTRUCT", "US"}) {
    out.push_back({"modality " + m, [m](Stage1Filter& f) { f.modality = m; }});
  }
  for (std::string g : {"Brain*", "*MRI*", "*[[]FDG]", "brain*", "?T*"}) {
    out.push_back({"description glob " + g, [g](Stage1Filter& f) { f.study_description_glob = g; }});
  }
  for (std::string g : {"hippo*", "HIPPOCAMPUS", "*TAIL", "*a*a*", "[ai]*", "tumour ?"}) {
    out.push_back({"name glob " + g, [g](Stage1Filter& f) { f.structure_name_glob = g; }});
  }
  for (std::string l : {"L", "R"}) out.push_back({"laterality " + l, [l](Stage1Filter& f) { f.laterality = l; }});
  // Each stored feature with each operator (the values are tenths in [0, 100)).
  const std::vector<Comparison> ops = {Comparison::kLess,           Comparison::kLessOrEqual, Comparison::kGreater,
                                       Comparison::kGreaterOrEqual, Comparison::kEqual,       Comparison::kNotEqual};
  for (size_t i = 0; i < stored_feature_names().size(); ++i) {
    const std::string name = stored_feature_names()[i];
    const Comparison op = ops[i % ops.size()];
    const double value = op == Comparison::kEqual || op == Comparison::kNotEqual ? 42.5 : 20.0 + 10.0 * double(i);
    out.push_back({name + " " + comparison_symbol(op), [=](Stage1Filter& f) {
                     f.stored_features.push_back({name, op, value});
                   }});
  }
  return out;
}

}  // namespace soiq::db::testing
