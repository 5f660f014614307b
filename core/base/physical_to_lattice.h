#pragma once
// ImageGeometry::physical_to_lattice for many points: the grid's constants (its shear test, the
// slices' normal) worked out once, the per-point arithmetic inline, so that a loop over a mesh's
// vertices costs a few multiplies per vertex and can be compiled for the CPU's best level
// (cpu_dispatch.h). ImageGeometry::physical_to_lattice is this map, so both agree bit for bit.
//
// Input    a valid geometry (validate_geometry); points in LPS mm.
// Output   lattice coordinates (i, j, z): voxel centres of an evenly spaced grid at integers.
// Cost     O(1) to build; per point 3 divisions and about 15 multiply-adds (sheared grids a few more).

#include "core/base/image_geometry.h"
#include "core/base/vec3.h"

namespace soiq {

class PhysicalToLattice {
 public:
  explicit PhysicalToLattice(const ImageGeometry& g)
      : origin_(g.origin_mm), spacing_(g.spacing_mm), direction_(g.direction), sheared_(g.sheared()) {
    if (sheared_) {
      row_ = {g.direction[0][0], g.direction[1][0], g.direction[2][0]};
      col_ = {g.direction[0][1], g.direction[1][1], g.direction[2][1]};
      k_axis_ = {g.direction[0][2], g.direction[1][2], g.direction[2][2]};
      normal_ = cross(row_, col_);
      k_step_along_normal_ = dot(k_axis_, normal_) * spacing_[2];
    }
  }

  Vec3 operator()(const Vec3& p_mm) const {
    const Vec3 d = p_mm - origin_;
    if (sheared_) {
      // The slice first, from the distance along the normal (k alone moves a point off its plane),
      // then the in-plane position from that slice's own origin.
      const double k = dot(d, normal_) / k_step_along_normal_;
      const Vec3 in_plane = d - (k * spacing_[2]) * k_axis_;
      return {dot(in_plane, row_) / spacing_[0], dot(in_plane, col_) / spacing_[1], k};
    }
    // D is orthonormal (validate_geometry), so its inverse is its transpose.
    Vec3 out{};
    for (int c = 0; c < 3; ++c) {
      out[c] = (direction_[0][c] * d[0] + direction_[1][c] * d[1] + direction_[2][c] * d[2]) / spacing_[c];
    }
    return out;
  }

 private:
  Vec3 origin_, spacing_;
  Mat3 direction_;
  bool sheared_;
  Vec3 row_{}, col_{}, k_axis_{}, normal_{};
  double k_step_along_normal_ = 1;
};

}  // namespace soiq
