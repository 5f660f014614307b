#pragma once
// The DICOM objects soiq writes of a structure on demand, each of which DICOMweb lists and serves
// as a series of one instance (record_store.h "DICOMweb's view"): its binary SEG
// (server/app/structure_seg.h) and its RT Structure Set (server/app/structure_rt_struct.h).
// The one place their Modality values are named, for the store's searches and the answers.
//
// Output   structure_object_modality: "SEG" or "RTSTRUCT". structure_object_of_modality: the
//          object a Modality names, nullopt for any other value (an image series' modality).
// Cost     constant; thread-safe.

#include <array>
#include <optional>
#include <string_view>

namespace soiq::db {

enum class StructureObject { kSeg, kRtStruct };

// In the order DICOMweb lists a structure's series: its SEG, then its RT Structure Set.
inline constexpr std::array<StructureObject, 2> kStructureObjects = {StructureObject::kSeg, StructureObject::kRtStruct};

constexpr const char* structure_object_modality(StructureObject o) {
  return o == StructureObject::kSeg ? "SEG" : "RTSTRUCT";
}

constexpr std::optional<StructureObject> structure_object_of_modality(std::string_view modality) {
  for (const StructureObject o : kStructureObjects)
    if (modality == structure_object_modality(o)) return o;
  return std::nullopt;
}

}  // namespace soiq::db
