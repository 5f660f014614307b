#!/bin/bash
# `soiq mesh` on real files: a mesh run per output format, and the exit codes of its errors.
# Usage: bash mesh_test.sh /path/to/soiq /path/to/tests/data
set -u
soiq=$1
data=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# expect_exit CODE STDERR_PHRASE ARGS...: runs soiq with ARGS, checks the exit code and stderr.
expect_exit() {
  local want=$1 phrase=$2
  shift 2
  "$soiq" "$@" >"$out/stdout" 2>"$out/stderr"
  local got=$?
  [ "$got" -eq "$want" ] || fail "soiq $* exited $got, expected $want ($(cat "$out/stderr"))"
  grep -q -- "$phrase" "$out/stderr" || fail "soiq $* stderr lacks '$phrase': $(cat "$out/stderr")"
  grep -q '^soiq mesh: ' "$out/stderr" || fail "soiq $* stderr does not start with 'soiq mesh: '"
}

# A real label map: every format writes, the summary line is printed, and the STL is binary.
for ext in stl vtk vtp ply obj; do
  line=$("$soiq" mesh "$data/pyradiomics/brain1_label.nrrd" -o "$out/brain1.$ext" --label 1)
  code=$?
  [ "$code" -eq 0 ] || fail "mesh to .$ext exited $code"
  [ -s "$out/brain1.$ext" ] || fail "mesh to .$ext wrote no file"
  echo "$line" | grep -Eq "^[0-9]+ triangles, [0-9]+ vertices, mesh volume [0-9.]+ mm3 -> $out/brain1.$ext$" ||
    fail "unexpected summary line for .$ext: $line"
done
# Binary STL: 84 + 50 * n bytes, with n from the summary line.
triangles=$("$soiq" mesh "$data/pyradiomics/brain1_label.nrrd" -o "$out/again.stl" --label 1 | cut -d' ' -f1)
size=$(stat -c %s "$out/again.stl")
[ "$size" -eq $((84 + 50 * triangles)) ] || fail "STL has $size bytes for $triangles triangles"

# A NIfTI mask with the default (nonzero) label.
"$soiq" mesh "$data/sts/STS_002/CT_mask.nii.gz" -o "$out/sts.vtp" >/dev/null || fail "mesh of an STS NIfTI mask failed"

# Errors and their exit codes (STYLE.md section 3).
expect_exit 3 "does not exist" mesh "$data/no_such_mask.nrrd" -o "$out/x.stl"
expect_exit 2 "unknown mesh extension" mesh "$data/pyradiomics/brain1_label.nrrd" -o "$out/x.xyz"
expect_exit 2 "no voxels with label 99" mesh "$data/pyradiomics/brain1_label.nrrd" -o "$out/x.stl" --label 99
expect_exit 2 "missing -o" mesh "$data/pyradiomics/brain1_label.nrrd"
expect_exit 2 "--label needs an integer" mesh "$data/pyradiomics/brain1_label.nrrd" -o "$out/x.stl" --label abc
# An output folder that does not exist yet is made, as by every command with -o; one that cannot
# be made (a file is in the way) is named.
"$soiq" mesh "$data/pyradiomics/brain1_label.nrrd" -o "$out/new/deeper/x.stl" >/dev/null || fail "-o into a new folder"
[ -s "$out/new/deeper/x.stl" ] || fail "-o into a new folder wrote nothing"
: >"$out/plainfile"
expect_exit 2 "cannot make the output folder '$out/plainfile/sub'" mesh "$data/pyradiomics/brain1_label.nrrd" -o "$out/plainfile/sub/x.stl"
printf 'NRRD0004\ntype: uint8\n\n' >"$out/bad.nrrd"
expect_exit 2 "no 'dimension' field" mesh "$out/bad.nrrd" -o "$out/x.stl"

if [ "$failures" -ne 0 ]; then
  echo "$failures failure(s)" >&2
  exit 1
fi
echo "mesh_test.sh: all passed"
