#pragma once
// The peak bytes an ImportDicom or a PacsPull will hold for its images, from the files' headers
// alone (dicom::scan_dicom reads no pixel), so that soiqd admits the import against its memory
// budget (server/app/memory_budget.h) before a voxel is decoded.
//
// Inputs   scan: the header-only scan of the files. max_voxels: the per-image limit; a series
//          over it is refused by read_image_series before its pixels are decoded, so costs nothing.
// Output   Summed over the CT, MR and PT series (those import_dicom decodes), each of columns x
//          rows x slices voxels (its first instance's Columns and Rows, one slice per instance;
//          read_image_series refuses a slice of another size before decoding it):
//          - 4 bytes per voxel for the float volume, kept until the import's write;
//          - 4 for the per-slice floats read_image_series gathers before assembling the volume;
//          - 4 for the compressed blob stored (deflate's bound is within 0.1% of the raw floats,
//            and SQLite copies a blob when binding it), as UploadImage counts decoding, volume
//            and blob;
//          - one slice's Pixel Data as DCMTK holds it, at most 4 bytes per pixel.
//          Every series is held until the one write transaction, so the sum is what the import
//          holds at its peak. A series without Rows or Columns counts nothing (it is refused).
//          `what` names the series for messages: "importing series <uid> (161x143x48)", or
//          "importing 2 series (<uid> 161x143x48, <uid> 30x27x48)" (the first 3, then "and N more").
// Errors   none; bytes saturate at INT64_MAX rather than overflow.
// Cost     O(series); thread-safe.
// Caveats  Structures (RT Structure Set and SEG volumes, their surfaces) are not counted: they
//          are bounded by the series' grids and the per-grid voxel limit, not by the images.

#include <cstdint>
#include <string>

#include "dicom/records.h"

namespace soiq::server {

struct DicomImportBytes {
  int64_t bytes = 0;
  int series = 0;  // the series counted
  std::string what;
};

DicomImportBytes dicom_import_bytes(const dicom::DicomScan& scan, int64_t max_voxels);

}  // namespace soiq::server
