#!/usr/bin/env bash
# The remote `soiq` commands end to end against a real soiqd: upload (and deduplication),
# upload-image, import (DICOM), ls, show, features and convert (checked against the offline commands on the same
# data), download, query (rows, summary, a malformed expression), rm, the demo cohort, and each
# error with its exit code and one line: unknown id 3, open mesh 4, bad usage 2, no token 7,
# server down 6.
# Usage: remote_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"

start_soiqd main
export SOIQ_SERVER=$server
phantom="$data/ibsi_digital_phantom"

"$soiq" info >"$tmp/info" || fail "soiq info: $(cat "$tmp/info")"
grep -q "^version" "$tmp/info" || fail "info lacks the version: $(cat "$tmp/info")"
[ "$("$soiq" health)" = SERVING ] || fail "soiq health does not say SERVING"

# A closed surface model of the IBSI phantom's mask, made offline.
"$soiq" mesh "$phantom/mask.nii.gz" -o "$tmp/phantom.stl" >/dev/null || fail "soiq mesh"
record=(--patient P1 --study 1.2.3 --sex F --birth-date 19600101 --study-date 20200101 --modality CT)
id=$("$soiq" upload "$tmp/phantom.stl" "${record[@]}" --name phantom --laterality L -q) || fail "upload: $id"
[[ "$id" =~ ^[0-9]+$ ]] || fail "upload -q printed '$id', not an id"
"$soiq" upload "$tmp/phantom.stl" "${record[@]}" --name phantom --laterality R >"$tmp/up2" || fail "second upload"
grep -q "deduplicated" "$tmp/up2" || fail "the same mesh again is not deduplicated: $(cat "$tmp/up2")"
id2=$(sed -n 's/^structure \([0-9]*\):.*/\1/p' "$tmp/up2")
[ -n "$id2" ] && [ "$id2" != "$id" ] || fail "second upload is not a new structure: $(cat "$tmp/up2")"
"$soiq" upload-image "$phantom/phantom.nii.gz" "${record[@]}" --series 1.2.3.1 >"$tmp/img" || fail "upload-image"
grep -q "^series 1.2.3.1: CT" "$tmp/img" || fail "upload-image output: $(cat "$tmp/img")"

# The address as people write it: a URL copied from a config, the bare host with the default port
# (nothing listens on 50051 here unless a soiqd does, so only the form is checked there).
"$soiq" info --server "http://$server/" >/dev/null || fail "info --server http://$server/"
expect 2 "scheme 'grpc://'" -- "$soiq" info --server "grpc://$server"
expect 2 "not a number in 1..65535" -- "$soiq" info --server 127.0.0.1:http
SOIQ_SERVER= "$soiq" info --server 127.0.0.1 --timeout 0.5 2>"$tmp/err" >/dev/null
grep -q "127.0.0.1:0" "$tmp/err" && fail "a bare host is shown with port 0: $(cat "$tmp/err")"

# Listing and showing.
grep -q "^P1 " <<<"$("$soiq" ls)" || fail "ls patients lacks P1"
[ "$("$soiq" ls structures --patient P1 --format csv | wc -l)" -eq 3 ] || fail "ls structures: not header + 2 rows"
"$soiq" ls structures --name PHANT* --laterality R --format json >"$tmp/ls.json" || fail "ls --format json"
grep -q "\"id\": $id2," "$tmp/ls.json" || fail "ls json lacks structure $id2: $(cat "$tmp/ls.json")"
grep -q "\"id\": $id," "$tmp/ls.json" && fail "ls --laterality R lists the L structure"
grep -q "^1.2.3 " <<<"$("$soiq" ls studies --patient P1)" || fail "ls studies"
grep -q "^name  *phantom" <<<"$("$soiq" show structure "$id")" || fail "show structure"
grep -q "^name  *phantom" <<<"$("$soiq" show "$id")" || fail "show ID (a bare id is a structure)"
expect 2 "soiq rm structure $id" -- "$soiq" rm "$id"
grep -q "^series  *1.2.3.1 CT" <<<"$("$soiq" show study 1.2.3)" || fail "show study lacks its series"
grep -q '"patient_id":"P1"' <<<"$("$soiq" show patient P1 --format json)" || fail "show patient --format json"

# Features on the stored image's grid: the voxels are the mask's own (the conversion is exact), so
# the volume equals the offline value of the mask, and the mean is IBSI's 2.15.
"$soiq" features "$id" --series 1.2.3.1 --image CT --features voxel_volume_mm3,mean --format csv >"$tmp/f.csv" ||
  fail "remote features: $(cat "$tmp/f.csv")"
remote_volume=$(awk -F, '$3 == "voxel_volume_mm3" { print $4 }' "$tmp/f.csv")
local_volume=$("$soiq" features "$phantom/mask.nii.gz" --features voxel_volume_mm3 --format csv |
  awk -F, '$3 == "voxel_volume_mm3" { print $4 }')
[ -n "$remote_volume" ] && [ "$remote_volume" = "$local_volume" ] ||
  fail "remote volume '$remote_volume' != offline '$local_volume'"
within mean "$(awk -F, '$3 == "mean" { print $4 }' "$tmp/f.csv")" 2.15 0.005
"$soiq" convert "$id" --series 1.2.3.1 -o "$tmp/back.nii.gz" >/dev/null || fail "remote convert"
grep -q "^identical" <<<"$("$soiq" compare "$tmp/back.nii.gz" "$phantom/mask.nii.gz")" || fail "remote convert != mask"
grep -q "voxels inside" <<<"$("$soiq" convert "$id" --spacing 0.5 -o "$tmp/fine.nrrd")" || fail "remote convert to nrrd"
[ -s "$tmp/fine.nrrd" ] || fail "no nrrd written"
# Coverage fractions computed by soiqd equal the offline ones for the same surface on the same grid,
# value for value: bytes straight from soiqd's .nii.gz, floats and bytes through the client's .nii.
check=$(dirname "$0")/../cli/fraction_file.py
line=$("$soiq" convert "$id" --series 1.2.3.1 --fractional --oversample 3 -o "$tmp/remote_f.nii.gz") ||
  fail "remote convert --fractional: $line"
grep -qE "^[0-9]+ voxels inside or partly \([0-9]+ partly\), [0-9.]+ mm3 by fractions \(3x3 lines" <<<"$line" ||
  fail "remote fraction summary: $line"
"$soiq" convert "$tmp/phantom.stl" --reference "$phantom/mask.nii.gz" --fractional --oversample 3 \
  -o "$tmp/local_f.nii.gz" >/dev/null || fail "offline convert --fractional"
python3 "$check" "$tmp/remote_f.nii.gz" same "$tmp/local_f.nii.gz" || fail "remote uint8 fractions != offline"
"$soiq" convert "$id" --series 1.2.3.1 --fractional -o "$tmp/remote_u8.nii" >/dev/null || fail "remote fractions to .nii"
"$soiq" convert "$tmp/phantom.stl" --reference "$phantom/mask.nii.gz" --fractional -o "$tmp/local_u8.nii" >/dev/null
python3 "$check" "$tmp/remote_u8.nii" same "$tmp/local_u8.nii" || fail "remote uint8 fractions via .nii != offline"
"$soiq" convert "$id" --series 1.2.3.1 --fractional --float32 -o "$tmp/remote_f32.nii" >/dev/null ||
  fail "remote float32 fractions"
"$soiq" convert "$tmp/phantom.stl" --reference "$phantom/mask.nii.gz" --fractional --float32 -o "$tmp/local_f32.nii" >/dev/null
python3 "$check" "$tmp/remote_f32.nii" same "$tmp/local_f32.nii" || fail "remote float32 fractions != offline"
expect 2 "add --fractional" -- "$soiq" convert "$id" --float32 -o "$tmp/x.nii.gz"
grep -q "bytes ->" <<<"$("$soiq" download "$id" -o "$tmp/down.vtp")" || fail "download"
"$soiq" features "$tmp/down.vtp" --features mesh_volume_mm3 --format csv >/dev/null || fail "downloaded mesh unreadable"
"$soiq" download "$id" -o "$tmp/new/folder/down.stl" >/dev/null && [ -s "$tmp/new/folder/down.stl" ] || fail "download into a new folder"

# The two-stage query: rows on stdout, the summary on stderr.
"$soiq" query --patient 'P*' --sex F --name phantom --where 'voxel_volume_mm3 > 0' --select 'mean[inside,CT]' \
  --series-modality CT --order-by voxel_volume_mm3 --format csv >"$tmp/q.csv" 2>"$tmp/q.err" ||
  fail "query: $(cat "$tmp/q.err")"
head -1 "$tmp/q.csv" | grep -qxF 'id,patient_id,study_uid,name,laterality,voxel_volume_mm3,"mean[inside,CT]"' ||
  fail "query header: $(head -1 "$tmp/q.csv")"
[ "$(wc -l <"$tmp/q.csv")" -eq 3 ] || fail "query rows: $(cat "$tmp/q.csv")"
grep -q "2 candidates.*2 matched" "$tmp/q.err" || fail "query summary: $(cat "$tmp/q.err")"
"$soiq" query --sex M --format json >"$tmp/q.json" 2>/dev/null || fail "empty query"
[ "$(tr -d '[:space:]' <"$tmp/q.json")" = "[]" ] || fail "a query without matches is not []: $(cat "$tmp/q.json")"
expect 2 "expected ']' at column 16" -- "$soiq" query --where 'mean[shell:5,PT>2'
expect 2 "unknown feature\|bogus" -- "$soiq" query --name phantom --where 'bogus > 1'

# Errors: one line each, with the exit code of exit_code.h.
expect 3 "999999" -- "$soiq" show structure 999999
expect 3 "999999" -- "$soiq" features 999999
expect 3 "NOPE" -- "$soiq" show patient NOPE
expect 2 "missing --patient" -- "$soiq" upload "$tmp/phantom.stl" --study 1.2.3 --name x
expect 2 "structure id" -- "$soiq" rm structure abc
printf 'solid open\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 10 0 0\nvertex 0 10 0\nendloop\nendfacet\nendsolid open\n' >"$tmp/open.stl"
expect 4 "robust" -- "$soiq" upload "$tmp/open.stl" "${record[@]}" --name open

# Deleting.
grep -q "^deleted 1 structure$" <<<"$("$soiq" rm structure "$id2")" || fail "rm structure"
expect 3 "$id2" -- "$soiq" show structure "$id2"
grep -q "^deleted 1 structure$" <<<"$("$soiq" rm patient P1)" || fail "rm patient"
expect 3 "P1" -- "$soiq" show patient P1

# The demo cohort answers queries at once.
"$soiq" demo-load --patients 2 >"$tmp/demo" || fail "demo-load: $(cat "$tmp/demo")"
grep -q "loaded 2 patients, 2 MR images, 12 structures" "$tmp/demo" || fail "demo-load output: $(cat "$tmp/demo")"
"$soiq" query --name hippocampus --select voxel_volume_mm3 --select 'mean[shell:3,MR]' --series-modality MR \
  --format csv >"$tmp/h.csv" 2>/dev/null || fail "hippocampus query"
[ "$(wc -l <"$tmp/h.csv")" -eq 5 ] || fail "hippocampus rows: $(cat "$tmp/h.csv")"
"$soiq" query --name amygdala --laterality L --select 'asym(voxel_volume_mm3)' --format csv >"$tmp/a.csv" 2>/dev/null ||
  fail "asymmetry query"
[ "$(wc -l <"$tmp/a.csv")" -eq 3 ] || fail "asymmetry rows: $(cat "$tmp/a.csv")"

# DICOM import: STS_002's CT and PET with their structure sets, then a query on the PET uptake.
"$soiq" import "$data/sts/STS_002/dicom" --format csv >"$tmp/imp.csv" 2>"$tmp/imp.err" ||
  fail "import: $(cat "$tmp/imp.err")"
grep -q "^patient,STS_002," "$tmp/imp.csv" || fail "import lacks the patient: $(cat "$tmp/imp.csv")"
[ "$(grep -c "^series," "$tmp/imp.csv")" -eq 2 ] || fail "import series: $(cat "$tmp/imp.csv")"
grep -q "^structure,.*GTV_Mass_CT" "$tmp/imp.csv" || fail "import lacks GTV_Mass_CT: $(cat "$tmp/imp.csv")"
grep -q "imported 2 series and 2 structures from 98 files" "$tmp/imp.err" || fail "import summary: $(cat "$tmp/imp.err")"
"$soiq" query --patient STS_002 --name 'GTV*' --select 'mean[inside,PT]' --series-modality CT --format csv \
  >"$tmp/pet.csv" 2>/dev/null || fail "query on imported structures"
[ "$(wc -l <"$tmp/pet.csv")" -eq 3 ] || fail "PET uptake rows: $(cat "$tmp/pet.csv")"
printf 'not dicom' >"$tmp/plain.txt"
expect 2 "plain.txt" -- "$soiq" import "$tmp/plain.txt"
# One UID, one content: the CT structure set with its ROI renamed (same length, still valid DICOM)
# is refused (exit 4, ALREADY_EXISTS) naming what differs, until --replace asks for it.
perl -0777 -pe 's/GTV_Mass/GTV_Zass/g' "$data/sts/STS_002/dicom/CT/mask/RS.dcm" >"$tmp/RS_renamed.dcm"
expect 4 "with another name ('GTV_Mass_CT' stored, 'GTV_Zass_CT' sent)" -- "$soiq" import "$tmp/RS_renamed.dcm"
"$soiq" import "$tmp/RS_renamed.dcm" --replace --format csv >"$tmp/replaced.csv" 2>"$tmp/replaced.err" ||
  fail "import --replace: $(cat "$tmp/replaced.err")"
grep -q "^structure,.*GTV_Zass_CT" "$tmp/replaced.csv" || fail "import --replace: $(cat "$tmp/replaced.csv")"
"$soiq" import "$data/sts/STS_002/dicom/CT/mask/RS.dcm" --replace >/dev/null 2>&1 || fail "import --replace back"

# No silent empty answers. "PET" is DICOM's PT: the same rows as [inside,PT].
"$soiq" query --patient STS_002 --name 'GTV*' --select 'mean[inside,PET]' --series-modality CT --format csv \
  >"$tmp/pet2.csv" 2>/dev/null || fail "query naming PET"
[ "$(tail -n +2 "$tmp/pet2.csv" | sort)" = "$(tail -n +2 "$tmp/pet.csv" | sort)" ] || fail "PET and PT differ: $(cat "$tmp/pet2.csv" "$tmp/pet.csv")"
# An image no stored series has is refused before anything is computed, naming what is held.
expect 3 "no image in this soiqd has modality 'NM'; it holds CT, MR, PT" -- "$soiq" query --select 'mean[inside,NM]'
expect 3 "it holds CT, MR, PT; did you mean 'MR'?" -- "$soiq" query --select 'mean[inside,MRI]'
# The demo's amygdalae have no PT image in their studies: a partial answer, exit 8, with the count
# and the reason on stderr.
"$soiq" query --name 'amygdala' --where 'mean[inside,PT] > 0' >"$tmp/partial.out" 2>"$tmp/partial.err"
[ $? -eq 8 ] || fail "a partial answer does not exit 8: $(cat "$tmp/partial.err")"
grep -q "^  4 skipped: NOT_FOUND: no image series 'PT' in their study" "$tmp/partial.err" ||
  fail "partial answer without its reason: $(cat "$tmp/partial.err")"

# Pictures: soiq render writes the file its extension names and says what it drew; each bad
# request is one line and exit 2 (usage) or 3 (not found), and leaves no file; --plot writes the
# query's plot beside its rows.
gtv=$("$soiq" query --patient STS_002 --name 'GTV_Mass_CT' --format csv 2>/dev/null | awk -F, 'NR == 2 { print $1 }')
"$soiq" render "$gtv" -o "$tmp/pics/gtv.png" >"$tmp/render.out" || fail "render: $(cat "$tmp/render.out")"
grep -q "^axial slice [0-9]* of 0\.\.47 over series .*: [0-9]*x[0-9]* image/png, [0-9]* bytes -> $tmp/pics/gtv.png$" "$tmp/render.out" ||
  fail "render's line: $(cat "$tmp/render.out")"
[ "$(head -c 4 "$tmp/pics/gtv.png" | od -An -tx1 | tr -d ' \n')" = 89504e47 ] || fail "render did not write a PNG"
"$soiq" render "$gtv" --image PT --through centroid --window 2.5,5 -o "$tmp/pics/gtv.svg" >/dev/null || fail "render svg"
grep -q "<svg" "$tmp/pics/gtv.svg" || fail "render did not write an SVG"
alone=$("$soiq" upload "$tmp/phantom.stl" --patient P9 --study 9.9.9 --name alone -q) || fail "upload alone: $alone"
"$soiq" render "$alone" -o "$tmp/pics/alone.jpg" --quality 80 >"$tmp/render.out" || fail "render of an upload"
grep -q "over the mask alone" "$tmp/render.out" || fail "a mesh without images: $(cat "$tmp/render.out")"
expect 2 "missing -o" -- "$soiq" render "$gtv"
expect 2 "does not name a picture format" -- "$soiq" render "$gtv" -o "$tmp/pics/gtv.gif"
expect 2 "--plane" -- "$soiq" render "$gtv" --plane oblique -o "$tmp/pics/x.png"
expect 2 "--window" -- "$soiq" render "$gtv" --window 40 -o "$tmp/pics/x.png"
expect 2 "without --through or --montage" -- "$soiq" render "$gtv" --slice 3 --montage -o "$tmp/pics/x.png"
expect 2 "--quality is for JPEG" -- "$soiq" render "$gtv" --quality 50 -o "$tmp/pics/x.png"
expect 2 "outside 0..47" -- "$soiq" render "$gtv" --slice 99 -o "$tmp/pics/x.png"
expect 3 "999999" -- "$soiq" render 999999 -o "$tmp/pics/x.png"
[ -e "$tmp/pics/x.png" ] && fail "a refused render left a file"
"$soiq" query --name 'GTV*' --select voxel_volume_mm3 --select 'mean[inside,PT]' --plot "$tmp/pics/plot.svg" --format csv \
  >"$tmp/plot.csv" 2>"$tmp/plot.err" || fail "query --plot: $(cat "$tmp/plot.err")"
grep -q "^plot of 2 rows -> $tmp/pics/plot.svg$" "$tmp/plot.err" || fail "query --plot's line: $(cat "$tmp/plot.err")"
grep -q "voxel_volume_mm3 (mm3)" "$tmp/pics/plot.svg" 2>/dev/null || grep -q "<svg" "$tmp/pics/plot.svg" || fail "no plot"
expect 2 "--plot needs a feature" -- "$soiq" query --name 'GTV*' --plot "$tmp/pics/p.png"
expect 2 "written as .png or .svg" -- "$soiq" query --select sphericity --plot "$tmp/pics/p.jpg"

# Authentication: a server with a token refuses a client without it.
echo "0123456789abcdef0123456789abcdef" >"$tmp/token"
start_soiqd auth --token-file "$tmp/token"
expect 7 "" -- "$soiq" info --server "$server"
"$soiq" --server "$server" --token-file "$tmp/token" info >/dev/null || fail "info with the token"
expect 3 "token file" -- "$soiq" info --server "$server" --token-file "$tmp/token-missing"
stop_soiqd

# An endless input (a pipe that never ends) is cut at soiqd's upload limit, not buffered forever.
start_soiqd limited --max-upload-bytes 100000
mkfifo "$tmp/endless.stl"
(yes "solid endless" >"$tmp/endless.stl" 2>/dev/null &)
expect 5 "upload limit of 100000 bytes" -- "$soiq" upload "$tmp/endless.stl" --server "$server" "${record[@]}" --name endless
stop_soiqd

# Server down: exit 6, naming the address.
expect 6 "cannot reach soiqd at $server" -- "$soiq" ls --server "$server"
expect 6 "cannot reach soiqd at $server" -- "$soiq" health --server "$server"

finish remote_test
