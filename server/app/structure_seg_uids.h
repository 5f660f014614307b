#pragma once
// Stable DICOM UIDs for the SEG soiq writes of one structure on demand (DICOMweb lists it as a
// series of one instance, server/http/): the same structure with the same surface gets the same
// Series and SOP Instance UID on every request and on every replica, and a UID says which
// structure it names without a lookup table.
//
// A UID is "2.25." and a UUID as a decimal integer (PS3.5 B.2), of RFC 9562's version 8 (custom):
// the structure id in its first 48 bits, a bit telling series from instance, and 61 bits of the
// sha256 of the structure's surface and source series (so a structure whose surface changes gets
// new UIDs, and an old UID no longer resolves).
//
// Inputs   structure: a stored structure (id in 1..2^48-1).
// Output   structure_seg_uids: both UIDs (at most 44 characters, within UI's 64).
//          parse_structure_seg_uid: the structure id and kind a UID names, or nullopt for a UID not
//          of this form; the caller must compare it with structure_seg_uids of the structure it
//          loads (the hash bits are checked there).
// Cost     one sha256 of ~150 bytes; no allocation beyond the strings.

#include <cstdint>
#include <optional>
#include <string>

#include "db/store.h"

namespace soiq::server {

struct StructureSegUids {
  std::string series_uid;
  std::string sop_instance_uid;
};

StructureSegUids structure_seg_uids(const db::StructureRecord& structure);

struct ParsedSegUid {
  int64_t structure_id = 0;
  bool instance = false;  // the SOP Instance UID, else the Series UID
};
std::optional<ParsedSegUid> parse_structure_seg_uid(const std::string& uid);

}  // namespace soiq::server
