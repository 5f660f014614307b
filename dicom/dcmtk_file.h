#pragma once
// dicom/'s one adapter to DCMTK's dcmdata (STYLE.md 3): loading a file and reading typed values,
// with every OFCondition turned into a Status that names the file and keeps DCMTK's text.
// Internal to dicom/: the public headers never include DCMTK.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::dicom {

// True when the first bytes look like DICOM: "DICM" at offset 128 (Part 10 file), or, for a bare
// dataset without preamble and file meta header, a first tag of group 0002, 0004 or 0008 (either
// byte order) with a small element number. Files that fail this test are not DICOM at all (a
// README, a NIfTI); files that pass it and then fail to load are corrupt DICOM.
bool looks_like_dicom(const std::string& path);

// Loads `path` with or without preamble and file meta header (ERM_autoDetect, transfer syntax
// detected). `until_pixel_data` stops before (7FE0,0010) for a fast header read.
// Errors: NOT_FOUND when the file does not exist; DATA_LOSS when DCMTK cannot parse it (the
// message names the file and gives DCMTK's reason).
Result<std::unique_ptr<DcmFileFormat>> load_dicom_file(const std::string& path, bool until_pixel_data);

// A Part 10 file held in memory (an instance soiqd kept, a SEG it wrote), parsed whole.
// Errors: INVALID_ARGUMENT with DCMTK's reason when the bytes are not DICOM.
Result<std::unique_ptr<DcmFileFormat>> parse_part10(const std::string& part10);

// The value at `pos` with padding trimmed; "" when absent or empty.
std::string get_string(DcmItem& item, const DcmTagKey& tag, unsigned long pos = 0);
// All values joined by '\\'; "" when absent.
std::string get_string_array(DcmItem& item, const DcmTagKey& tag);
// A DS/FL/FD/IS value at `pos` as double; nullopt when absent, empty or not a number.
std::optional<double> get_number(DcmItem& item, const DcmTagKey& tag, unsigned long pos = 0);
// `count` numbers, or nullopt unless all are present.
std::optional<std::vector<double>> get_numbers(DcmItem& item, const DcmTagKey& tag, unsigned long count);

// "'<path>': <what> (<DCMTK's text>)" as a Status with `code`.
Status condition_status(StatusCode code, const std::string& path, const std::string& what, const OFCondition& cond);

// `file` as Part 10 bytes in Explicit VR Little Endian (what soiq writes and sends); INTERNAL with
// DCMTK's words when it cannot encode it.
Result<std::string> part10_bytes(DcmFileFormat& file);

}  // namespace soiq::dicom
