// The rows of the commands that store, list, show, remove and fetch records on soiqd in the
// command table: upload, upload-image, import, export-seg, render, ls, show, rm, download.
#include "client/cli/command_table.h"
#include "client/cli/download_command.h"
#include "client/cli/export_rt_struct_command.h"
#include "client/cli/export_seg_command.h"
#include "client/cli/import_command.h"
#include "client/cli/ls_command.h"
#include "client/cli/render_command.h"
#include "client/cli/rm_command.h"
#include "client/cli/show_command.h"
#include "client/cli/upload_command.h"
#include "client/cli/upload_image_command.h"

namespace soiq::cli {

std::vector<CommandSpec> record_commands() {
  const OptionSpec patient = {"--patient", "ID", "", "the patient id (required)"};
  const OptionSpec study = {"--study", "UID", "", "the study instance uid (required)"};
  const OptionSpec sex = {"--sex", "M|F|O", "", "the patient's sex"};
  const OptionSpec birth = {"--birth-date", "YYYYMMDD", "", "the patient's birth date"};
  const OptionSpec study_date = {"--study-date", "YYYYMMDD", "", "the study's date"};
  const OptionSpec description = {"--description", "TEXT", "", "the study's description"};
  const OptionSpec rows = {"--format", "table|json|csv", "table", "output format"};
  const OptionSpec output = {"-o", "OUT", "", "the file to write", "--output"};
  const OptionSpec wait = {"--wait", "", "",
                           "return once soiqd has computed the default features of what it queued (precompute)"};
  return {
      {"upload",
       CommandGroup::kRemote,
       {"upload MESH --patient ID --study UID --name NAME [--laterality L|R] [--sex M|F|O]",
        "       [--birth-date YYYYMMDD] [--study-date YYYYMMDD] [--modality MR] [--description D]",
        "       [--ras] [--robust] [--wait] [--quiet]"},
       "stores a surface model; prints its structure id and whether the surface was deduplicated",
       "Sends a surface model (.stl .obj .ply .vtk .vtp) with its patient and study to soiqd, which checks "
       "it, converts it and stores it. Prints the new structure id (with --quiet, only the id).",
       {patient,
        study,
        {"--name", "NAME", "", "the structure's name, e.g. hippocampus (required)"},
        {"--laterality", "L|R", "", "the structure's side"},
        sex,
        birth,
        study_date,
        {"--modality", "M", "", "the study's modality (MR, CT, PT)"},
        description,
        {"--ras", "", "LPS", "the file's coordinates are RAS, not LPS"},
        {"--robust", "", "", "accept open or self-intersecting surfaces"},
        wait},
       {"soiq upload brain1.vtp --patient P1 --study 1.2.3 --name hippocampus --laterality L",
        "id=$(soiq upload --quiet brain1.vtp --patient P1 --study 1.2.3 --name hippocampus)"},
       run_upload_command},
      {"upload-image",
       CommandGroup::kRemote,
       {"upload-image IMAGE --patient ID --study UID --series UID --modality PT [--sex ..] [--birth-date ..]",
        "             [--study-date ..] [--description D]"},
       "stores an image series (.nii .nii.gz .nrrd .mha): a target grid and the image of intensity features",
       "Sends an image with its patient, study and series to soiqd. The series can then be a conversion's "
       "target grid (--series UID) and the image of intensity features (--image MODALITY).",
       {patient,
        study,
        {"--series", "UID", "", "the series instance uid (required)"},
        {"--modality", "M", "", "the series' modality: MR, CT, PT, ... (required)"},
        sex,
        birth,
        study_date,
        description},
       {"soiq upload-image pet.nii.gz --patient P1 --study 1.2.3 --series 1.2.3.4 --modality PT"},
       run_upload_image_command},
      {"import",
       CommandGroup::kRemote,
       {"import PATH... [--format table|json|csv] [--wait] [--replace]"},
       "sends DICOM files and folders (recursively) to soiqd: CT, MR and PET series become images, RT "
       "Structure Set ROIs structures on their series' grid; prints what was imported, problems on stderr",
       "Sends DICOM files and folders (recursively) to soiqd: CT, MR and PET series become images, RT "
       "Structure Set ROIs structures on their series' grid. Prints what was imported; problems on stderr.",
       {rows,
        wait,
        {"--replace", "", "",
         "replace what soiqd stores under the same DICOM UIDs with the files' content (without it, a series, RT "
         "Structure Set or SEG stored with other content is refused, naming the UID and what differs)"}},
       {"soiq import data/STS_002/", "soiq import --wait data/STS_002/"},
       run_import_command},
      {"export-seg",
       CommandGroup::kRemote,
       {"export-seg ID... -o OUT.dcm [--description TEXT] [--fractional [--oversample N]]"},
       "imported structures as one binary DICOM SEG on the image series they were drawn on",
       "Writes imported structures as one binary DICOM Segmentation on the image series they were drawn "
       "on, one segment per structure. With --fractional the SEG is FRACTIONAL (OCCUPANCY): each pixel the "
       "fraction of its voxel inside the structure, 0-255 (0 wholly outside, 255 wholly inside), as 'soiq "
       "convert --fractional' computes it; OHIF and dcmqi read only binary SEGs, highdicom and pydicom read "
       "both.",
       {output,
        {"--description", "TEXT", "", "the SEG series' description"},
        {"--fractional", "", "binary", "a FRACTIONAL SEG of coverage fractions (OCCUPANCY, 0-255)"},
        {"--oversample", "N", "4", "with --fractional: N x N lines across each voxel (1-8; exact along rows)"}},
       {"soiq export-seg 1 2 -o seg.dcm", "soiq export-seg 1 -o gtv_fractions.dcm --fractional"},
       run_export_seg_command},
      {"export-rtstruct",
       CommandGroup::kRemote,
       {"export-rtstruct ID... -o OUT.dcm [--description TEXT]"},
       "imported structures as one DICOM RT Structure Set on the image series they were drawn on",
       "Writes imported structures as one DICOM RT Structure Set on the image series they were drawn on, one "
       "ROI per structure: each stored surface cut into closed planar contours on every slice plane of that "
       "series (holes and separate parts as separate contours), each contour referencing its slice.",
       {output, {"--description", "TEXT", "", "the RT Structure Set series' description"}},
       {"soiq export-rtstruct 1 2 -o rtstruct.dcm"},
       run_export_rt_struct_command},
      {"render",
       CommandGroup::kRemote,
       {"render ID [--image MODALITY|SERIES_UID|none] [--plane axial|coronal|sagittal]",
        "       [--slice K | --through largest|centroid | --montage] [--window C,W] [--width PX]",
        "       [--patient-caption] [--quality Q] -o FILE.png|.svg|.jpg"},
       "a picture of a structure over a slice of its image",
       "Draws a stored structure over a slice of its image, as soiqd converts it: the windowed slice, the "
       "structure's voxels filled and outlined, a scale bar, orientation letters from the image's direction "
       "cosines and a caption without patient data. A structure without images is drawn as its mask alone. "
       "The picture's format follows FILE's extension.",
       {output,
        {"--image", "MODALITY|SERIES_UID|none", "",
         "the image under the structure: a series of its study by modality or uid; default: the series it "
         "was imported on, else the study's first; none: the mask alone"},
        {"--plane", "axial|coronal|sagittal", "axial", "the plane of the slice"},
        {"--slice", "K", "", "the slice number along the plane's normal (0-based, as the grid numbers it)"},
        {"--through", "largest|centroid", "largest",
         "the slice holding most of the structure, or the one holding its centroid"},
        {"--montage", "", "", "every slice holding the structure, side by side"},
        {"--window", "C,W", "", "the window's centre and width (default: from the image, robust percentiles)"},
        {"--width", "PX", "", "the picture's width in pixels (default: 512 for a slice, 256 per montage tile)"},
        {"--patient-caption", "", "", "add the patient id and study date to the caption"},
        {"--quality", "Q", "90", "JPEG quality 1..100"}},
       {"soiq render 1 -o gtv.png", "soiq render 1 --image PT --through centroid --window 2.5,5 -o gtv_pet.png",
        "soiq render 1 --montage -o gtv_all.svg"},
       run_render_command},
      {"ls",
       CommandGroup::kRemote,
       {"ls [patients|studies|structures] [--patient ID|GLOB] [--study UID] [--name GLOB] [--laterality L|R]",
        "   [--sex M|F|O] [--format table|json|csv] [--all | --page-size N]"},
       "lists patients, studies or structures",
       "Lists the patients (default), studies or structures soiqd holds, a page at a time (or --all).",
       {{"--patient", "ID|GLOB", "",
         "only this patient; for patients and structures also a glob (* and ?), e.g. 'DEMO_*'"},
        {"--study", "UID", "", "structures of this study"},
        {"--name", "GLOB", "", "structures of this name"},
        {"--laterality", "L|R", "", "structures of this side"},
        {"--sex", "M|F|O", "", "patients of this sex"},
        rows,
        {"--all", "", "", "every page"},
        {"--page-size", "N", "100", "rows per page"}},
       {"soiq ls structures --name 'hippo*' --laterality L", "soiq ls patients --all --format csv"},
       run_ls_command},
      {"show",
       CommandGroup::kRemote,
       {"show patient ID | study UID | [structure] ID [--format text|json]"},
       "one record in full",
       "Prints one patient, study or structure in full. A bare number is a structure id.",
       {{"--format", "text|json", "text", "output format"}},
       {"soiq show 4", "soiq show patient P1 --format json"},
       run_show_command},
      {"rm",
       CommandGroup::kRemote,
       {"rm structure ID | patient ID"},
       "removes a structure, or a patient with everything of theirs",
       "Removes one structure, or one patient with their studies, series and structures.",
       {},
       {"soiq rm structure 4"},
       run_rm_command},
      {"download",
       CommandGroup::kRemote,
       {"download ID -o OUT.{stl,obj,ply,vtk,vtp} [--ras]"},
       "a stored structure's surface model",
       "Writes a stored structure's surface model; its extension chooses the format.",
       {output, {"--ras", "", "LPS", "write RAS coordinates instead of LPS"}},
       {"soiq download 4 -o hippocampus.stl"},
       run_download_command},
  };
}

}  // namespace soiq::cli
