#pragma once
// A DICOM instance's metadata as the DICOM JSON Model (PS3.18 F.2), for WADO-RS /metadata: every
// attribute of the dataset (DCMTK's JSON writer), the Pixel Data replaced by a BulkDataURI.
//
// Inputs   part10: a DICOM Part 10 file in memory (soiq's own SEG, dicom/seg_export.h).
//          bulk_data_uri: where Pixel Data can be had (WADO-RS bulkdata).
// Output   one JSON object, as text (DCMTK's compact form).
// Errors   INVALID_ARGUMENT when the bytes are not DICOM; INTERNAL when DCMTK cannot write JSON.
// Cost     one parse of the file; O(attributes) output. Thread-safe.

#include <string>

#include "core/base/status.h"

namespace soiq::dicom {

Result<std::string> dicom_json_metadata(const std::string& part10, const std::string& bulk_data_uri);

// Metadata kept with an instance (soiqd keeps the original instances of image series) is written
// once, at import, with this in place of the Pixel Data's BulkDataURI; with_bulk_data_uri puts the
// address the answer is served from in its place (it depends on the Host the client asked).
inline constexpr char kBulkDataUriPlaceholder[] = "soiq:bulkdata";
std::string with_bulk_data_uri(std::string metadata, const std::string& bulk_data_uri);

// The Pixel Data of a Part 10 file in memory, as it is stored (native bytes for soiq's SEGs).
Result<std::string> pixel_data_of(const std::string& part10);

}  // namespace soiq::dicom
