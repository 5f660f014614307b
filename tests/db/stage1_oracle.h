#pragma once
// The brute-force oracle of the stage-1 tests: which structures a Stage1Filter must select, decided
// in C++ row by row, independently of the store's SQL.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "db/store.h"

namespace soiq::db::testing {

// SQLite's GLOB, written independently: * any run, ? one byte, [...] a set with ranges and ^ for
// negation, a ']' first in the set is literal. (ASCII data only, so bytes are characters.)
inline bool glob_match(const char* p, const char* s) {
  for (; *p != '\0'; ++p, ++s) {
    if (*p == '*') {
      while (p[1] == '*') ++p;
      for (const char* t = s;; ++t) {
        if (glob_match(p + 1, t)) return true;
        if (*t == '\0') return false;
      }
    }
    if (*s == '\0') return false;
    if (*p == '?') continue;
    if (*p == '[') {
      const char* q = p + 1;
      const bool negate = *q == '^';
      if (negate) ++q;
      bool found = false;
      bool first = true;
      for (; *q != '\0' && (first || *q != ']'); ++q, first = false) {
        if (q[1] == '-' && q[2] != ']' && q[2] != '\0') {
          found = found || (*s >= q[0] && *s <= q[2]);
          q += 2;
        } else {
          found = found || *s == *q;
        }
      }
      if (*q != ']' || found == negate) return false;
      p = q;
      continue;
    }
    if (*p != *s) return false;
  }
  return *s == '\0';
}

inline std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

struct Row {
  int64_t id;
  PatientRecord patient;
  StudyRecord study;  // age_years as the store should have it
  std::set<std::string> series_modalities;
  std::string name, laterality;
  // The precomputed values stored for it (by stored_feature_names()), if any.
  std::optional<std::vector<std::optional<double>>> stored;
};

// `value op threshold` as stage 2 compares (server/app/query.h): NaN and unknown never hold.
// Written out here rather than calling soiq::compare: the oracle stays independent of the code under test.
inline bool holds(const std::optional<double>& value, Comparison op, double threshold) {
  if (!value || std::isnan(*value)) return false;
  const double v = *value;
  if (op == Comparison::kLess) return v < threshold;
  if (op == Comparison::kLessOrEqual) return v <= threshold;
  if (op == Comparison::kGreater) return v > threshold;
  if (op == Comparison::kGreaterOrEqual) return v >= threshold;
  if (op == Comparison::kEqual) return v == threshold;
  return v != threshold;
}

inline bool matches(const Row& r, const Stage1Filter& f) {
  const auto in_range = [](const std::string& v, const std::string& from, const std::string& to) {
    if (from.empty() && to.empty()) return true;
    return !v.empty() && (from.empty() || v >= from) && (to.empty() || v <= to);
  };
  if (!f.patient_id_glob.empty() && !glob_match(f.patient_id_glob.c_str(), r.patient.patient_id.c_str())) return false;
  if (!f.sex.empty() && r.patient.sex != f.sex) return false;
  if (f.min_age_years && !(r.study.age_years && *r.study.age_years >= *f.min_age_years)) return false;
  if (f.max_age_years && !(r.study.age_years && *r.study.age_years <= *f.max_age_years)) return false;
  if (!in_range(r.patient.birth_date, f.birth_date_from, f.birth_date_to)) return false;
  if (!in_range(r.study.study_date, f.study_date_from, f.study_date_to)) return false;
  if (!f.modality.empty() && r.study.modality != f.modality && !r.series_modalities.count(f.modality)) return false;
  if (!f.study_description_glob.empty() && !glob_match(f.study_description_glob.c_str(), r.study.description.c_str())) {
    return false;
  }
  if (!f.structure_name_glob.empty() && !glob_match(lower(f.structure_name_glob).c_str(), lower(r.name).c_str())) {
    return false;
  }
  if (!f.laterality.empty() && r.laterality != f.laterality) return false;
  // Stored-feature conditions apply only where values are stored; the others pass, for stage 2.
  if (!r.stored) return true;
  const std::vector<std::string>& names = stored_feature_names();
  for (const StoredFeatureCondition& c : f.stored_features) {
    const size_t i = size_t(std::find(names.begin(), names.end(), c.name) - names.begin());
    if (!holds(r.stored->at(i), c.op, c.value)) return false;
  }
  return true;
}

}  // namespace soiq::db::testing
