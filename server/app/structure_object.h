#pragma once
// One of a structure's DICOM objects as DICOMweb lists and serves it (db/structure_object.h): its
// binary SEG or its RT Structure Set, written on demand with the stable UIDs of
// structure_object_uids.h and the structure's creation time, so the same structure and surface
// give the same object on every request and QIDO-RS lists exactly what WADO-RS returns.
//
// find_structure_object
//   Inputs   study_uid, series_uid from a DICOMweb path; instance_uid "" or the instance asked.
//   Output   the structure and object the UIDs name; nullopt for a series UID not of soiq's form
//            (an image series' own UID, or an instance UID given as a series).
//   Errors   NOT_FOUND naming the series (or instance) for a structure that is not stored, not in
//            that study, or whose surface changed since the UID was listed (the message says to
//            query the study's series again); the store's errors.
// structure_object_listing
//   Output   what QIDO-RS says of the object's series and instance: Modality, SOP Class UID,
//            Series Number and Series Description (the structure's name when it is a valid LO, else
//            the writer's default), as the written object carries them.
// write_structure_object
//   Output   the object's Part 10 bytes and their share of the memory budget (held until the
//            answer holding them is written).
//   Errors   as structure_seg.h or structure_rt_struct.h for one structure (e.g.
//            FAILED_PRECONDITION for an RT Structure Set of a structure that meets no slice
//            plane); `stop` ends a wait for the budget.
// Cost     find: one store read; write: one conversion (SEG) or one set of cuts (RT Structure
//          Set). Thread-safe as Store, FeatureEngine and MemoryBudget are.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"
#include "server/app/memory_budget.h"

namespace soiq::server {

struct StructureObjectRef {
  db::StructureRecord structure;
  db::StructureObject object = db::StructureObject::kSeg;
};

Result<std::optional<StructureObjectRef>> find_structure_object(db::Store& store, const std::string& study_uid,
                                                                const std::string& series_uid,
                                                                const std::string& instance_uid);

struct StructureObjectListing {
  std::string modality;  // "SEG", "RTSTRUCT"
  std::string sop_class_uid;
  int32_t series_number = 0;
  std::string series_description;
};

StructureObjectListing structure_object_listing(const db::StructureRecord& structure, db::StructureObject object);

struct WrittenStructureObject {
  std::string bytes;  // the Part 10 file
  MemoryBudget::Reservation held;
};

Result<WrittenStructureObject> write_structure_object(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                                      const StructureObjectRef& ref,
                                                      const std::function<Status()>& stop = {});

}  // namespace soiq::server
