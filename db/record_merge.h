#pragma once
// How a write merges what it is given into what is stored, the same in every backend: a given
// field overwrites the stored one unless it is empty, and an age that was given once is kept over
// one the store would compute (age_years.h).

#include <optional>
#include <string>

#include "core/base/status.h"

namespace soiq::db {

inline const std::string& merged(const std::string& given, const std::string& stored) {
  return given.empty() ? stored : given;
}

// The age to store for a study: the given one, else one given before, else computed from the
// patient's birth date and the study date (nullopt when either is unknown).
Result<std::optional<double>> study_age(const std::optional<double>& given, const std::optional<double>& stored_given,
                                        const std::string& birth_date, const std::string& study_date);

}  // namespace soiq::db
