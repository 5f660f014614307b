#pragma once
// Stable DICOM UIDs for the objects soiq writes of one structure on demand, its SEG and its RT
// Structure Set (db/structure_object.h; DICOMweb lists each as a series of one instance,
// server/http/): the same structure with the same surface gets the same Series and SOP Instance
// UID of each object on every request and on every replica, the two objects' UIDs differ, and a
// UID says which structure and object it names without a lookup table.
//
// A UID is "2.25." and a UUID as a decimal integer (PS3.5 B.2), of RFC 9562's version 8 (custom):
// the object (1 bit: 0 the SEG, 1 the RT Structure Set) and the structure id (47 bits) in its
// first 48 bits, a bit telling series from instance, and 61 bits of the sha256 of the object, the
// structure's surface and its source series (so a structure whose surface changes gets new UIDs,
// and an old UID no longer resolves). A SEG's UIDs are those soiq gave it before RT Structure
// Sets were served (the object bit 0, the SEG's own salt).
//
// Inputs   structure: a stored structure (id in 1..2^47-1; a larger id gets UIDs no parse
//          accepts, so nothing resolves them); object: which of its objects.
// Output   structure_object_uids: both UIDs (at most 44 characters, within UI's 64).
//          parse_structure_object_uid: the structure id, object and kind a UID names, or nullopt
//          for a UID not of this form; the caller must compare it with structure_object_uids of
//          the structure it loads (the hash bits are checked there).
// Cost     one sha256 of ~150 bytes; no allocation beyond the strings.

#include <cstdint>
#include <optional>
#include <string>

#include "db/store.h"

namespace soiq::server {

struct StructureObjectUids {
  std::string series_uid;
  std::string sop_instance_uid;
};

StructureObjectUids structure_object_uids(const db::StructureRecord& structure, db::StructureObject object);

struct ParsedStructureUid {
  int64_t structure_id = 0;
  db::StructureObject object = db::StructureObject::kSeg;
  bool instance = false;  // the SOP Instance UID, else the Series UID
};
std::optional<ParsedStructureUid> parse_structure_object_uid(const std::string& uid);

}  // namespace soiq::server
