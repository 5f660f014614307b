#include "server/app/image_refs_check.h"

#include <algorithm>
#include <cctype>

#include "core/base/did_you_mean.h"
#include "server/app/modality_names.h"

namespace soiq::server {
namespace {

std::string held(const std::vector<std::string>& modalities) {
  if (modalities.empty()) return "it holds no image series yet (soiq upload-image, soiq import)";
  std::string out = "it holds ";
  for (size_t i = 0; i < modalities.size(); ++i) out += (i ? ", " : "") + modalities[i];
  return out;
}

}  // namespace

Result<bool> ImageRefsCheck::known(db::RecordStore& store, const std::string& modality, bool fresh) {
  if (fresh) {
    SOIQ_ASSIGN_OR_RETURN(db::Counts counts, store.counts());
    std::lock_guard<std::mutex> lock(mutex_);
    modalities_ = std::move(counts.series_modalities);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  return std::any_of(modalities_.begin(), modalities_.end(),
                     [&](const std::string& m) { return same_modality(m, modality); });
}

Status ImageRefsCheck::check(db::RecordStore& store, const std::vector<std::string>& refs) {
  for (const std::string& ref : refs) {
    if (is_series_uid(ref)) {
      Result<db::SeriesRecord> series = store.get_series(ref);
      if (series.status().code() == StatusCode::kNotFound)
        return not_found("no image series '" + ref + "' in this soiqd (soiq show study UID lists a study's series)");
      SOIQ_RETURN_IF_ERROR(series.status());
      continue;
    }
    SOIQ_ASSIGN_OR_RETURN(const bool seen, known(store, ref, false));
    if (seen) continue;
    SOIQ_ASSIGN_OR_RETURN(const bool found, known(store, ref, true));
    if (!found) {
      const std::string alias = same_modality(ref, "PT") ? " (PET's DICOM code)" : "";
      std::lock_guard<std::mutex> lock(mutex_);
      return not_found("no image in this soiqd has modality '" + ref + "'" + alias + "; " + held(modalities_) +
                       did_you_mean(ref, modalities_));
    }
  }
  return ok_status();
}

}  // namespace soiq::server
