#!/usr/bin/env bash
# soiq's RT Structure Set contour rules end to end against a real soiqd: STS_002's CT imported with
# structure sets made from its own (tests/cli_remote/contour_rules_make.py). A contour 0.3 of the
# slice spacing off its plane goes to the nearest slice (the same voxels as the original); a contour
# with a point 2 mm off its plane leaves out its own ROI only, the problem naming the ROI, the
# contour and the distance in mm; a structure set that stores no structure makes the import exit
# non-zero, the CT still imported.
# Usage: contour_rules_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"

start_soiqd main
export SOIQ_SERVER=$server
ct="$data/sts/STS_002/dicom/CT/image"
rs="$data/sts/STS_002/dicom/CT/mask/RS.dcm"
spacing=3.27
# Debian's python3 (python3-pydicom), whatever python3 comes first on PATH.
/usr/bin/python3 "$(dirname "$0")/contour_rules_make.py" "$rs" "$tmp" "$spacing" || fail "making the structure sets"

# The original first: its GTV's voxels are the reference.
"$soiq" import "$ct" "$rs" --format csv >"$tmp/orig.csv" 2>"$tmp/orig.err" || fail "import of the original: $(cat "$tmp/orig.err")"
orig_id=$(awk -F, '$1 == "structure" { print $2; exit }' "$tmp/orig.csv")
[ -n "$orig_id" ] || fail "the original GTV was not imported: $(cat "$tmp/orig.csv" "$tmp/orig.err")"

"$soiq" import "$tmp/three_rois.dcm" --format csv >"$tmp/three.csv" 2>"$tmp/three.err"
code=$?
[ "$code" -eq 0 ] || fail "three ROIs, two sound: exit $code, expected 0: $(cat "$tmp/three.err")"
[ "$(grep -c '^structure,' "$tmp/three.csv")" -eq 2 ] || fail "not two structures stored: $(cat "$tmp/three.csv")"
grep -q "ROI 'strayed' (number 2) skipped: refused: contour 0 is not planar: a point lies 2 mm from the contour's plane" \
  "$tmp/three.err" || fail "the strayed ROI's problem: $(cat "$tmp/three.err")"
grep -q "sound A\|sound B" "$tmp/three.err" && fail "a sound ROI is named among the problems: $(cat "$tmp/three.err")"
# 'sound B', 0.3 of a spacing off, has the original's voxels.
b_id=$(awk -F, '$1 == "structure" && $4 ~ /^"sound B/ { print $2 }' "$tmp/three.csv")
[ -n "$b_id" ] || fail "sound B not listed: $(cat "$tmp/three.csv")"
"$soiq" convert "$orig_id" --series-modality CT -o "$tmp/orig.nii.gz" >/dev/null || fail "convert original"
"$soiq" convert "$b_id" --series-modality CT -o "$tmp/b.nii.gz" >/dev/null || fail "convert sound B"
grep -q "^identical" <<<"$("$soiq" compare "$tmp/orig.nii.gz" "$tmp/b.nii.gz")" ||
  fail "contours 0.3 of a spacing off do not give the original's voxels: $("$soiq" compare "$tmp/orig.nii.gz" "$tmp/b.nii.gz")"

# Every contour midway between slices: nothing stored from the set, exit 4 (FAILED_PRECONDITION).
"$soiq" import "$ct" "$tmp/between.dcm" >"$tmp/between.out" 2>"$tmp/between.err"
code=$?
[ "$code" -eq 4 ] || fail "a structure set that stores nothing: exit $code, expected 4: $(cat "$tmp/between.err")"
grep -q "contour 0 lies 1.63 mm from the nearest image plane" "$tmp/between.err" || fail "distance not named: $(cat "$tmp/between.err")"
grep -q "soiq import: 1 structure set stored no structure (between.dcm" "$tmp/between.err" ||
  fail "the failure line: $(cat "$tmp/between.err")"
[ "$(tail -1 "$tmp/between.err" | grep -c 'stored no structure')" -eq 1 ] || fail "the last line is not the failure"

finish contour_rules_test
