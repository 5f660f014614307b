#pragma once
// The frames of a DICOM instance as WADO-RS /frames sends them: each frame's pixel data
// uncompressed, little endian, in the instance's own Bits Allocated, Samples per Pixel and
// Planar Configuration (PS3.18 8.7.3.5.4, the "native" bulk data of PS3.5 A.1), so a viewer that
// asks for any transfer syntax gets the values pydicom decodes from the original file.
//
// Inputs   part10: a Part 10 file in memory (an original instance soiqd kept).
//          frames: 1-based frame numbers, in the order they are wanted (repeats allowed); empty
//          for all of them.
// Output   the frames' bytes, one string each, in the order asked. Compressed pixel data (JPEG,
//          JPEG-LS, RLE) is decoded first (decompress_pixels.h).
// Errors   INVALID_ARGUMENT when the bytes are not DICOM; NOT_FOUND for a frame number of 0 or
//          over Number of Frames (the message gives the count), or an instance without Pixel Data;
//          UNIMPLEMENTED for Bits Allocated 1 (a binary SEG's frames are not byte-aligned: retrieve
//          the instance) or a decoder soiq lacks; DATA_LOSS when Pixel Data is shorter than its
//          frames need or decoding fails.
// Cost     one parse of the file, O(pixels) when it must be decoded; thread-safe.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::dicom {

Result<std::vector<std::string>> instance_frames(const std::string& part10, std::vector<int64_t> frames);

}  // namespace soiq::dicom
