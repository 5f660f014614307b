#pragma once
// Whether a value copied from a source series fits the VR of the object soiq writes (SEG, RT
// Structure Set). Both declare no Specific Character Set, so only the default repertoire (ASCII)
// fits and characters are bytes. A Type 2 value that does not fit is written empty ("unknown"):
// a truncated one would name something else, a copied one makes the object non-conformant (the
// STS CTs' 17-character Study ID "IBSI_1_STS_002_CT" where SH allows 16; dciodvfy: "Length invalid
// for this VR").

#include <string>

namespace soiq::dicom {

bool fits_date(const std::string& v);          // DA
bool fits_time(const std::string& v);          // TM
bool fits_short_string(const std::string& v);  // SH: <= 16 printable ASCII, no backslash
bool fits_long_string(const std::string& v);   // LO: <= 64, no backslash or control characters

// `value` when it fits, else "" (a Type 2 attribute's "unknown").
inline std::string type2_value(const std::string& value, bool fits) { return fits ? value : ""; }

}  // namespace soiq::dicom
