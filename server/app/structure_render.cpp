#include "server/app/structure_render.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include "core/base/fill_rule.h"
#include "server/app/grid_choice.h"

namespace soiq::server {
namespace {

// A default window from at most this many voxels, evenly strided: percentiles of a million
// samples differ from the whole image's by far less than a grey level.
constexpr int64_t kWindowSamples = 1'000'000;

render::Window window_for(const RenderAsk& ask, const Image* image, const db::SeriesRecord* series) {
  if (ask.window) return *ask.window;
  if (series != nullptr && series->window_width > 0) return {series->window_center, series->window_width};
  if (image == nullptr) return {};
  const std::string modality = series != nullptr ? series->modality : "";
  const size_t n = image->voxels.size();
  const size_t stride = std::max<size_t>(1, n / size_t(kWindowSamples));
  std::vector<float> sample;
  sample.reserve(n / stride + 1);
  for (size_t i = 0; i < n; i += stride) sample.push_back(image->voxels[i]);
  return render::default_window(sample, modality);
}

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", v);
  return text;
}

// The series a structure is drawn over (nullopt: the mask alone), by RenderAsk::image's rule.
Result<std::optional<db::SeriesRecord>> image_series(const std::string& ref, const db::StructureRecord& structure,
                                                     const std::vector<db::SeriesRecord>& study_series) {
  if (ref == "none") return std::optional<db::SeriesRecord>();
  if (!ref.empty()) {
    SOIQ_ASSIGN_OR_RETURN(db::SeriesRecord s, find_series(ref, study_series, structure.study_uid));
    return std::optional<db::SeriesRecord>(std::move(s));
  }
  for (const db::SeriesRecord& s : study_series)
    if (!structure.source_series_uid.empty() && s.series_uid == structure.source_series_uid)
      return std::optional<db::SeriesRecord>(s);
  if (study_series.empty()) return std::optional<db::SeriesRecord>();
  return std::optional<db::SeriesRecord>(study_series.front());
}

// The slices to draw: the asked one, or the largest or centroid slice, or every slice holding
// a voxel for a montage.
Result<std::vector<int64_t>> slices_to_draw(const RenderAsk& ask, const std::vector<int64_t>& inside,
                                            int64_t slice_count) {
  if (slice_count <= 0) return invalid_argument("the grid has no slice in that plane");
  if (ask.slice) {
    if (*ask.slice < 0 || *ask.slice >= slice_count)
      return invalid_argument("slice " + std::to_string(*ask.slice) + " is outside 0.." +
                              std::to_string(slice_count - 1) + " of this plane")
          .in_field("slice");
    return std::vector<int64_t>{*ask.slice};
  }
  if (ask.seg_frame) {
    int64_t frame = 0;
    for (int64_t k = 0; k < slice_count; ++k)
      if (inside[size_t(k)] > 0 && ++frame == *ask.seg_frame) return std::vector<int64_t>{k};
    return not_found("the structure's SEG has frames 1.." + std::to_string(frame) + ", not " +
                     std::to_string(*ask.seg_frame));
  }
  int64_t total = 0;
  for (const int64_t n : inside) total += n;
  if (total == 0) return std::vector<int64_t>{slice_count / 2};
  if (ask.montage) {
    std::vector<int64_t> all;
    for (int64_t k = 0; k < slice_count; ++k)
      if (inside[size_t(k)] > 0) all.push_back(k);
    return all;
  }
  if (ask.through == RenderThrough::kLargest)
    return std::vector<int64_t>{int64_t(std::max_element(inside.begin(), inside.end()) - inside.begin())};
  double weighted = 0;
  for (int64_t k = 0; k < slice_count; ++k) weighted += double(k) * double(inside[size_t(k)]);
  return std::vector<int64_t>{std::clamp<int64_t>(std::llround(weighted / double(total)), 0, slice_count - 1)};
}

// The picture's width: asked, or the largest that fits the asked box with the tiles' aspect.
Result<int> picture_width(const RenderAsk& ask, const render::SliceAxes& axes, size_t tiles) {
  if (!ask.fit) return ask.width;
  SOIQ_ASSIGN_OR_RETURN(const render::PictureSize natural, render::overlay_size(axes, tiles, 0));
  const double scale = std::min(double(ask.fit->width) / natural.width, double(ask.fit->height) / natural.height);
  int width = std::max(16, int(std::floor(natural.width * scale)));
  // The height follows the width with rounding of its own: step down until it fits.
  for (int tries = 0; tries < 8 && width > 16; ++tries) {
    SOIQ_ASSIGN_OR_RETURN(const render::PictureSize size, render::overlay_size(axes, tiles, width));
    if (size.height <= ask.fit->height) break;
    width = std::max(16, int(std::floor(width * double(ask.fit->height) / size.height)));
  }
  return width;
}

// The pixels [x0, x1) x [y0, y1) of a slice, or all of them.
struct Crop {
  int64_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Around the structure's pixels on every tile, with a margin of half its size (at least 8 pixels);
// the whole slice when it has none.
Crop crop_around(const std::vector<render::SliceMask>& masks, int64_t width, int64_t height) {
  int64_t x0 = width, y0 = height, x1 = 0, y1 = 0;
  for (const render::SliceMask& m : masks)
    for (int64_t y = 0; y < m.height; ++y)
      for (int64_t x = 0; x < m.width; ++x)
        if (m.inside[size_t(y * m.width + x)]) {
          x0 = std::min(x0, x), x1 = std::max(x1, x + 1);
          y0 = std::min(y0, y), y1 = std::max(y1, y + 1);
        }
  if (x1 <= x0) return {0, 0, width, height};
  const int64_t mx = std::max<int64_t>(8, (x1 - x0) / 2), my = std::max<int64_t>(8, (y1 - y0) / 2);
  return {std::max<int64_t>(0, x0 - mx), std::max<int64_t>(0, y0 - my), std::min(width, x1 + mx),
          std::min(height, y1 + my)};
}

template <typename T>
std::vector<T> cropped(const std::vector<T>& values, int64_t width, const Crop& c) {
  std::vector<T> out;
  out.reserve(size_t((c.x1 - c.x0) * (c.y1 - c.y0)));
  for (int64_t y = c.y0; y < c.y1; ++y)
    out.insert(out.end(), values.begin() + y * width + c.x0, values.begin() + y * width + c.x1);
  return out;
}

struct Drawn {
  const db::StructureRecord* structure = nullptr;  // nullptr: an image slice alone
  const RunLengthVolume* volume = nullptr;
  const db::SeriesRecord* series = nullptr;  // nullptr: the mask alone
  const Image* image = nullptr;
  std::string patient_caption;  // "" unless asked
};

// The picture of `slices` of `axes` for what `drawn` holds.
Result<RenderedPicture> draw(const RenderAsk& ask, const Drawn& drawn, const render::SliceAxes& axes,
                             const std::vector<int64_t>& slices, bool empty_structure) {
  RenderedPicture out;
  out.format = ask.picture.format;
  out.series_uid = drawn.series != nullptr ? drawn.series->series_uid : "";
  out.plane = axes.plane;
  out.slices = slices;
  out.slice_count = axes.slice_count;
  const std::string modality = drawn.series != nullptr ? drawn.series->modality : "";
  out.window = window_for(ask, drawn.image, drawn.series);

  // Short enough for a 512-pixel picture: what is drawn, where, how. The series' description is
  // left out (often long, sometimes naming the patient).
  std::string caption;
  if (drawn.structure != nullptr) caption = drawn.structure->name;
  if (drawn.series != nullptr) caption += (caption.empty() ? "" : "  |  ") + drawn.series->modality;
  caption += std::string(caption.empty() ? "" : "  |  ") + render::plane_name(axes.plane);
  if (slices.size() == 1)
    caption += " " + std::to_string(slices[0]) + "/" + std::to_string(axes.slice_count - 1);
  else
    caption += ", " + std::to_string(slices.size()) + " slices";
  if (drawn.image != nullptr)
    caption += "  |  W " + number_text(out.window.width) + " L " + number_text(out.window.center);
  if (empty_structure) caption += "  |  no voxel inside on this grid";
  if (!drawn.patient_caption.empty()) caption += "  |  " + drawn.patient_caption;

  std::vector<render::OverlayScene> tiles;
  tiles.reserve(slices.size());
  for (const int64_t k : slices) {
    render::OverlayScene scene;
    if (drawn.image != nullptr) {
      SOIQ_ASSIGN_OR_RETURN(render::SliceImage image, render::image_slice(*drawn.image, axes, k));
      scene.image = std::move(image);
    }
    if (drawn.volume != nullptr) {
      SOIQ_ASSIGN_OR_RETURN(scene.mask, render::mask_slice(*drawn.volume, axes, k));
    } else {
      scene.mask.width = axes.width;
      scene.mask.height = axes.height;
      scene.mask.inside.assign(size_t(axes.width * axes.height), 0);
    }
    scene.window = out.window;
    scene.colours = render::colour_map_for_modality(modality);
    // Red disappears into PET's hot colours: cyan stands apart from all of them.
    if (scene.colours == render::ColourMap::kHot) scene.structure_colour = render::Rgb{0, 230, 255};
    scene.pixel_width_mm = axes.pixel_width_mm;
    scene.pixel_height_mm = axes.pixel_height_mm;
    scene.left = axes.left;
    scene.right = axes.right;
    scene.top = axes.top;
    scene.bottom = axes.bottom;
    if (slices.size() > 1) scene.label = std::to_string(k);
    tiles.push_back(std::move(scene));
  }
  // One caption for the whole picture: on the first tile.
  if (!tiles.empty()) tiles.front().caption = caption;
  render::SliceAxes shown = axes;
  if (ask.thumbnail) {
    std::vector<render::SliceMask> masks;
    for (const render::OverlayScene& t : tiles) masks.push_back(t.mask);
    const Crop c = crop_around(masks, axes.width, axes.height);
    for (render::OverlayScene& t : tiles) {
      t.annotations = false;
      t.mask.inside = cropped(t.mask.inside, t.mask.width, c);
      t.mask.width = c.x1 - c.x0;
      t.mask.height = c.y1 - c.y0;
      if (t.image) {
        t.image->values = cropped(t.image->values, t.image->width, c);
        t.image->width = c.x1 - c.x0;
        t.image->height = c.y1 - c.y0;
      }
    }
    shown.width = c.x1 - c.x0;
    shown.height = c.y1 - c.y0;
  }
  SOIQ_ASSIGN_OR_RETURN(const int width, picture_width(ask, shown, tiles.size()));
  SOIQ_ASSIGN_OR_RETURN(out.size, render::overlay_size(shown, tiles.size(), width));
  if (out.size.width > render::kMaxPictureSide || out.size.height > render::kMaxPictureSide)
    return invalid_argument("the picture would be " + std::to_string(out.size.width) + "x" +
                            std::to_string(out.size.height) + " pixels, over " +
                            std::to_string(render::kMaxPictureSide) +
                            " on a side: ask for a smaller width, or for single slices instead of a montage");
  SOIQ_ASSIGN_OR_RETURN(out.bytes, render::overlay_picture(tiles, width, ask.picture));
  return out;
}

std::string patient_text(db::Store& store, const db::StructureRecord& structure) {
  std::string text = "patient " + structure.patient_id;
  Result<db::StudyRecord> study = store.get_study(structure.study_uid);
  if (study.ok() && !study->study_date.empty()) text += ", study " + study->study_date;
  return text;
}

}  // namespace

render::Plane stacking_plane(const ImageGeometry& geometry) {
  for (const render::Plane p : {render::Plane::kAxial, render::Plane::kCoronal, render::Plane::kSagittal}) {
    Result<render::SliceAxes> axes = render::slice_axes(geometry, p);
    if (axes.ok() && axes->normal_axis == 2) return p;
  }
  return render::Plane::kAxial;
}

Result<RenderedPicture> render_structure(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                         int64_t structure_id, const RenderAsk& ask,
                                         const std::function<Status()>& stop) {
  SOIQ_ASSIGN_OR_RETURN(const db::StructureRecord structure, store.get_structure(structure_id));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> study_series, store.list_series(structure.study_uid));
  SOIQ_ASSIGN_OR_RETURN(const std::optional<db::SeriesRecord> series, image_series(ask.image, structure, study_series));
  GridChoice choice;  // the mask alone: 1 mm around the structure
  if (series) {
    choice.kind = GridChoice::Kind::kSeriesUid;
    choice.series = series->series_uid;
  }
  SOIQ_ASSIGN_OR_RETURN(const ResolvedGrid grid,
                        resolve_grid(choice, structure, study_series, 0, features.max_grid_voxels()));
  const render::Plane plane = ask.plane.value_or(render::Plane::kAxial);
  SOIQ_ASSIGN_OR_RETURN(const render::SliceAxes axes, render::slice_axes(grid.geometry, plane));
  const std::string patient = ask.patient_caption ? patient_text(store, structure) : "";

  std::optional<RenderedPicture> out;
  // Admitted on the worker, as every conversion is (structure_conversion.cpp says why), with the
  // picture it may draw: at most its tiles' pixels, 4 bytes each on cairo's surface and about as
  // many again for the slices' copies and the encoded file.
  const size_t tiles = ask.montage ? size_t(std::max<int64_t>(1, axes.slice_count)) : 1;
  const Result<render::PictureSize> size = render::overlay_size(axes, tiles, ask.fit ? 0 : ask.width);
  const int64_t side = render::kMaxPictureSide;
  const int64_t pixels = size.ok() ? std::min(int64_t(size->width) * size->height, side * side) : side * side;
  auto work = [&]() -> Status {
    FeatureEngine::WorkExtras extras;
    extras.other_bytes = pixels * 8;
    SOIQ_ASSIGN_OR_RETURN(FeatureEngine::Admission held, features.admit(structure, grid.geometry, extras, stop));
    SOIQ_ASSIGN_OR_RETURN(const Voxelization v, features.convert(held, structure, grid.geometry, FillRule::kNonZero));
    std::shared_ptr<const Image> image;
    if (series) {
      SOIQ_ASSIGN_OR_RETURN(image, features.image(*series));
    }
    const std::vector<int64_t> inside = render::inside_per_slice(v.volume, axes);
    SOIQ_ASSIGN_OR_RETURN(const std::vector<int64_t> slices, slices_to_draw(ask, inside, axes.slice_count));
    const bool empty = std::all_of(inside.begin(), inside.end(), [](int64_t n) { return n == 0; });
    Drawn drawn{&structure, &v.volume, series ? &*series : nullptr, image.get(), patient};
    SOIQ_ASSIGN_OR_RETURN(RenderedPicture picture, draw(ask, drawn, axes, slices, empty));
    out.emplace(std::move(picture));
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(pool.call(work));
  return std::move(*out);
}

Result<RenderedPicture> render_series_slice(db::Store& store, FeatureEngine& features, MemoryBudget& budget,
                                            WorkerPool& pool, const std::string& series_uid, int64_t k,
                                            const RenderAsk& ask) {
  SOIQ_ASSIGN_OR_RETURN(const db::SeriesRecord series, store.get_series(series_uid));
  SOIQ_ASSIGN_OR_RETURN(const render::SliceAxes axes,
                        render::slice_axes(series.geometry, stacking_plane(series.geometry)));
  if (k < 0 || k >= axes.slice_count)
    return not_found("series " + series_uid + " has slices 0.." + std::to_string(axes.slice_count - 1) + ", not " +
                     std::to_string(k));
  std::optional<RenderedPicture> out;
  auto work = [&]() -> Status {
    const int64_t bytes = series.geometry.voxel_count() * int64_t(sizeof(float)) + axes.width * axes.height * 8;
    SOIQ_ASSIGN_OR_RETURN(const MemoryBudget::Reservation held,
                          budget.reserve(bytes, "a picture of series " + series_uid));
    SOIQ_ASSIGN_OR_RETURN(const std::shared_ptr<const Image> image, features.image(series));
    Drawn drawn{nullptr, nullptr, &series, image.get(), ""};
    SOIQ_ASSIGN_OR_RETURN(RenderedPicture picture, draw(ask, drawn, axes, {k}, false));
    out.emplace(std::move(picture));
    return ok_status();
  };
  SOIQ_RETURN_IF_ERROR(pool.call(work));
  return std::move(*out);
}

}  // namespace soiq::server
