#include "server/app/upload_surface.h"

#include "db/surface_blob.h"
#include "server/app/uploaded_files.h"

namespace soiq::server {

Result<UploadedSurface> upload_surface(db::RecordStore& store, const SurfaceUpload& upload, const std::string& bytes) {
  SOIQ_ASSIGN_OR_RETURN(ParsedSurface parsed,
                        parse_surface(bytes, upload.format, upload.ras, upload.robust, upload.structure_name));
  SOIQ_ASSIGN_OR_RETURN(db::EncodedSurface encoded, db::encode_surface(parsed.mesh));
  db::NewStructure s;
  s.patient = upload.patient;
  s.study = upload.study;
  s.name = upload.structure_name;
  s.laterality = upload.laterality;
  s.robust = upload.robust;
  s.surface = encoded.info;
  s.surface_blob = std::move(encoded.blob);
  SOIQ_ASSIGN_OR_RETURN(db::AddedStructure added, store.add_structure(std::move(s)));
  return UploadedSurface{std::move(added), parsed.defects};
}

}  // namespace soiq::server
