#!/usr/bin/env bash
# Gantry-tilted and unevenly spaced series through a real soiqd with the real `soiq`: STS_002's CT
# altered as new series (tests/dicom/altered_series.py): resampled onto a sheared stack (each
# slice's first pixel k x (0.37, 0.21) pixels further, 7.2 degrees), and also thinned (every other
# slice of 10..30 left out, with the contours on them: 3.27 to 6.54 mm apart), each imported with
# its real RT Structure Set beside the original. Their structures' voxels are those of the series'
# own grids (tests/dicom/irregular_stacks_test.cpp checks them against pydicom); features on those
# grids; SEG and RT Structure Set exports that dciodvfy finds no error in and that import back to
# the same voxels; a shell region refused with exit 4 and one line, and NIfTI too for the uneven
# one, saying what to do instead.
# Usage: irregular_stacks_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"
command -v dciodvfy >/dev/null || fail "dciodvfy is not installed (dicom3tools; scripts/install-deps)"

ct="$data/sts/STS_002/dicom/CT"
start_soiqd main
export SOIQ_SERVER=$server

"$soiq" import "$ct" --format csv >"$tmp/orig.csv" 2>"$tmp/orig.err" || fail "import of the original: $(cat "$tmp/orig.err")"
orig_id=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/orig.csv")
orig_series=$(awk -F, '$1 == "series" { print $2; exit }' "$tmp/orig.csv")

feature() {  # ID SERIES NAME: the structure's feature on the series' grid
  "$soiq" features "$1" --series "$2" --features "$3" --format csv | awk -F, -v n="$3" '$3 == n { print $4 }'
}

# Imports DIR, sets id and series, and checks that the SEG and RT Structure Set exports of the
# structure import back with its voxel count on the same series.
import_and_export() {
  local name=$1 dir=$2
  "$soiq" import "$dir" --format csv >"$tmp/$name.csv" 2>"$tmp/$name.err" ||
    fail "import of the $name CT: $(cat "$tmp/$name.err")"
  id=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/$name.csv")
  series=$(awk -F, '$1 == "series" { print $2; exit }' "$tmp/$name.csv")
  [ -n "$id" ] && [ -n "$series" ] || fail "$name: no structure or series: $(cat "$tmp/$name.csv" "$tmp/$name.err")"
  local count
  count=$(feature "$id" "$series" voxel_count)
  [ -n "$count" ] && [ "$count" -gt 1000 ] || fail "$name: voxel count '$count'"
  "$soiq" export-seg "$id" -o "$tmp/$name/seg.dcm" >"$tmp/$name.seg.out" || fail "$name export-seg: $(cat "$tmp/$name.seg.out")"
  "$soiq" export-rtstruct "$id" -o "$tmp/$name/rt.dcm" >"$tmp/$name.rt.out" ||
    fail "$name export-rtstruct: $(cat "$tmp/$name.rt.out")"
  local object back
  for object in seg rt; do
    dciodvfy "$tmp/$name/$object.dcm" >"$tmp/$name.$object.log" 2>&1
    grep -q "Segmentation\|RTStructureSet" "$tmp/$name.$object.log" || fail "dciodvfy did not run: $(cat "$tmp/$name.$object.log")"
    grep "^Error" "$tmp/$name.$object.log" && fail "dciodvfy finds errors in the $object of the $name CT"
    "$soiq" import "$tmp/$name/$object.dcm" --format csv >"$tmp/$name.$object.csv" 2>&1 ||
      fail "$name $object back: $(cat "$tmp/$name.$object.csv")"
    back=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/$name.$object.csv")
    [ -n "$back" ] || fail "$name $object back stored no structure: $(cat "$tmp/$name.$object.csv")"
    [ "$(feature "$back" "$series" voxel_count)" = "$count" ] ||
      fail "$name $object back has $(feature "$back" "$series" voxel_count) voxels, not $count"
  done
  # Distances in mm along axes that lean or are unevenly spaced: refused, one line, exit 4.
  expect 4 "gantry-tilted or unevenly spaced series; use the inside region" -- \
    "$soiq" features "$id" --series "$series" --image "$series" --features mean --region shell:3
}

# Sheared: the tumour's volume is the original's to 2 %, and NIfTI holds the sheared grid.
/usr/bin/python3 "$(dirname "$0")/../dicom/altered_series.py" "$ct/image" "$tmp/sheared" --shear 0.37 0.21 "$ct/mask" \
  >"$tmp/sheared.out" || fail "altered_series.py: $(cat "$tmp/sheared.out")"
import_and_export sheared "$tmp/sheared"
tilted=$(feature "$id" "$series" voxel_volume_mm3)
original=$(feature "$orig_id" "$orig_series" voxel_volume_mm3)
echo "GTV on the tilted CT $tilted mm3, on the original $original mm3"
within "tilted GTV volume" "$tilted" "$original" "$(awk -v v="$original" 'BEGIN { print 0.02 * v }')"
"$soiq" features "$id" --series "$series" --image "$series" --features mean --format csv >"$tmp/f.csv" 2>&1 ||
  fail "features with the tilted CT: $(cat "$tmp/f.csv")"
grep -q ',mean,' "$tmp/f.csv" || fail "no mean: $(cat "$tmp/f.csv")"
"$soiq" convert "$id" --series "$series" -o "$tmp/sheared.nii.gz" >/dev/null || fail "NIfTI of the sheared grid"

# Sheared and thinned: unevenly spaced slices, shown as such; NIfTI cannot hold them.
/usr/bin/python3 "$(dirname "$0")/../dicom/altered_series.py" "$ct/image" "$tmp/thinned" --shear 0.37 0.21 \
  --thin 10 30 "$ct/mask" >"$tmp/thinned.out" || fail "altered_series.py: $(cat "$tmp/thinned.out")"
import_and_export thinned "$tmp/thinned"
grep -q "slices unevenly spaced, tilted 7.2" "$tmp/thinned.csv" || fail "the series row: $(cat "$tmp/thinned.csv")"
expect 4 "NIfTI, NRRD and MetaImage hold evenly spaced slices only" -- \
  "$soiq" convert "$id" --series "$series" -o "$tmp/thinned.nii.gz"
[ -e "$tmp/thinned.nii.gz" ] && fail "a refused conversion left a file"

finish irregular_stacks_test
