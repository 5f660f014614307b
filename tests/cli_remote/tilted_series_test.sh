#!/usr/bin/env bash
# A gantry-tilted series through a real soiqd with the real `soiq`: STS_002's CT resampled onto a
# sheared stack as a new series (tests/dicom/shear_series.py: each slice's first pixel k x (0.37,
# 0.21) pixels further, 7.2 degrees) imported with its real RT Structure Set, the original beside it; the structure's voxels are those of
# the sheared grid (tests/dicom/tilted_series_test.cpp checks them against pydicom), its volume that
# of the original CT's GTV to 2 %; features on the series; SEG and RT Structure Set exports that
# dciodvfy finds no error in and that import back to the same voxels; a shell region refused with
# exit 4 and one line.
# Usage: tilted_series_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"
command -v dciodvfy >/dev/null || fail "dciodvfy is not installed (dicom3tools; scripts/install-deps)"

ct="$data/sts/STS_002/dicom/CT"
# Debian's python3 (python3-pydicom), whatever python3 comes first on PATH.
/usr/bin/python3 "$(dirname "$0")/../dicom/shear_series.py" "$ct/image" "$tmp/image" 0.37 0.21 "$ct/mask" \
  >"$tmp/tilt.out" || fail "shear_series.py: $(cat "$tmp/tilt.out")"

start_soiqd main
export SOIQ_SERVER=$server
"$soiq" import "$tmp/image" --format csv >"$tmp/import.csv" 2>"$tmp/import.err" ||
  fail "import of the tilted CT: $(cat "$tmp/import.err")"
id=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/import.csv")
[ -n "$id" ] || fail "no structure imported: $(cat "$tmp/import.csv" "$tmp/import.err")"
# The original CT joins the study as a second CT series: the tilted one is named by its uid.
series=$(awk -F, '$1 == "series" { print $2; exit }' "$tmp/import.csv")
[ -n "$series" ] || fail "no series row: $(cat "$tmp/import.csv")"

# Its volume: voxels of the sheared grid (count x the parallelepiped's volume), the original's to 2 %.
volume() {
  "$soiq" features "$1" --series "$2" --features voxel_volume_mm3 --format csv |
    awk -F, '$3 == "voxel_volume_mm3" { print $4 }'
}
tilted=$(volume "$id" "$series")
"$soiq" convert "$id" --series "$series" -o "$tmp/tilted.nii.gz" >"$tmp/convert.out" || fail "convert: $(cat "$tmp/convert.out")"
"$soiq" import "$ct" --format csv >"$tmp/orig.csv" 2>"$tmp/orig.err" || fail "import of the original: $(cat "$tmp/orig.err")"
orig_id=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/orig.csv")
orig_series=$(awk -F, '$1 == "series" { print $2; exit }' "$tmp/orig.csv")
original=$(volume "$orig_id" "$orig_series")
echo "GTV on the tilted CT $tilted mm3, on the original $original mm3"
within "tilted GTV volume" "$tilted" "$original" "$(awk -v v="$original" 'BEGIN { print 0.02 * v }')"
# Intensity features read the sheared CT on its own voxels.
"$soiq" features "$id" --series "$series" --image "$series" --features mean,voxel_count --format csv >"$tmp/f.csv" 2>&1 ||
  fail "features with the CT: $(cat "$tmp/f.csv")"
grep -q ',mean,' "$tmp/f.csv" || fail "no mean: $(cat "$tmp/f.csv")"

# The voxels a file of the structure holds, as `soiq compare` counts them against the conversion.
same_voxels() {
  "$soiq" convert "$1" --series "$series" -o "$tmp/$2.nii.gz" >/dev/null || fail "convert $2"
  grep -q "^identical" <<<"$("$soiq" compare "$tmp/tilted.nii.gz" "$tmp/$2.nii.gz")" ||
    fail "$2 differs: $("$soiq" compare "$tmp/tilted.nii.gz" "$tmp/$2.nii.gz")"
}

# SEG: one frame per tilted slice at its own position.
"$soiq" export-seg "$id" -o "$tmp/seg/gtv.dcm" >"$tmp/seg.out" || fail "export-seg: $(cat "$tmp/seg.out")"
dciodvfy "$tmp/seg/gtv.dcm" >"$tmp/seg.log" 2>&1
grep -q "Segmentation" "$tmp/seg.log" || fail "dciodvfy did not check a SEG: $(cat "$tmp/seg.log")"
grep "^Error" "$tmp/seg.log" && fail "dciodvfy finds errors in the SEG of a tilted series"
"$soiq" import "$tmp/seg/gtv.dcm" --format csv >"$tmp/seg.csv" 2>"$tmp/seg.err" || fail "SEG back: $(cat "$tmp/seg.err")"
seg_id=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/seg.csv")
[ -n "$seg_id" ] || fail "SEG back stored no structure: $(cat "$tmp/seg.csv" "$tmp/seg.err")"
same_voxels "$seg_id" seg_back

# RT Structure Set: the surface cut by each tilted plane.
"$soiq" export-rtstruct "$id" -o "$tmp/rt/gtv.dcm" >"$tmp/rt.out" || fail "export-rtstruct: $(cat "$tmp/rt.out")"
dciodvfy "$tmp/rt/gtv.dcm" >"$tmp/rt.log" 2>&1
grep -q "RTStructureSet" "$tmp/rt.log" || fail "dciodvfy did not check an RT Structure Set: $(cat "$tmp/rt.log")"
grep "^Error" "$tmp/rt.log" && fail "dciodvfy finds errors in the RT Structure Set of a tilted series"
"$soiq" import "$tmp/rt/gtv.dcm" --format csv >"$tmp/rt.csv" 2>"$tmp/rt.err" || fail "RTSTRUCT back: $(cat "$tmp/rt.err")"
rt_id=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/rt.csv")
[ -n "$rt_id" ] || fail "RTSTRUCT back stored no structure: $(cat "$tmp/rt.csv" "$tmp/rt.err")"
same_voxels "$rt_id" rt_back

# Distances in mm along axes that lean: refused, one line, exit 4 (FAILED_PRECONDITION).
expect 4 "gantry-tilted or unevenly spaced series; use the inside region" -- "$soiq" features "$id" --series "$series" --image "$series" --features mean --region shell:3


finish tilted_series_test
