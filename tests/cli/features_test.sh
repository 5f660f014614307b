#!/usr/bin/env bash
# `soiq features` end to end: the IBSI phantom's published values through the command line, a real
# STS tumour with PET uptake inside and around it, every output format, and each bad input answered
# with its exit code and one readable line.
# Usage: features_test.sh SOIQ_BINARY TEST_DATA_DIR
soiq=$1
data=$2
source "$(dirname "$0")/lib.sh"

phantom="$data/ibsi_digital_phantom"
"$soiq" features "$phantom/mask.nii.gz" --image "$phantom/phantom.nii.gz" --ibsi --format csv >"$tmp/ibsi.csv" ||
  fail "features of the IBSI phantom"
get() { awk -F, -v r="$1" -v n="$2" '$1 == r && $3 == n { print $4 }' "$tmp/ibsi.csv"; }
# IBSI reference values and tolerances (REFERENCE_VALUES.md).
within mesh_volume_mm3 "$(get "" mesh_volume_mm3)" 556 4
within surface_area_mm2 "$(get "" surface_area_mm2)" 388 3
within sphericity "$(get "" sphericity)" 0.843 0.005
within major_axis_length_mm "$(get "" major_axis_length_mm)" 11.4 0.1
within mean "$(get inside mean)" 2.15 0.005
within p90 "$(get inside p90)" 4 0.0001
within energy "$(get inside energy)" 567 0.5

# A real tumour (STS_002, its CT mask) with the patient's PET: uptake inside and in a 5 mm shell.
sts="$data/sts/STS_002"
json=$("$soiq" features "$sts/CT_mask.nii.gz" --image "PET=$sts/PET_image.nii.gz" --region inside --region shell:5 \
  --features voxel_volume_mm3,sphericity,mean --format json) || fail "features of STS_002"
echo "$json" | grep -qE '^\{"voxel_volume_mm3": [0-9.]+, "sphericity": 0\.[0-9]+, "intensity": \{"inside": \{"PET": \{"mean": [0-9.]+\}\}, "shell:5": \{"PET": \{"mean": [0-9.]+\}\}\}, "timings_ms": \{' ||
  fail "json shape: $json"

# A surface model: converted on the mask's grid, its own surface values and the mask surface's.
"$soiq" mesh "$sts/PET_mask.nii.gz" -o "$tmp/pet.vtp" >/dev/null || fail "soiq mesh"
"$soiq" features "$tmp/pet.vtp" --reference "$sts/PET_mask.nii.gz" --features mesh_volume_mm3,mask_mesh_volume_mm3 \
  --format csv >"$tmp/s.csv" || fail "features of a surface model"
[ "$(grep -c mesh_volume_mm3 "$tmp/s.csv")" -eq 2 ] || fail "surface and mask surface values: $(cat "$tmp/s.csv")"

expect 2 "unknown feature 'bogus'" -- "$soiq" features "$phantom/mask.nii.gz" --features bogus
expect 2 "need an image" -- "$soiq" features "$phantom/mask.nii.gz" --features mean
expect 2 "radius" -- "$soiq" features "$phantom/mask.nii.gz" --image "$phantom/phantom.nii.gz" --region shell:0
expect 2 "accepted\|inside" -- "$soiq" features "$phantom/mask.nii.gz" --image "$phantom/phantom.nii.gz" --region around
expect 2 "empty" -- "$soiq" features "$phantom/mask.nii.gz" --image "$phantom/phantom.nii.gz" --region core:40
expect 2 "frame of reference" -- "$soiq" features "$phantom/mask.nii.gz" --image "$sts/PET_image.nii.gz" --features mean
expect 3 "not" -- "$soiq" features "$tmp/missing.nii.gz"
expect 2 "--format" -- "$soiq" features "$phantom/mask.nii.gz" --format xml
# Two images of one name would share their keys in the output: refused, naming it.
expect 2 "image name 'phantom' is given twice" -- "$soiq" features "$phantom/mask.nii.gz" \
  --image "$phantom/phantom.nii.gz" --image "$phantom/phantom.nii.gz" --features mean
# A radius far beyond the grid answers at once (it used to loop over a billion offset lines) with
# every outside voxel of the grid: 5x4x4 = 80, of which the mask holds 74.
"$soiq" features "$phantom/mask.nii.gz" --image "$phantom/phantom.nii.gz" --region shell:1e9 --features voxel_count \
  --format csv >"$tmp/huge.csv" || fail "features in shell:1e9"
[ "$(awk -F, '$1 == "shell:1e+09" && $3 == "voxel_count" { print $4 }' "$tmp/huge.csv")" = 6 ] ||
  fail "shell:1e9 should hold the grid's 6 outside voxels: $(cat "$tmp/huge.csv")"

# The catalogue: docs/FEATURES.md's table is `soiq features --list --format markdown`, so the docs
# cannot drift from the code; --list names every feature in every format.
"$soiq" features --list --format markdown >"$tmp/list.md" || fail "features --list --format markdown"
sed -n '/^| name | family/,/^$/p' "$data/../../docs/FEATURES.md" | sed '/^$/d' >"$tmp/doc.md"
diff -u "$tmp/doc.md" "$tmp/list.md" >"$tmp/doc.diff" ||
  fail "docs/FEATURES.md's table differs from 'soiq features --list --format markdown': $(head -20 "$tmp/doc.diff")"
"$soiq" features --list --format csv >"$tmp/list.csv" || fail "features --list --format csv"
grep -q '^sphericity,surface,,surface,' "$tmp/list.csv" || fail "features --list csv lacks sphericity: $(cat "$tmp/list.csv")"
"$soiq" features --list >"$tmp/list.txt" || fail "features --list"
grep -q '^centre_of_mass_shift_mm ' "$tmp/list.txt" || fail "features --list lacks centre_of_mass_shift_mm"
expect 2 "--list takes no INPUT" -- "$soiq" features --list "$phantom/mask.nii.gz"
expect 2 "unknown feature 'mask_voxel_count'" -- "$soiq" features "$phantom/mask.nii.gz" --features mask_voxel_count

finish features_test
