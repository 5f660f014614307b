#!/usr/bin/env bash
# `soiq export-seg --fractional` end to end: a real soiqd, STS_002 imported, its CT and PET GTVs
# written as FRACTIONAL (OCCUPANCY) SEGs. Each is checked by dicom3tools' dciodvfy (no error, and no
# warning the binary SEG of the same structure does not have) and by pydicom
# (fractional_seg_check.py): its header, each frame placed by its position and its referenced
# slice, its bytes equal to `soiq convert --fractional` of the same structure on the same series,
# the summed volume equal to convert's, other UIDs than the binary SEG's. Refusals: --oversample
# without --fractional and --float32 (exit 2, one line).
# Usage: fractional_seg_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"
check=$(dirname "$0")/fractional_seg_check.py

command -v dciodvfy >/dev/null || { echo "FAIL: dciodvfy is not installed (Debian package dicom3tools)"; exit 1; }
/usr/bin/python3 -c "import pydicom" 2>/dev/null || { echo "FAIL: pydicom is not installed (Debian package python3-pydicom)"; exit 1; }

start_soiqd main
export SOIQ_SERVER=$server
"$soiq" import "$data/sts/STS_002/dicom" --format csv >"$tmp/import.csv" 2>"$tmp/import.err" ||
  fail "import: $(cat "$tmp/import.err")"

# structure MODALITY OVERSAMPLE: a fractional SEG of that GTV checked against convert --fractional.
check_structure() {
  local modality=$1 n=$2
  local id series
  id=$(sed -n "s/^structure,\([0-9]*\),STS_002,\"GTV_Mass_$modality,.*/\1/p" "$tmp/import.csv")
  series=$(sed -n "s/^structure,[0-9]*,STS_002,\"GTV_Mass_$modality, [0-9]* voxels on series \([0-9.]*\)\"/\1/p" "$tmp/import.csv")
  [ -n "$id" ] && [ -n "$series" ] || { fail "import rows lack GTV_Mass_$modality: $(cat "$tmp/import.csv")"; return; }
  local seg=$tmp/$modality.dcm binary=$tmp/${modality}_binary.dcm
  local line
  line=$("$soiq" export-seg "$id" -o "$seg" --fractional --oversample "$n") || { fail "export-seg --fractional: $line"; return; }
  grep -q "(FRACTIONAL, ${n}x${n} lines per voxel): 1 segment, [0-9]* frames" <<<"$line" || fail "export-seg says: $line"
  "$soiq" export-seg "$id" -o "$binary" >/dev/null || fail "binary export-seg of $modality"
  dciodvfy "$seg" >"$tmp/$modality.vfy" 2>&1
  grep -q "^Error" "$tmp/$modality.vfy" && fail "dciodvfy finds errors in the $modality fractional SEG: $(grep "^Error" "$tmp/$modality.vfy")"
  dciodvfy "$binary" >"$tmp/${modality}_binary.vfy" 2>&1
  local extra
  extra=$(comm -23 <(grep "^Warning" "$tmp/$modality.vfy" | sort -u) <(grep "^Warning" "$tmp/${modality}_binary.vfy" | sort -u))
  [ -z "$extra" ] || fail "dciodvfy warns of the $modality fractional SEG only: $extra"
  line=$("$soiq" convert "$id" --series "$series" --fractional --oversample "$n" -o "$tmp/$modality.nii") ||
    { fail "convert --fractional: $line"; return; }
  local mm3
  mm3=$(sed -n 's/.* \([0-9.]*\) mm3 by fractions .*/\1/p' <<<"$line")
  [ -n "$mm3" ] || { fail "convert summary: $line"; return; }
  /usr/bin/python3 "$check" "$seg" "$tmp/$modality.nii" "$data/sts/STS_002/dicom" "$mm3" "$binary" >"$tmp/$modality.check" 2>&1 ||
    fail "$modality: $(cat "$tmp/$modality.check")"
  echo "$modality GTV, ${n}x${n} lines: $(cat "$tmp/$modality.check")"
}
check_structure CT 4
check_structure PET 2

ct_id=$(sed -n 's/^structure,\([0-9]*\),STS_002,"GTV_Mass_CT,.*/\1/p' "$tmp/import.csv")
expect 2 "add --fractional" -- "$soiq" export-seg "$ct_id" --oversample 2 -o "$tmp/x.dcm"
expect 2 "--float32" -- "$soiq" export-seg "$ct_id" --fractional --float32 -o "$tmp/x.dcm"
expect 2 "--oversample" -- "$soiq" export-seg "$ct_id" --fractional --oversample 9 -o "$tmp/x.dcm"
[ -e "$tmp/x.dcm" ] && fail "a refused export left a file"

finish fractional_seg_test
