#include "server/app/upload_image.h"

#include <optional>

#include "core/io/image_decode_limits.h"
#include "db/image_blob.h"
#include "server/app/uploaded_files.h"

namespace soiq::server {

Result<UploadedImage> upload_image(db::RecordStore& store, MemoryBudget& budget, int64_t max_grid_voxels,
                                   const ImageUpload& upload, const std::string& bytes,
                                   const std::function<Status()>& stop) {
  // Held until the series is stored: the decoded voxels and the encoded blob live that long.
  std::optional<MemoryBudget::Reservation> held;
  ImageDecodeLimits limits;
  limits.max_voxels = max_grid_voxels;
  limits.before_decoding = [&](const ImageGeometry& g, int64_t decode_bytes) -> Status {
    const auto& d = g.dims;
    SOIQ_ASSIGN_OR_RETURN(MemoryBudget::Reservation r,
                          budget.reserve(decode_bytes + g.voxel_count() * int64_t(sizeof(float)),
                                         "image '" + upload.series_uid + "' of " + std::to_string(d[0]) + "x" +
                                             std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels",
                                         stop));
    held = std::move(r);
    return ok_status();
  };
  SOIQ_ASSIGN_OR_RETURN(Image image, parse_image(bytes, upload.format, upload.series_uid, limits));
  SOIQ_ASSIGN_OR_RETURN(db::EncodedImage encoded, db::encode_image(image));
  db::NewSeries s;
  s.patient = upload.patient;
  s.study = upload.study;
  s.series.series_uid = upload.series_uid;
  s.series.study_uid = upload.study.study_uid;
  s.series.modality = upload.modality;
  s.series.geometry = image.geometry;
  s.series.sha256 = encoded.sha256;
  s.image_blob = std::move(encoded.blob);
  UploadedImage out{s.series, false};
  if (stop) SOIQ_RETURN_IF_ERROR(stop());  // a client that gave up while this decoded gets nothing stored
  SOIQ_ASSIGN_OR_RETURN(out.replaced, store.put_series(std::move(s)));  // moved: the blob is not copied
  return out;
}

}  // namespace soiq::server
