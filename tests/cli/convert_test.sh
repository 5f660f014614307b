#!/usr/bin/env bash
# `soiq convert` end to end on real files: lossless round trips through every mesh format, and each
# bad input answered with its exit code and one readable line.
# Usage: convert_test.sh SOIQ_BINARY TEST_DATA_DIR
soiq=$1
data=$2
source "$(dirname "$0")/lib.sh"

# Lossless round trip: mask -> soiq mesh -> soiq convert --reference mask -> identical.
for mask in "pyradiomics/brain1_label.nrrd" "sts/STS_002/CT_mask.nii.gz" "ibsi_digital_phantom/mask.nii.gz"; do
  for fmt in vtp stl ply obj vtk; do
    "$soiq" mesh "$data/$mask" -o "$tmp/s.$fmt" >/dev/null || fail "soiq mesh $mask -> $fmt"
    for out in nii.gz nrrd mha; do
      "$soiq" convert "$tmp/s.$fmt" --reference "$data/$mask" -o "$tmp/back.$out" >/dev/null || fail "convert $mask $fmt -> $out"
      result=$("$soiq" compare "$data/$mask" "$tmp/back.$out")
      case "$result" in identical:*) ;; *) fail "$mask via $fmt/$out: $result" ;; esac
    done
  done
done

# A grid around the mesh: the summary line reports voxels, volume, defects and time.
"$soiq" mesh "$data/sts/STS_002/PET_mask.nii.gz" -o "$tmp/pet.stl" >/dev/null
line=$("$soiq" convert "$tmp/pet.stl" --spacing 1 --margin 3 -o "$tmp/pet_1mm.nii.gz" --threads 2)
echo "$line" | grep -qE '^[0-9]+ voxels inside, [0-9.]+ mm3 on .* 0 boundary edges.* ms -> ' || fail "summary line: $line"

# Coverage fractions of an axis-aligned box on an axis-aligned grid, checked voxel by voxel against
# the fractions computed independently by tests/cli/fraction_file.py (exact along rows, n x n sample
# lines across), as bytes and as floats; the summary's volume is the sum of the fractions.
check=$(dirname "$0")/fraction_file.py
lo=0.2537,0.1031,-0.3119
hi=3.7713,3.3307,2.6171
{
  printf 'v %s %s %s\n' 0.2537 0.1031 -0.3119 3.7713 0.1031 -0.3119 0.2537 3.3307 -0.3119 3.7713 3.3307 -0.3119
  printf 'v %s %s %s\n' 0.2537 0.1031 2.6171 3.7713 0.1031 2.6171 0.2537 3.3307 2.6171 3.7713 3.3307 2.6171
  printf 'f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n'
} >"$tmp/box.obj"
for n in 1 3 8; do
  line=$("$soiq" convert "$tmp/box.obj" --spacing 0.7 --fractional --oversample "$n" -o "$tmp/box_u8.nii.gz") ||
    fail "convert --fractional --oversample $n"
  echo "$line" | grep -qE "^[0-9]+ voxels inside or partly \([0-9]+ partly\), [0-9.]+ mm3 by fractions \(${n}x${n} lines per voxel\)" ||
    fail "fraction summary line: $line"
  python3 "$check" "$tmp/box_u8.nii.gz" box "$lo" "$hi" "$n" >/dev/null || fail "uint8 fractions, n=$n"
  "$soiq" convert "$tmp/box.obj" --spacing 0.7 --fractional --float32 --oversample "$n" -o "$tmp/box_f.nii" >/dev/null ||
    fail "convert --fractional --float32"
  sum=$(python3 "$check" "$tmp/box_f.nii" box "$lo" "$hi" "$n") || fail "float32 fractions, n=$n"
  mm3=$(sed -E 's/.*partly\), ([0-9.]+) mm3.*/\1/' <<<"$line")
  within "sum of fractions x 0.343 mm3 (n=$n)" "$(awk -v s="$sum" 'BEGIN { print s * 0.343 }')" "$mm3" 0.002
done
# Other formats are written by the same writers as masks (their round trips are tested above).
"$soiq" convert "$tmp/box.obj" --spacing 0.7 --fractional -o "$tmp/box_u8.nrrd" >/dev/null || fail "fractions to nrrd"
[ -s "$tmp/box_u8.nrrd" ] || fail "no nrrd of fractions"
"$soiq" convert "$tmp/box.obj" --spacing 0.7 --fractional -o "$tmp/box_u8.nii" >/dev/null || fail "fractions to nii"
python3 "$check" "$tmp/box_u8.nii" box "$lo" "$hi" 4 >/dev/null || fail "uint8 fractions, default n=4"
expect 2 "add --fractional" -- "$soiq" convert "$tmp/box.obj" --spacing 1 --float32 -o "$tmp/x.nii.gz"
expect 2 "add --fractional" -- "$soiq" convert "$tmp/box.obj" --spacing 1 --oversample 2 -o "$tmp/x.nii.gz"
expect 2 "from 1 to 8" -- "$soiq" convert "$tmp/box.obj" --spacing 1 --fractional --oversample 9 -o "$tmp/x.nii.gz"
expect 2 "closed surface" -- "$soiq" convert "$tmp/box.obj" --spacing 1 --fractional --robust -o "$tmp/x.nii.gz"
expect 5 "needs an estimated" -- env SOIQ_MEMORY_BUDGET=1M "$soiq" convert "$tmp/box.obj" --spacing 0.01 --fractional --oversample 8 -o "$tmp/x.nii.gz"

# An open mesh: plain mode names --robust (exit 4); robust mode gives a result.
cat >"$tmp/open.stl" <<'STL'
solid open
facet normal 0 0 1
outer loop
vertex 0 0 0
vertex 10 0 0
vertex 0 10 0
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 0 0 0
vertex 0 10 0
vertex 0 0 10
endloop
endfacet
endsolid open
STL
expect 4 "--robust" -- "$soiq" convert "$tmp/open.stl" --spacing 1 -o "$tmp/o.nii.gz"
expect 4 "closed surface" -- "$soiq" convert "$tmp/open.stl" --spacing 1 --fractional -o "$tmp/o.nii.gz"
"$soiq" convert "$tmp/open.stl" --spacing 1 --robust -o "$tmp/o.nii.gz" >/dev/null || fail "robust mode on an open mesh"

# Inverted orientation (a tetrahedron written inside out): fixed on reading, said so, same voxels.
tet() {  # $1: 1 for outward, 0 for inward
  local a="0 0 0" b="9 0 0" c="0 9 0" d="0 0 9"
  echo "solid t"
  if [ "$1" = 1 ]; then faces=("$a|$c|$b" "$a|$b|$d" "$b|$c|$d" "$a|$d|$c"); else faces=("$a|$b|$c" "$a|$d|$b" "$b|$d|$c" "$a|$c|$d"); fi
  for f in "${faces[@]}"; do
    IFS='|' read -r p q r <<<"$f"
    printf 'facet normal 0 0 0\nouter loop\nvertex %s\nvertex %s\nvertex %s\nendloop\nendfacet\n' "$p" "$q" "$r"
  done
  echo "endsolid t"
}
tet 1 >"$tmp/out.stl"
tet 0 >"$tmp/in.stl"
out_line=$("$soiq" convert "$tmp/out.stl" --spacing 0.5 -o "$tmp/out.nii.gz")
in_line=$("$soiq" convert "$tmp/in.stl" --spacing 0.5 -o "$tmp/in.nii.gz")
echo "$in_line" | grep -q "orientation flipped to outward" || fail "inverted mesh not reported: $in_line"
echo "$out_line" | grep -q "orientation flipped" && fail "outward mesh reported as flipped: $out_line"
[ "${out_line%% voxels*}" = "${in_line%% voxels*}" ] || fail "inverted mesh gives other voxels: $out_line / $in_line"
case "$("$soiq" compare "$tmp/out.nii.gz" "$tmp/in.nii.gz")" in identical:*) ;; *) fail "inverted mesh mask differs" ;; esac

expect 3 "not" -- "$soiq" convert "$tmp/missing.stl" --spacing 1 -o "$tmp/x.nii.gz"
expect 3 "missing_ref" -- "$soiq" convert "$tmp/pet.stl" --reference "$tmp/missing_ref.nii.gz" -o "$tmp/x.nii.gz"
expect 5 "exceeds the limit" -- "$soiq" convert "$tmp/pet.stl" --spacing 0.001 -o "$tmp/x.nii.gz"
expect 2 "unknown option" -- "$soiq" convert "$tmp/pet.stl" --bogus -o "$tmp/x.nii.gz"
expect 2 "missing -o" -- "$soiq" convert "$tmp/pet.stl"
expect 2 "--spacing" -- "$soiq" convert "$tmp/pet.stl" --spacing -1 -o "$tmp/x.nii.gz"
: >"$tmp/empty.stl"
expect 2 "empty.stl" -- "$soiq" convert "$tmp/empty.stl" --spacing 1 -o "$tmp/x.nii.gz"
expect 2 "extension" -- "$soiq" convert "$tmp/pet.stl" --spacing 1 -o "$tmp/x.png"

# Hostile meshes read offline by the same strict parsers as soiqd's uploads: one line, exit 2.
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n' >"$tmp/short.ply"
expect 2 "vertex has 2 values" -- "$soiq" convert "$tmp/short.ply" --spacing 1 -o "$tmp/x.nii.gz"
printf 'v 0 0 0\nv 1 0 nan\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n' >"$tmp/nan.obj"
expect 2 "nan" -- "$soiq" convert "$tmp/nan.obj" --spacing 1 -o "$tmp/x.nii.gz"
printf 'v 0 0 0\nv 5abc 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n' >"$tmp/junk.obj"
expect 2 "5abc" -- "$soiq" convert "$tmp/junk.obj" --spacing 1 -o "$tmp/x.nii.gz"

# A 300-byte slab of 2.5 x 7500 x 7500 mm: 5.6e7 row lines at 1 mm, gigabytes of crossings. Refused
# by its estimate before anything is allocated (it died of bad_alloc before).
printf 'v 0 0 0\nv 2.5 0 0\nv 0 7500 0\nv 2.5 7500 0\nv 0 0 7500\nv 2.5 0 7500\nv 0 7500 7500\nv 2.5 7500 7500\n' >"$tmp/slab.obj"
printf 'f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n' >>"$tmp/slab.obj"
expect 5 "memory budget of 1.07 GB" -- env SOIQ_MEMORY_BUDGET=1G "$soiq" convert "$tmp/slab.obj" --spacing 1 -o "$tmp/x.nii.gz"
expect 5 "needs an estimated" -- env SOIQ_MEMORY_BUDGET=1G "$soiq" features "$tmp/slab.obj" --spacing 1
expect 2 "SOIQ_MEMORY_BUDGET" -- env SOIQ_MEMORY_BUDGET=lots "$soiq" convert "$tmp/slab.obj" --spacing 1 -o "$tmp/x.nii.gz"

# A file named like a structure id is ambiguous: refused naming both spellings, before any server
# is asked (none runs here); ./N means the file.
cp "$tmp/pet.stl" "$tmp/7"
pushd "$tmp" >/dev/null || fail "cd $tmp"
expect 2 "write id:7 for the stored structure or ./7 for the file" -- "$soiq" convert 7 --spacing 1 -o x.nii.gz
expect 2 "both a structure id and a file" -- "$soiq" features 7 --spacing 1
expect 2 "unknown mesh extension" -- "$soiq" convert ./7 --spacing 1 -o x.nii.gz
popd >/dev/null || fail "cd back"

# Stderr of a failure is one line.
"$soiq" convert "$tmp/missing.stl" --spacing 1 -o "$tmp/x.nii.gz" 2>"$tmp/err"
[ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "error output is not one line: $(cat "$tmp/err")"

finish convert_test
