#pragma once
// Pictures of what soiqd stores (soiq render, the Render RPC, WADO-RS rendered and thumbnail, the
// query page's thumbnails): a structure's voxels over a slice of its image, or an image series'
// slice alone. The structure is converted by the 1D method on the image's own grid, so the
// outline drawn is exactly the voxel set every feature is computed on (render/overlay_picture.h
// draws the pixel edges, never a smoothed contour).
//
// Which image: RenderAsk::image names a series of the structure's study by uid or modality;
// "" takes the series the structure was imported on, else the study's only (or first) series,
// else, when the study has none (a mesh uploaded alone), the mask alone on the 1 mm grid around
// it; "none" asks for the mask alone.
// Which slice: `slice` when given (INVALID_ARGUMENT naming the range when out of it), else the
// slice holding most of the structure's voxels (kLargest) or the one holding its centroid
// (kCentroid); a montage draws every slice holding a voxel, in order. A structure with no voxel
// on the grid is drawn on the middle slice, its caption saying so.
// Window: RenderAsk::window, else the series' own from its DICOM (SeriesRecord::window_center), else
// render::default_window over the image (sampled to at most 10^6
// voxels, so a thumbnail of a large CT costs little more than its decode).
// Caption: structure name, modality and series description, plane and slice, window; with
// patient_caption also the patient id and study date (off by default: a picture travels further
// than the store).
//
// Errors   NOT_FOUND for an unknown structure or series; resolve_grid's and the conversion's
//          errors (RESOURCE_EXHAUSTED, DATA_LOSS); INVALID_ARGUMENT for a slice out of range or a
//          picture over render::kMaxPictureSide (naming the size and what to ask instead).
// Memory   the conversion is admitted against the budget with the image's voxels
//          (FeatureEngine::admit); the picture is a few MB at most.
// Cost     one conversion on the image's grid (cached image decode), then O(pixels drawn).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "render/overlay_picture.h"
#include "render/picture.h"
#include "render/slice_view.h"
#include "render/window.h"
#include "server/app/feature_engine.h"
#include "server/app/memory_budget.h"
#include "server/util/worker_pool.h"

namespace soiq::server {

enum class RenderThrough { kLargest, kCentroid };

struct RenderAsk {
  std::string image;                   // series uid or modality; "" the default above; "none"
  std::optional<render::Plane> plane;  // nullopt: axial (for a series: the plane its slices lie in)
  std::optional<int64_t> slice;
  // Instead of slice: the structure's SEG frame (1-based), i.e. the frame-th of the k slices holding
  // a voxel, in order (dicom/seg_export.h); use with the series' stacking_plane. NOT_FOUND past the
  // last frame.
  std::optional<int64_t> seg_frame;
  RenderThrough through = RenderThrough::kLargest;
  std::optional<render::Window> window;
  bool montage = false;
  int width = 0;                           // of the picture; 0: overlay_picture's default
  std::optional<render::PictureSize> fit;  // instead of width: the largest picture inside this box
  bool patient_caption = false;
  // A thumbnail: no letters, scale bar or caption, and the slice cut to the structure with a margin
  // of half its size (at least 8 pixels), so that a small lesion fills the picture.
  bool thumbnail = false;
  render::PictureOptions picture;
};

struct RenderedPicture {
  std::string bytes;
  render::PictureFormat format = render::PictureFormat::kPng;
  std::string series_uid;  // the image drawn under the structure; "" for the mask alone
  render::Plane plane = render::Plane::kAxial;
  std::vector<int64_t> slices;  // drawn, in order
  int64_t slice_count = 0;      // of the plane, along its normal
  render::Window window;
  render::PictureSize size;
};

Result<RenderedPicture> render_structure(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                         int64_t structure_id, const RenderAsk& ask,
                                         const std::function<Status()>& stop = {});

// Slice `k` of a stored image series alone (k along the axis its slices are stacked on, as its
// slice SOP Instance UIDs are numbered), ask.plane ignored. The decode is admitted in `budget` by
// the image's bytes.
Result<RenderedPicture> render_series_slice(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                            WorkerPool& pool, const std::string& series_uid, int64_t k,
                                            const RenderAsk& ask);

// The plane whose slices are the grid's k slices (an axial series: axial), for pictures that must
// match a series' own slices (a SEG frame, an image instance).
render::Plane stacking_plane(const ImageGeometry& geometry);

}  // namespace soiq::server
