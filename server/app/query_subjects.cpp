#include "server/app/query_subjects.h"

#include "core/features/asymmetry_index.h"

namespace soiq::server::query_run {

const std::vector<double>* asked_value(size_t f, const Subject& s) {
  if (!s.ready || !s.error.ok() || f >= s.asked.size()) return nullptr;
  return s.asked[f];
}

std::optional<double> candidate_scalar(size_t f, bool asymmetry, const Subject& own, const Subject* twin) {
  const std::vector<double>* v = asked_value(f, own);
  if (v == nullptr || v->size() != 1) return std::nullopt;
  if (!asymmetry) return (*v)[0];
  const std::vector<double>* t = twin != nullptr ? asked_value(f, *twin) : nullptr;
  if (t == nullptr || t->size() != 1) return std::nullopt;
  // The index is of the left structure's value against the right's, whichever is the candidate.
  const bool left = own.structure.laterality == "L";
  Result<double> a = left ? asymmetry_index((*v)[0], (*t)[0]) : asymmetry_index((*t)[0], (*v)[0]);
  if (!a.ok()) return std::nullopt;
  return *a;
}

std::optional<std::vector<double>> candidate_value(size_t f, bool asymmetry, const Subject& own, const Subject* twin) {
  if (asymmetry) {
    const std::optional<double> a = candidate_scalar(f, asymmetry, own, twin);
    if (!a) return std::nullopt;
    return std::vector<double>{*a};
  }
  const std::vector<double>* v = asked_value(f, own);
  if (v == nullptr) return std::nullopt;
  return *v;
}

}  // namespace soiq::server::query_run
