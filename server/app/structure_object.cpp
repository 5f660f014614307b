#include "server/app/structure_object.h"

#include "server/app/structure_object_uids.h"
#include "server/app/structure_rt_struct.h"
#include "server/app/structure_seg.h"

namespace soiq::server {
namespace {

constexpr char kSegmentationStorage[] = "1.2.840.10008.5.1.4.1.1.66.4";
constexpr char kRtStructureSetStorage[] = "1.2.840.10008.5.1.4.1.1.481.3";

}  // namespace

Result<std::optional<StructureObjectRef>> find_structure_object(db::Store& store, const std::string& study_uid,
                                                                const std::string& series_uid,
                                                                const std::string& instance_uid) {
  const std::optional<ParsedStructureUid> parsed = parse_structure_object_uid(series_uid);
  if (!parsed || parsed->instance) return std::optional<StructureObjectRef>();
  Result<db::StructureRecord> s = store.get_structure(parsed->structure_id);
  if (!s.ok() && s.status().code() != StatusCode::kNotFound) return s.status();
  // The hash bits tell the structure's current surface (and each object) apart: compare whole UIDs.
  const std::optional<StructureObjectUids> uids =
      s.ok() ? std::optional(structure_object_uids(*s, parsed->object)) : std::nullopt;
  if (!uids || s->study_uid != study_uid || uids->series_uid != series_uid)
    return not_found("series '" + series_uid + "' not found in study '" + study_uid +
                     "' (a structure whose surface changed has new UIDs: query the study's series again)");
  if (!instance_uid.empty() && uids->sop_instance_uid != instance_uid)
    return not_found("instance '" + instance_uid + "' not found in series '" + series_uid + "'");
  return std::optional<StructureObjectRef>(StructureObjectRef{std::move(*s), parsed->object});
}

StructureObjectListing structure_object_listing(const db::StructureRecord& s, db::StructureObject object) {
  if (object == db::StructureObject::kSeg)
    return {db::structure_object_modality(object), kSegmentationStorage, dicom::SegWriteOptions{}.series_number,
            seg_series_description(s.name)};
  return {db::structure_object_modality(object), kRtStructureSetStorage, dicom::RtStructWriteOptions{}.series_number,
          rt_struct_series_description(s.name)};
}

Result<WrittenStructureObject> write_structure_object(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                                      const StructureObjectRef& ref,
                                                      const std::function<Status()>& stop) {
  const db::StructureRecord& s = ref.structure;
  const StructureObjectUids uids = structure_object_uids(s, ref.object);
  const StructureObjectListing listed = structure_object_listing(s, ref.object);
  if (ref.object == db::StructureObject::kSeg) {
    SOIQ_ASSIGN_OR_RETURN(BudgetedSeg w,
                          structure_seg(store, features, budget, {s.id}, listed.series_description, &uids, stop));
    return WrittenStructureObject{std::move(w.seg.bytes), std::move(w.held)};
  }
  SOIQ_ASSIGN_OR_RETURN(BudgetedRtStruct w,
                        structure_rt_struct(store, features, budget, {s.id}, listed.series_description, &uids, stop));
  return WrittenStructureObject{std::move(w.rt_struct.bytes), std::move(w.held)};
}

}  // namespace soiq::server
