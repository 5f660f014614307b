#include "server/app/image_refs_check.h"

#include <algorithm>
#include <cctype>

#include "core/base/did_you_mean.h"
#include "server/app/modality_names.h"

namespace soiq::server {
namespace {

bool same_ignoring_case(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](unsigned char x, unsigned char y) {
           return std::toupper(x) == std::toupper(y);
         });
}

std::string held(const std::vector<std::string>& modalities) {
  if (modalities.empty()) return "it holds no image series yet (soiq upload-image, soiq import)";
  std::string out = "it holds ";
  for (size_t i = 0; i < modalities.size(); ++i) out += (i ? ", " : "") + modalities[i];
  return out;
}

}  // namespace

Status check_image_refs(db::Store& store, const std::vector<std::string>& refs) {
  std::vector<std::string> modalities;
  bool counted = false;
  for (const std::string& ref : refs) {
    if (is_series_uid(ref)) {
      Result<db::SeriesRecord> series = store.get_series(ref);
      if (series.status().code() == StatusCode::kNotFound)
        return not_found("no image series '" + ref + "' in this soiqd (soiq show study UID lists a study's series)");
      SOIQ_RETURN_IF_ERROR(series.status());
      continue;
    }
    if (!counted) {
      SOIQ_ASSIGN_OR_RETURN(db::Counts counts, store.counts());
      modalities = std::move(counts.series_modalities);
      counted = true;
    }
    const bool found = std::any_of(modalities.begin(), modalities.end(),
                                   [&](const std::string& m) { return same_ignoring_case(m, ref); });
    if (!found) {
      const std::string alias = same_ignoring_case(ref, "PT") ? " (PET's DICOM code)" : "";
      return not_found("no image in this soiqd has modality '" + ref + "'" + alias + "; " + held(modalities) +
                       did_you_mean(ref, modalities));
    }
  }
  return ok_status();
}

}  // namespace soiq::server
