#include "render/slice_view.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace soiq::render {

namespace {

// The screen's right and down as LPS directions, per plane, as radiology viewers show them.
struct ScreenFrame {
  Vec3 right;
  Vec3 down;
};

ScreenFrame screen_frame(Plane plane) {
  switch (plane) {
    case Plane::kAxial:
      return {{1, 0, 0}, {0, 1, 0}};  // right -> patient left, down -> posterior
    case Plane::kCoronal:
      return {{1, 0, 0}, {0, 0, -1}};  // right -> patient left, down -> inferior
    case Plane::kSagittal:
      break;
  }
  return {{0, 1, 0}, {0, 0, -1}};  // right -> posterior, down -> inferior
}

Vec3 voxel_axis_direction(const ImageGeometry& g, int axis) {
  return {g.direction[0][axis], g.direction[1][axis], g.direction[2][axis]};
}

// The LPS letters of a direction: the axes whose component exceeds 1e-3, largest first.
std::string direction_letters(const Vec3& d) {
  static constexpr std::array<std::array<char, 2>, 3> kLetters{{{'R', 'L'}, {'A', 'P'}, {'I', 'S'}}};
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(d[a]) > std::abs(d[b]); });
  std::string letters;
  for (int axis : order) {
    if (std::abs(d[axis]) > 1e-3) letters += kLetters[axis][d[axis] > 0 ? 1 : 0];
  }
  return letters;
}

// The voxel axis matched to each patient axis (x, y, z): of the six one-to-one matchings, the one
// whose cosines have the largest sum of magnitudes. Matching each voxel axis to its own largest
// component is not enough: an orthonormal grid can have two axes whose largest component is the
// same patient axis (columns (0.71, 0.5, 0.5) and (0.71, -0.5, -0.5)).
std::array<int, 3> voxel_axis_per_patient_axis(const ImageGeometry& g) {
  std::array<int, 3> permutation{0, 1, 2}, best = permutation;
  double best_sum = -1;
  do {
    double sum = 0;
    for (int patient = 0; patient < 3; ++patient) sum += std::abs(g.direction[patient][permutation[patient]]);
    if (sum > best_sum + 1e-12) {  // ties keep the first in lexicographic order, so the choice is stable
      best_sum = sum;
      best = permutation;
    }
  } while (std::next_permutation(permutation.begin(), permutation.end()));
  return best;
}

int patient_axis_of(const Vec3& screen_direction) {
  for (int a = 0; a < 3; ++a) {
    if (screen_direction[a] != 0) return a;
  }
  return 0;
}

Status check_slice(const SliceAxes& axes, int64_t k) {
  if (k < 0 || k >= axes.slice_count) {
    return invalid_argument(std::string(plane_name(axes.plane)) + " slice " + std::to_string(k) +
                            " is out of range 0.." + std::to_string(axes.slice_count - 1));
  }
  return ok_status();
}

// The grid's dims as `axes` was made from them.
std::array<int64_t, 3> dims_of(const SliceAxes& axes) {
  std::array<int64_t, 3> dims{};
  dims[axes.across_axis] = axes.width;
  dims[axes.down_axis] = axes.height;
  dims[axes.normal_axis] = axes.slice_count;
  return dims;
}

Status check_dims(const std::array<int64_t, 3>& have, const SliceAxes& axes, const char* what) {
  if (have != dims_of(axes)) {
    const auto d = dims_of(axes);
    return invalid_argument(std::string(what) + " of " + std::to_string(have[0]) + "x" + std::to_string(have[1]) + "x" +
                            std::to_string(have[2]) + " voxels is not on the slice's grid of " + std::to_string(d[0]) +
                            "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]));
  }
  return ok_status();
}

// The slice pixel (x, y) of voxel index `along` on the across axis and `down` on the down axis.
int64_t screen_x(const SliceAxes& axes, int64_t across) { return axes.flip_across ? axes.width - 1 - across : across; }
int64_t screen_y(const SliceAxes& axes, int64_t down) { return axes.flip_down ? axes.height - 1 - down : down; }

}  // namespace

Result<Plane> plane_of_name(const std::string& name) {
  for (Plane plane : {Plane::kAxial, Plane::kCoronal, Plane::kSagittal}) {
    if (name == plane_name(plane)) return plane;
  }
  return invalid_argument("unknown plane '" + name + "'; the planes are axial, coronal and sagittal");
}

const char* plane_name(Plane plane) {
  switch (plane) {
    case Plane::kAxial:
      return "axial";
    case Plane::kCoronal:
      return "coronal";
    case Plane::kSagittal:
      break;
  }
  return "sagittal";
}

Result<SliceAxes> slice_axes(const ImageGeometry& geometry, Plane plane) {
  if (Status valid = validate_geometry(geometry); !valid.ok()) {
    return failed_precondition("the grid's axes cannot be matched with the " + std::string(plane_name(plane)) +
                               " plane: " + valid.message());
  }
  const ScreenFrame frame = screen_frame(plane);
  const std::array<int, 3> voxel_axis = voxel_axis_per_patient_axis(geometry);
  const int across_patient = patient_axis_of(frame.right), down_patient = patient_axis_of(frame.down);
  SliceAxes axes;
  axes.plane = plane;
  axes.across_axis = voxel_axis[across_patient];
  axes.down_axis = voxel_axis[down_patient];
  axes.normal_axis = 3 - axes.across_axis - axes.down_axis;
  const Vec3 across = voxel_axis_direction(geometry, axes.across_axis);
  const Vec3 down = voxel_axis_direction(geometry, axes.down_axis);
  axes.flip_across = dot(across, frame.right) < 0;
  axes.flip_down = dot(down, frame.down) < 0;
  axes.slice_count = geometry.dims[axes.normal_axis];
  axes.width = geometry.dims[axes.across_axis];
  axes.height = geometry.dims[axes.down_axis];
  // A tilted series' slices stand their planes' distance apart (the shear itself is not drawn).
  auto pixel_mm = [&](int axis) { return axis == 2 ? geometry.slice_distance_mm() : geometry.spacing_mm[axis]; };
  axes.pixel_width_mm = pixel_mm(axes.across_axis);
  axes.pixel_height_mm = pixel_mm(axes.down_axis);
  // Where the screen's right and down point in the patient: the voxel axes as shown, flips included.
  const Vec3 right = (axes.flip_across ? -1.0 : 1.0) * across;
  const Vec3 below = (axes.flip_down ? -1.0 : 1.0) * down;
  axes.right = direction_letters(right);
  axes.left = direction_letters(-1.0 * right);
  axes.bottom = direction_letters(below);
  axes.top = direction_letters(-1.0 * below);
  return axes;
}

Result<SliceImage> image_slice(const Image& image, const SliceAxes& axes, int64_t k) {
  SOIQ_RETURN_IF_ERROR(check_slice(axes, k));
  SOIQ_RETURN_IF_ERROR(check_dims(image.geometry.dims, axes, "an image"));
  if (static_cast<int64_t>(image.voxels.size()) != image.geometry.voxel_count()) {
    return invalid_argument("an image has " + std::to_string(image.voxels.size()) + " voxels where its grid has " +
                            std::to_string(image.geometry.voxel_count()));
  }
  const auto& dims = image.geometry.dims;
  const std::array<int64_t, 3> stride{1, dims[0], dims[0] * dims[1]};
  SliceImage slice{axes.width, axes.height, std::vector<float>(static_cast<size_t>(axes.width * axes.height))};
  const int64_t base = k * stride[axes.normal_axis];
  for (int64_t y = 0; y < axes.height; ++y) {
    const int64_t row = base + screen_y(axes, y) * stride[axes.down_axis];
    for (int64_t x = 0; x < axes.width; ++x) {
      slice.values[static_cast<size_t>(y * axes.width + x)] =
          image.voxels[static_cast<size_t>(row + screen_x(axes, x) * stride[axes.across_axis])];
    }
  }
  return slice;
}

Result<SliceMask> mask_slice(const RunLengthVolume& volume, const SliceAxes& axes, int64_t k) {
  SOIQ_RETURN_IF_ERROR(check_slice(axes, k));
  SOIQ_RETURN_IF_ERROR(check_dims(volume.geometry.dims, axes, "a structure"));
  const int64_t ny = volume.geometry.dims[1], nz = volume.geometry.dims[2];
  if (static_cast<int64_t>(volume.line_start.size()) != ny * nz + 1) {
    return invalid_argument("a structure's run index has " + std::to_string(volume.line_start.size()) +
                            " entries where its grid needs " + std::to_string(ny * nz + 1));
  }
  SliceMask mask{axes.width, axes.height, std::vector<uint8_t>(static_cast<size_t>(axes.width * axes.height), 0)};
  const auto set = [&](const std::array<int64_t, 3>& ijk) {
    const int64_t x = screen_x(axes, ijk[axes.across_axis]), y = screen_y(axes, ijk[axes.down_axis]);
    mask.inside[static_cast<size_t>(y * axes.width + x)] = 1;
  };
  // Only the lines (j, k) that cross the slice: all of them when the slice is across the runs
  // (i fixed), else one row of lines.
  const int64_t j_begin = axes.normal_axis == 1 ? k : 0, j_end = axes.normal_axis == 1 ? k + 1 : ny;
  const int64_t k_begin = axes.normal_axis == 2 ? k : 0, k_end = axes.normal_axis == 2 ? k + 1 : nz;
  for (int64_t kk = k_begin; kk < k_end; ++kk) {
    for (int64_t j = j_begin; j < j_end; ++j) {
      const int64_t line = j + ny * kk;
      const auto first = volume.runs.begin() + volume.line_start[static_cast<size_t>(line)];
      const auto last = volume.runs.begin() + volume.line_start[static_cast<size_t>(line) + 1];
      if (axes.normal_axis == 0) {
        // The run holding i = k, if any: the first run ending past k.
        const auto run = std::upper_bound(first, last, k, [](int64_t i, const Run& r) { return i < r.end; });
        if (run != last && run->begin <= k) set({k, j, kk});
        continue;
      }
      for (auto run = first; run != last; ++run) {
        for (int64_t i = run->begin; i < run->end; ++i) set({i, j, kk});
      }
    }
  }
  return mask;
}

std::vector<int64_t> inside_per_slice(const RunLengthVolume& volume, const SliceAxes& axes) {
  std::vector<int64_t> counts(static_cast<size_t>(std::max<int64_t>(axes.slice_count, 0)), 0);
  const int64_t ny = volume.geometry.dims[1];
  if (axes.normal_axis == 0) {
    // A run adds one to every slice it spans: a difference array keeps it O(runs + slices).
    std::vector<int64_t> steps(counts.size() + 1, 0);
    for (const Run& run : volume.runs) {
      if (run.begin >= static_cast<int64_t>(counts.size())) continue;
      ++steps[static_cast<size_t>(run.begin)];
      --steps[static_cast<size_t>(std::min<int64_t>(run.end, static_cast<int64_t>(counts.size())))];
    }
    int64_t running = 0;
    for (size_t i = 0; i < counts.size(); ++i) counts[i] = running += steps[i];
    return counts;
  }
  for (int64_t line = 0; line + 1 < static_cast<int64_t>(volume.line_start.size()); ++line) {
    const auto slice = static_cast<size_t>(axes.normal_axis == 1 ? line % ny : line / ny);
    if (slice >= counts.size()) continue;
    for (int64_t r = volume.line_start[static_cast<size_t>(line)]; r < volume.line_start[static_cast<size_t>(line) + 1];
         ++r) {
      counts[slice] += volume.runs[static_cast<size_t>(r)].end - volume.runs[static_cast<size_t>(r)].begin;
    }
  }
  return counts;
}

}  // namespace soiq::render
