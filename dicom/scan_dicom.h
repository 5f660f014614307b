#pragma once
// Finds the DICOM data under some paths and indexes it by patient, study and series (docs/DESIGN.md
// "DICOM and PACS"). Reads headers only (stops before Pixel Data).
//
// Inputs   paths: files, folders (walked recursively, symlinks followed, in sorted order) and
//          DICOMDIRs. A DICOMDIR (a file with a Directory Record Sequence, any transfer syntax,
//          records in any order) contributes the files its records reference (Referenced File ID,
//          resolved against the DICOMDIR's folder); the File-set descriptor file it may name is
//          ignored. A file met twice (through a folder and a DICOMDIR) is read once.
//          DICOM files are read with or without preamble and file meta header.
// Output   DicomScan (dicom/records.h): one record per patient, study and series, fields taken
//          from the first instance that has them non-empty; study.age_years from Patient's Age or
//          birth and study dates (dicom/age_at_study.h); each instance with its Rows and Columns,
//          so that what decoding it will take is known without reading a pixel. Files that do not
//          look like DICOM (dicom/dcmtk_file.h looks_like_dicom) are counted in non_dicom_skipped.
//          A DICOM file that fails to load, has no SOP Instance / Series / Study UID, or a DICOMDIR
//          reference to a missing file goes to `unreadable` with a Status naming the file
//          (DATA_LOSS for parse errors, INVALID_ARGUMENT for missing UIDs, NOT_FOUND for missing
//          references); the scan goes on.
// Errors   NOT_FOUND when a given path does not exist. Nothing else stops a scan.
// Cost     O(files) header reads; not thread-safe with respect to the files changing meanwhile.

#include <string>
#include <vector>

#include "core/base/status.h"
#include "dicom/records.h"

namespace soiq::dicom {

Result<DicomScan> scan_dicom(const std::vector<std::string>& paths);

}  // namespace soiq::dicom
