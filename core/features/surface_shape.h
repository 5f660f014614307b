#pragma once
// Shape features of a closed surface (docs/DESIGN.md "Features"; IBSI "Morphological features" with
// their ids below; PyRadiomics MeshVolume, SurfaceArea, SurfaceVolumeRatio, Sphericity,
// Maximum3DDiameter). For a mask, the surface is marching_cubes(mask), as IBSI and PyRadiomics do.
//
// Inputs   mesh       closed, outward-oriented triangles in LPS mm (e.g. marching_cubes output).
//          box_axes   columns: the orthonormal axes of the "axis-aligned" bounding box; pass the
//                     grid's direction matrix to measure it in the image's frame (IBSI's choice,
//                     and rigid-motion invariant together with the grid), identity for LPS.
// Output   with V = mesh volume, A = area, over the vertices referenced by a triangle:
//            mesh_volume_mm3             V = sum of signed tetrahedra (IBSI RNU0)
//            surface_area_mm2            A = sum of triangle areas (C0JK)
//            surface_volume_ratio        A / V, 1/mm (2PR5; the paper's "complexity")
//            compactness_1               V / (sqrt(pi) A^(3/2)) (SKGS)
//            compactness_2               36 pi V^2 / A^3 (BQWJ)
//            spherical_disproportion     A / (36 pi V^2)^(1/3) (KRCK)
//            sphericity                  (36 pi V^2)^(1/3) / A (QCFX)
//            asphericity                 (A^3 / (36 pi V^2))^(1/3) - 1 (25C7)
//            maximum_3d_diameter_mm      largest distance between two vertices (L0JK), over the
//                                        hull's vertices only (point_set_diameter)
//            convex_hull_volume_mm3, convex_hull_area_mm2
//            volume_density_aabb         V / volume of the vertices' bounding box (PBX1)
//            area_density_aabb           A / surface area of that box (R59B)
//            volume_density_convex_hull  V / hull volume (R3ER)
//            area_density_convex_hull    A / hull area (7T7F)
// Errors   INVALID_ARGUMENT  no triangles, an index out of range, a non-finite vertex or axis,
//                            V <= 0 (inward-facing or open surface), a flat vertex set (no hull).
// Cost     O(T + V) for the measures and the hull shortlist (hull_vertex_candidates.h: exact, it
//          keeps every hull vertex; on marching-cubes or contour surfaces a few % of V), the
//          exact hull of the shortlist (convex_hull.h), and the diameter search over the h hull vertices (about
//          O(h log h), O(h^2) worst case). Thread-safe.
// Caveats  Closedness is not checked (mesh_defects does that, O(T log T)); on an open surface V
//          depends on the origin and the ratios are meaningless. The 2D diameters need the grid:
//          maximum_2d_diameters.h.

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/base/vec3.h"
#include "core/geometry/convex_hull.h"

namespace soiq {

struct SurfaceShape {
  double mesh_volume_mm3 = 0;
  double surface_area_mm2 = 0;
  double surface_volume_ratio = 0;
  double compactness_1 = 0;
  double compactness_2 = 0;
  double spherical_disproportion = 0;
  double sphericity = 0;
  double asphericity = 0;
  double maximum_3d_diameter_mm = 0;
  double convex_hull_volume_mm3 = 0;
  double convex_hull_area_mm2 = 0;
  double volume_density_aabb = 0;
  double area_density_aabb = 0;
  double volume_density_convex_hull = 0;
  double area_density_convex_hull = 0;
};

// Whether the convex hull (convex_hull_volume_mm3/area_mm2, volume/area_density_convex_hull) and
// the diameter (maximum_3d_diameter_mm) are computed. The exact hull of a smooth surface in general
// position costs ~10x its conversion (every vertex of a convex patch is a hull corner), so a caller
// that needs none of them skips them (feature_catalogue.h: FeatureNeed::kConvexHull, kDiameter3d),
// and one that needs the diameter alone gets it without the hull: point_set_diameter over the
// hull shortlist, the same largest distance (a pair of hull corners reaches it). Skipped fields
// are NaN and nothing else changes, bit for bit.
enum class HullPart { kCompute, kDiameterOnly, kSkip };

Result<SurfaceShape> surface_shape(const TriangleMesh& mesh, const Mat3& box_axes = identity3(),
                                   HullPart hull = HullPart::kCompute);

// The hull-dependent inputs of surface_shape_from_measures when HullPart::kSkip: NaN throughout.
ConvexHull skipped_hull();

// The ratios and densities above from the measures they are made of: mesh volume V (> 0), area A,
// the vertices' convex hull, their largest distance and their extents along the box axes.
// surface_shape and mask_surface_shape both end here, so the formulas exist once. O(1).
SurfaceShape surface_shape_from_measures(double volume_mm3, double area_mm2, const ConvexHull& hull, double diameter_mm,
                                         const Vec3& box_extent_mm);

}  // namespace soiq
