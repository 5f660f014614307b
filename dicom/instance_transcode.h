#pragma once
// An original instance in the transfer syntax a WADO-RS client asks for: as it was received when
// it asks for that syntax or any, else in Explicit VR Little Endian (PS3.18's default for
// application/dicom), decoded when it was compressed. soiq encodes no compressed syntax.
//
// transfer_syntax_of        the Transfer Syntax UID (0002,0010) of the file's meta header;
//                           INVALID_ARGUMENT when the bytes are not DICOM or have no meta header.
// as_explicit_little_endian the same dataset in Explicit VR Little Endian, as Part 10 bytes with
//                           a new meta header; the file itself when it is in it already. Errors of
//                           decompress_pixels.h (UNIMPLEMENTED, DATA_LOSS) for compressed pixels.
// Cost     one parse (and decode, and write) of the file; thread-safe.

#include <string>

#include "core/base/status.h"

namespace soiq::dicom {

inline constexpr char kExplicitVrLittleEndianUid[] = "1.2.840.10008.1.2.1";

Result<std::string> transfer_syntax_of(const std::string& part10);

Result<std::string> as_explicit_little_endian(std::string part10);

}  // namespace soiq::dicom
