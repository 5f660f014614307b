#pragma once
// `soiq features INPUT [--label N] [--reference IMAGE | --spacing S|SX,SY,SZ [--margin N]] [--image [NAME=]IMAGE]...
//  [--region inside|shell:R|core:R]... [--features LIST] [--format table|json|csv]
//  [--interpolation nearest|linear] [--ibsi] [--robust] [--even-odd] [--ras] [--threads N]`:
// the features of one structure, offline. INPUT is a surface model (.stl .obj .ply .vtk .vtp,
// converted by the 1D method on --reference's grid or at --spacing, default 1 mm) or a mask.
// `soiq features --list [--format table|csv|markdown]`: every feature soiq computes, with unit,
// needs and definition (core/features/feature_catalogue.h; docs/FEATURES.md is its markdown).

namespace soiq::cli {

int run_features_command(int argc, char** argv);

}  // namespace soiq::cli
