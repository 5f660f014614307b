#include "server/app/kept_instances.h"

#include <map>
#include <set>

#include "core/io/read_file_bytes.h"
#include "db/surface_blob.h"
#include "dicom/dicom_json_metadata.h"
#include "dicom/import_dicom.h"

namespace soiq::server {

Result<std::vector<db::NewInstance>> kept_instances(const dicom::DicomSeries& series,
                                                    const std::vector<std::string>& slice_uids) {
  std::map<std::string, int64_t> slice_of;
  for (size_t k = 0; k < slice_uids.size(); ++k) slice_of.emplace(slice_uids[k], int64_t(k));
  std::vector<db::NewInstance> out;
  std::set<std::string> taken;
  for (const dicom::DicomInstance& file : series.instances) {
    const auto slice = slice_of.find(file.sop_instance_uid);
    // A file that holds no slice of the image (a duplicate left out by the reader) is not served.
    if (slice == slice_of.end() || !taken.insert(file.sop_instance_uid).second) continue;
    db::NewInstance i;
    SOIQ_ASSIGN_OR_RETURN(i.file, read_file_bytes(file.path, "DICOM file"));
    Result<std::string> metadata = dicom::dicom_json_metadata(i.file, dicom::kBulkDataUriPlaceholder);
    if (!metadata.ok())
      return invalid_argument("'" + file.path + "' could not be read again to keep it: " + metadata.status().message());
    i.record.sop_instance_uid = file.sop_instance_uid;
    i.record.series_uid = series.series_uid;
    i.record.slice = slice->second;
    i.record.file_sha256 = db::sha256_hex(i.file.data(), i.file.size());
    i.record.file_bytes = int64_t(i.file.size());
    i.record.metadata = std::move(metadata).value();
    out.push_back(std::move(i));
  }
  return out;
}

int64_t kept_instance_bytes(const dicom::DicomScan& scan) {
  // Each file is held as read, and once more while the store binds it (SQLite copies a bound blob);
  // its metadata is a few kilobytes, a CT's about 4.
  constexpr int64_t kMetadataBytes = 16 << 10;
  int64_t bytes = 0;
  for (const dicom::DicomSeries& series : scan.series) {
    if (!dicom::is_volume_modality(series.modality)) continue;
    for (const dicom::DicomInstance& file : series.instances) {
      const Result<int64_t> size = input_file_size(file.path, "DICOM file");
      if (size.ok()) bytes += 2 * *size + kMetadataBytes;
    }
  }
  return bytes;
}

}  // namespace soiq::server
