#pragma once
// Image names as people say them, in DICOM's words. A query, a grid or an upload names an image by
// its series uid or by its modality; people say "PET" where DICOM's Modality (0008,0060) code is
// "PT" (PS3.3 C.7.3.1.1.1), and a query for "PET" used to find nothing without a word.
//
// dicom_modality   "PET" (any case) -> "PT"; every other text unchanged. Applied once, where a
//                  request is decoded, so "PET" means PT everywhere (stage 1, images, grids,
//                  uploads) and rows and messages show "PT".
// same_modality    ASCII case-insensitive equality of two modality codes ("mr" is MR), the one
//                  comparison every lookup of an image by modality uses.
// is_series_uid    true for a DICOM UID (digits and dots, PS3.5 9.1), which names one series;
//                  false for a modality code.
// Cost O(length). Pure.

#include <string>

namespace soiq::server {

std::string dicom_modality(const std::string& name);

bool same_modality(const std::string& a, const std::string& b);

bool is_series_uid(const std::string& ref);

}  // namespace soiq::server
