#pragma once
// A stored structure's surface as a file, for the DownloadSurface RPC: the surface decoded through
// the feature engine's cache and written by surface_bytes (uploaded_files.h), so a download
// parses back as an upload of the same file would.
//
// Inputs   structure_id: a stored structure. format: stl (when empty), obj, ply, vtk or vtp.
//          ras: x and y negated, for tools that work in RAS.
// Output   The whole file.
// Errors   NOT_FOUND for an unknown structure; DATA_LOSS for a damaged surface blob;
//          INVALID_ARGUMENT for an unknown or read-only format (off).
// Cost     O(triangles); thread-safe as the Store and FeatureEngine are.

#include <cstdint>
#include <string>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"

namespace soiq::server {

Result<std::string> stored_surface_bytes(db::Store& store, FeatureEngine& features, int64_t structure_id,
                                         const std::string& format, bool ras);

}  // namespace soiq::server
