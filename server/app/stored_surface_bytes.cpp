#include "server/app/stored_surface_bytes.h"

#include "server/app/uploaded_files.h"

namespace soiq::server {

Result<std::string> stored_surface_bytes(db::Store& store, FeatureEngine& features, int64_t structure_id,
                                         const std::string& format, bool ras) {
  SOIQ_ASSIGN_OR_RETURN(const db::StructureRecord s, store.get_structure(structure_id));
  SOIQ_ASSIGN_OR_RETURN(const std::shared_ptr<const TriangleMesh> mesh, features.surface(s));
  return surface_bytes(*mesh, format, ras);
}

}  // namespace soiq::server
