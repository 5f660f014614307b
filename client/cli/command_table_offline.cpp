// The rows of the offline commands (no server needed) in the command table: mesh, convert,
// features, compare. convert and features take a stored structure id too; their rows list the
// options of both forms, and the parser of each form refuses the other's.
#include "client/cli/command_table.h"
#include "client/cli/compare_command.h"
#include "client/cli/mesh_command.h"
#include "client/cli/operand_dispatch.h"

namespace soiq::cli {

namespace {

int run_mesh(int argc, char** argv, const client::ClientOptions&) { return run_mesh_command(argc, argv); }
int run_compare(int argc, char** argv, const client::ClientOptions&) { return run_compare_command(argc, argv); }

}  // namespace

std::vector<CommandSpec> offline_commands() {
  const OptionSpec output = {"-o", "OUT", "", "the file to write; its extension chooses the format", "--output"};
  const OptionSpec reference = {"--reference", "IMAGE", "",
                                "convert onto this image's grid (a file; not with --spacing)"};
  const OptionSpec spacing = {"--spacing", "S|SX,SY,SZ", "1", "voxel size of a grid around the surface, in mm"};
  const OptionSpec margin = {"--margin", "N", "2", "voxels of margin around the surface (with --spacing)"};
  const OptionSpec robust = {"--robust", "", "", "accept open or self-intersecting surfaces (file only)"};
  const OptionSpec even_odd = {"--even-odd", "", "nonzero", "fill by the even-odd rule instead of nonzero winding"};
  const OptionSpec threads = {"--threads", "N", "1", "threads of the 1D method (file only)"};
  const OptionSpec ras = {"--ras", "", "LPS", "the file's coordinates are RAS, not LPS (file only)"};
  const OptionSpec series = {"--series", "UID", "", "stored structure only: the grid of this stored image series"};
  const OptionSpec series_modality = {"--series-modality", "M", "",
                                      "stored structure only: the grid of the study's series of modality M"};
  const OptionSpec fractional = {"--fractional", "", "binary",
                                 "write the fraction of each voxel inside (uint8: 0 outside, 255 inside)"};
  const OptionSpec float32 = {"--float32", "", "uint8", "with --fractional: fractions as float32 0-1"};
  const OptionSpec oversample = {"--oversample", "N", "4",
                                 "with --fractional: N x N lines across each voxel (1-8; exact along rows)"};
  const OptionSpec interpolation = {"--interpolation", "nearest|linear", "nearest", "how the image is sampled"};
  return {
      {"mesh",
       CommandGroup::kOffline,
       {"mesh MASK -o OUT.{stl,vtk,vtp,ply,obj} [--label N]"},
       "mask -> surface model (marching cubes at 0.5, LPS mm, outward normals)",
       "Reads a mask image (.nii, .nii.gz, .nrrd, .mha) and writes the surface of its nonzero voxels, or "
       "of the voxels with label N, as a triangle mesh in LPS millimetres with outward normals. Prints the "
       "triangle and vertex counts and the mesh volume.",
       {output, {"--label", "N", "every nonzero voxel", "mesh only the voxels with this label"}},
       {"soiq mesh brain1_mask.nii.gz -o brain1.vtp", "soiq mesh labels.nrrd --label 3 -o hippocampus.stl"},
       run_mesh},
      {"convert",
       CommandGroup::kOffline,
       {"convert MESH -o OUT.{nii.gz,nii,nrrd,mha} [--reference IMAGE | --spacing S|SX,SY,SZ [--margin N]]",
        "        [--robust] [--even-odd] [--threads N] [--ras] [--fractional [--float32] [--oversample N]]",
        "convert ID -o OUT.{nii.gz,nii,nrrd,mha} [--spacing S [--margin N] | --series UID | --series-modality M]",
        "        [--even-odd] [--fractional [--float32] [--oversample N]]"},
       "surface model -> volume model (the 1D scanline method); prints one summary line",
       "Converts a closed surface model to a binary volume by the 1D scanline method, or with --fractional "
       "to the fraction of each voxel inside it (partial volume: exact along the rows, sampled on N x N lines "
       "across them). The operand is a mesh file (run here) or a stored structure id (all digits, or id:N; "
       "run on soiqd). A file named like an id is refused as ambiguous: write ./N or id:N.",
       {output, reference, spacing, margin, robust, even_odd, threads, ras, series, series_modality, fractional,
        float32, oversample},
       {"soiq convert brain1.vtp -o brain1.nii.gz --spacing 0.5",
        "soiq convert 4 -o hippocampus.nii.gz --series-modality MR",
        "soiq convert 7 -o gtv_fractions.nii.gz --series-modality PT --fractional --float32"},
       run_convert_any},
      {"features",
       CommandGroup::kOffline,
       {"features INPUT [--label N] [--reference IMAGE | --spacing S [--margin N]] [--image [NAME=]IMAGE]...",
        "         [--region inside|shell:R|core:R]... [--features LIST] [--format table|json|csv]",
        "         [--interpolation nearest|linear] [--ibsi] [--robust] [--even-odd] [--ras] [--threads N]",
        "features ID [--features LIST] [--region inside|shell:R|core:R]... [--image MODALITY|SERIES_UID]...",
        "         [--spacing S [--margin N] | --series UID | --series-modality M] [--interpolation nearest|linear]",
        "         [--format table|json|csv]", "features --list [--format table|csv|markdown]"},
       "shape and intensity features of a structure (a surface model or a mask); --list: every feature",
       "Computes the shape features of a structure and, with images, its intensity features per region. "
       "INPUT is a surface model or a mask file (run here) or a stored structure id (run on soiqd). --list "
       "prints every feature soiq computes: family, unit, what it needs, definition.",
       {{"--label", "N", "every nonzero voxel", "a mask's label to measure (file only)"},
        reference,
        spacing,
        margin,
        {"--image", "[NAME=]IMAGE", "",
         "an image for intensity features: a file (named NAME, else after the file), or for a stored "
         "structure a modality or series uid; repeatable"},
        {"--region", "inside|shell:R|core:R", "inside", "where intensities are read (R in mm); repeatable"},
        {"--features", "LIST", "all that apply", "comma-separated feature names (soiq features --list)"},
        {"--format", "table|json|csv|markdown", "table", "output format (markdown with --list only)"},
        interpolation,
        {"--ibsi", "", "", "IBSI conventions for the intensity features (file only)"},
        robust,
        even_odd,
        ras,
        threads,
        series,
        series_modality,
        {"--list", "", "", "print the feature catalogue instead"}},
       {"soiq features brain1.vtp --image MR=brain1_t1.nii.gz --region shell:2",
        "soiq features 4 --image MR --features voxel_volume_mm3,mean"},
       run_features_any,
       false,
       "convert and features run on soiqd when their operand is a structure id (all digits, or id:N), "
       "offline when it is a file (a file named like an id is refused as ambiguous: write ./N or id:N)"},
      {"compare",
       CommandGroup::kOffline,
       {"compare MASK_A MASK_B [--label-a N] [--label-b N]"},
       "overlap of two masks on one grid: IoU, Dice, differing voxels",
       "Compares two masks on the same grid voxel by voxel and prints their intersection over union, Dice "
       "coefficient and the number of voxels that differ.",
       {{"--label-a", "N", "every nonzero voxel", "the label of MASK_A to compare"},
        {"--label-b", "N", "every nonzero voxel", "the label of MASK_B to compare"}},
       {"soiq compare ours.nii.gz theirs.nii.gz"},
       run_compare},
  };
}

}  // namespace soiq::cli
