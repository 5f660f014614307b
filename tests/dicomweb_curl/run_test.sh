#!/usr/bin/env bash
# curl against a real soiqd --http: each bad request gets its HTTP status and a JSON error body whose
# message names the problem, and nothing of a refused request is stored; a structure's RT Structure
# Set retrieved beside its SEG, judged by dciodvfy and by pydicom against the SEG's voxels.
#   run_test.sh SOIQ SOIQD
set -euo pipefail
soiq=$1
soiqd=$2
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../data
tmp=$(mktemp -d)
source "$here/../cli_remote/soiqd.sh"
failures=0

# expect STATUS TEXT CURL-ARGS...: the status, and TEXT in the body's error message.
expect() {
  local status=$1 text=$2
  shift 2
  local got
  got=$(curl -s -o "$tmp/body" -w '%{http_code}' "$@")
  local message
  message=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["error"]["message"])' "$tmp/body" 2>/dev/null ||
    echo "<no JSON error body: $(head -c 200 "$tmp/body")>")
  if [ "$got" != "$status" ] || [[ "$message" != *"$text"* ]]; then
    echo "FAIL: curl $*: $got '$message', expected $status with '$text'"
    failures=$((failures + 1))
  fi
}

start_soiqd dw --http 127.0.0.1:0 --http-port-file "$tmp/dw.http-port" --max-upload-bytes 4000000
base="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/dw.http-port")/dicom-web"
"$soiq" --server "$server" import "$data/dicom/CT_small.dcm" >/dev/null
study=1.3.6.1.4.1.5962.1.2.1.20040119072730.12322

expect 400 "unknown query key 'Colour'" "$base/studies?Colour=red"
expect 400 "StudyDate: '20201' is not a date or a date range" "$base/studies?StudyDate=20201"
expect 400 "limit must be an integer" "$base/studies?limit=many"
expect 400 "given twice" "$base/studies?PatientID=a&PatientID=b"
expect 400 "--keep-patient-names" "$base/studies?PatientName=Doe*"
expect 400 "matches exact values only" "$base/studies?AccessionNumber=A*"
expect 404 "study '1.2.3' not found" "$base/studies/1.2.3/series"
expect 404 "no such resource" "$base/frobnicate"
expect 404 "no such resource" -X DELETE "$base/studies/$study"
expect 404 "no such resource" "$base/studies/..%2F..%2Fetc%2Fpasswd/series"
expect 404 "instance '1.2.3' not found" "$base/studies/$study/series/1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322/instances/1.2.3/frames/1"
expect 400 "frames are numbers from 1" "$base/studies/$study/series/1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322/instances/1.3.6.1.4.1.5962.1.1.1.1.1.20040119072730.12322/frames/0"
expect 406 "not acceptable" -H 'Accept: application/dicom+xml' "$base/studies"
expect 415 "multipart/related" -X POST -H 'Content-Type: application/dicom' --data-binary "@$data/dicom/CT_small.dcm" "$base/studies"
expect 400 "boundary" -X POST -H 'Content-Type: multipart/related; type="application/dicom"' --data-binary 'x' "$base/studies"
head -c 5000000 /dev/zero >"$tmp/big"
expect 413 "max-upload-bytes" -X POST -H 'Content-Type: multipart/related; type="application/dicom"; boundary=b' --data-binary "@$tmp/big" "$base/studies"

# A path with a newline in it cannot forge a log line of its own.
curl -s -o /dev/null "$base/studies%0Alevel=error%20event=forged"
if grep -q '^level=error event=forged' "$tmp/dw.log"; then
  echo "FAIL: a request's path started a log line of its own"
  failures=$((failures + 1))
fi

# One STOW part for another study than the URL names: 409, nothing stored.
printf -- '--b\r\nContent-Type: application/dicom\r\n\r\n' >"$tmp/stow"
cat "$data/dicom/MR_small.dcm" >>"$tmp/stow"
printf -- '\r\n--b--\r\n' >>"$tmp/stow"
got=$(curl -s -o "$tmp/body" -w '%{http_code}' -X POST -H 'Content-Type: multipart/related; type="application/dicom"; boundary=b' \
  --data-binary "@$tmp/stow" "$base/studies/1.2.3")
reason=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["00081198"]["Value"][0]["00081197"]["Value"][0])' "$tmp/body")
if [ "$got" != 409 ] || [ "$reason" != $((0xA900)) ]; then
  echo "FAIL: STOW of another study: $got, reason $reason"
  failures=$((failures + 1))
fi
studies=$(curl -s "$base/studies" | /usr/bin/python3 -c 'import json,sys; print(len(json.load(sys.stdin)))')
[ "$studies" = 1 ] || { echo "FAIL: $studies studies after the refused requests, not 1"; failures=$((failures + 1)); }

# An image uploaded as a file has no DICOM instances to send: a 404 that says so.
"$soiq" --server "$server" upload-image "$data/sts/STS_002/PET_image.nii.gz" --patient UP1 --study 2.25.77 \
  --series 2.25.78 --modality PT >/dev/null
expect 404 "stored without its DICOM instances" "$base/studies/2.25.77/series/2.25.78/metadata"

# /soiq/v1/query: the rows `soiq query --format csv` prints, header and numbers alike (the CLI prints
# rows as they are computed, the HTTP answer by structure id: compared sorted).
"$soiq" --server "$server" import "$data/sts/STS_002/dicom/CT" >/dev/null
"$soiq" --server "$server" import "$data/sts/STS_002/dicom/PET" >/dev/null
"$soiq" --server "$server" query --name 'GTV*' --where 'voxel_volume_mm3 > 1000' --select 'mean[inside,PT]' \
  --select centroid_mm --format csv 2>/dev/null >"$tmp/cli.csv"
curl -s -H 'Accept: text/csv' --get --data-urlencode 'name=GTV*' --data-urlencode 'where=voxel_volume_mm3 > 1000' \
  --data-urlencode 'select=mean[inside,PT]' --data-urlencode 'select=centroid_mm' "${base%/dicom-web}/soiq/v1/query" >"$tmp/http.csv"
if ! diff <(head -1 "$tmp/cli.csv"; tail -n +2 "$tmp/cli.csv" | sort) "$tmp/http.csv" >/dev/null || [ "$(wc -l <"$tmp/http.csv")" != 3 ]; then
  echo "FAIL: /soiq/v1/query's CSV differs from soiq query's:"
  diff "$tmp/cli.csv" "$tmp/http.csv" || true
  failures=$((failures + 1))
fi
json_rows=$(curl -s "${base%/dicom-web}/soiq/v1/query?name=GTV*&select=sphericity" | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); print(len(d["rows"]), d["columns"][-1])')
[ "$json_rows" = "2 sphericity" ] || { echo "FAIL: /soiq/v1/query JSON: $json_rows"; failures=$((failures + 1)); }
expect 400 "did you mean 'name'" "${base%/dicom-web}/soiq/v1/query?nmae=GTV*"
expect 400 "unknown feature 'spherity'" "${base%/dicom-web}/soiq/v1/query?where=spherity%3E1"
# The field the error is about, apart from the prose (as gRPC's ErrorDetails).
field=$(/usr/bin/python3 -c 'import json,sys; e=json.load(open(sys.argv[1]))["error"]; print(e.get("field"), e.get("reason", "")[:15])' "$tmp/body")
[ "$field" = "where[0] unknown feature" ] || { echo "FAIL: the error's field and reason: '$field'"; failures=$((failures + 1)); }
expect 400 "at column" "${base%/dicom-web}/soiq/v1/query?where=sphericity%3E%3E1"
expect 400 "desc needs order-by" "${base%/dicom-web}/soiq/v1/query?desc=true"

# Pictures: WADO-RS rendered and thumbnail of the GTV's SEG (its frames on their CT slices) and of
# the CT's instances; soiq's own /soiq/v1/structures/{id}/... pictures and files. Each answer is
# judged by its status, its Content-Type and its first bytes (a PNG's size from its header).
# expect_file STATUS TYPE MAGIC-HEX CURL-ARGS...
expect_file() {
  local want="$1 $2" magic=$3
  shift 3
  local got head
  got=$(curl -s -o "$tmp/file" -w '%{http_code} %{content_type}' "$@")
  head=$(head -c $((${#magic} / 2)) "$tmp/file" | od -An -tx1 | tr -d ' \n')
  if [ "$got" != "$want" ] || [ "$head" != "$magic" ]; then
    echo "FAIL: curl $*: '$got' starting $head, expected '$want' starting $magic"
    failures=$((failures + 1))
  fi
}
png=89504e470d0a1a0a
jpeg=ffd8ff
svg=3c3f786d6c
root=${base%/dicom-web}
sts_study=$(curl -s "$base/studies?PatientID=STS_002" | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)[0]["0020000D"]["Value"][0])')
curl -s "$base/studies/$sts_study/series" >"$tmp/series.json"
seg_series=$(/usr/bin/python3 -c 'import json,sys; print([s["0020000E"]["Value"][0] for s in json.load(open(sys.argv[1])) if s["00080060"]["Value"][0] == "SEG"][0])' "$tmp/series.json")
ct_series=$(/usr/bin/python3 -c 'import json,sys; print([s["0020000E"]["Value"][0] for s in json.load(open(sys.argv[1])) if s["00080060"]["Value"][0] == "CT"][0])' "$tmp/series.json")
seg_instance=$(curl -s "$base/studies/$sts_study/series/$seg_series/instances" | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)[0]["00080018"]["Value"][0])')
ct_instance=$(curl -s "$base/studies/$sts_study/series/$ct_series/instances" | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)[3]["00080018"]["Value"][0])')
seg=$base/studies/$sts_study/series/$seg_series
ct=$base/studies/$sts_study/series/$ct_series
expect_file 200 image/jpeg $jpeg "$seg/rendered"
expect_file 200 image/png $png -H 'Accept: image/png' "$seg/rendered"
expect_file 200 image/jpeg $jpeg "$seg/instances/$seg_instance/rendered?quality=60"
expect_file 200 image/png $png -H 'Accept: image/png' "$seg/instances/$seg_instance/frames/1/rendered?window=40,400,linear"
expect_file 200 image/jpeg $jpeg "$seg/thumbnail"
expect_file 200 image/jpeg $jpeg "$ct/rendered"
expect_file 200 image/jpeg $jpeg "$ct/instances/$ct_instance/rendered"
expect_file 200 image/png $png -H 'Accept: image/png' "$ct/instances/$ct_instance/thumbnail?viewport=64,48"
size=$(/usr/bin/python3 -c 'import struct,sys; d=open(sys.argv[1],"rb").read(24); print("%dx%d" % struct.unpack(">II", d[16:24]))' "$tmp/file")
case $size in 64x*|*x48) ;; *) echo "FAIL: a 64x48 viewport gave a ${size} thumbnail"; failures=$((failures + 1)) ;; esac
/usr/bin/python3 -c 'import sys; w,h=map(int,sys.argv[1].split("x")); sys.exit(0 if w<=64 and h<=48 else 1)' "$size" ||
  { echo "FAIL: a ${size} thumbnail overflows its 64x48 viewport"; failures=$((failures + 1)); }
expect_file 200 image/jpeg $jpeg "$base/studies/$sts_study/thumbnail"
expect 400 "unsupported parameter 'annotation'" "$seg/rendered?annotation=patient"
expect 400 "window must be CENTER,WIDTH" "$seg/rendered?window=40"
expect 400 "'sigmoid' is not supported" "$seg/rendered?window=40,400,sigmoid"
expect 400 "source rectangle" "$seg/rendered?viewport=100,100,0,0,10,10"
expect 400 "quality must be a whole number in 1..100" "$seg/rendered?quality=0"
expect 400 "one frame per rendered request" "$seg/instances/$seg_instance/frames/1,2/rendered"
expect 404 "frames 1.." "$seg/instances/$seg_instance/frames/99999/rendered"
expect 404 "not found" "$ct/instances/1.2.3.4/rendered"

# The GTV's RT Structure Set, listed beside its SEG: retrieved as DICOM, the same object twice,
# one dciodvfy finds no error in, whose contours filled by pydicom are the SEG's voxels.
read -r rt_series rt_name < <(/usr/bin/python3 -c '
import json, sys
series = json.load(open(sys.argv[1]))
mods = [s["00080060"]["Value"][0] for s in series]
at = mods.index("SEG")
assert mods[at + 1] == "RTSTRUCT", mods
print(series[at + 1]["0020000E"]["Value"][0], series[at + 1]["0008103E"]["Value"][0])' \
  <(curl -s "$base/studies/$sts_study/series?includefield=SeriesDescription"))
rt=$base/studies/$sts_study/series/$rt_series
# part FILE OUT: the one application/dicom part of a multipart/related answer.
part() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys
body = open(sys.argv[1], "rb").read()
boundary = body[:body.index(b"\r\n")]
parts = [p for p in body.split(boundary)[1:] if not p.startswith(b"--")]
assert len(parts) == 1, len(parts)
head, _, data = parts[0].partition(b"\r\n\r\n")
assert b"application/dicom" in head, head
open(sys.argv[2], "wb").write(data[:-2])  # the CRLF before the next boundary
PY
}
for what in "$rt" "$seg"; do
  got=$(curl -s -o "$tmp/answer" -w '%{http_code} %{content_type}' -H 'Accept: multipart/related; type="application/dicom"' "$what")
  [[ "$got" == "200 multipart/related; type=\"application/dicom\""* ]] || { echo "FAIL: $what: $got"; failures=$((failures + 1)); }
  part "$tmp/answer" "$tmp/$([ "$what" = "$rt" ] && echo rt || echo seg).dcm"
done
rt_instance=$(curl -s "$rt/instances" | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); assert d[0]["00080016"]["Value"][0] == "1.2.840.10008.5.1.4.1.1.481.3"; print(d[0]["00080018"]["Value"][0])')
curl -s -o "$tmp/again" "$rt/instances/$rt_instance"
part "$tmp/again" "$tmp/rt-again.dcm"
cmp -s "$tmp/rt.dcm" "$tmp/rt-again.dcm" || { echo "FAIL: the RT Structure Set retrieved twice differs"; failures=$((failures + 1)); }
dciodvfy "$tmp/rt.dcm" >"$tmp/dciodvfy.log" 2>&1 || true
if ! grep -q "RTStructureSet" "$tmp/dciodvfy.log" || grep "^Error" "$tmp/dciodvfy.log"; then
  echo "FAIL: dciodvfy on the RT Structure Set: $(cat "$tmp/dciodvfy.log")"
  failures=$((failures + 1))
fi
/usr/bin/python3 "$here/../dicomweb_orthanc/rt_struct_matches_seg.py" "$tmp/rt.dcm" "$tmp/seg.dcm" \
  "$data/sts/STS_002/dicom/CT/image" "$rt_name" >"$tmp/rt.check" 2>&1 ||
  { echo "FAIL: the RT Structure Set against the SEG: $(tail -3 "$tmp/rt.check")"; failures=$((failures + 1)); }
metadata=$(curl -s "$rt/metadata" | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin)[0]; print(d["00080060"]["Value"][0], d["30060020"]["Value"][0]["30060026"]["Value"][0])')
[ "$metadata" = "RTSTRUCT $rt_name" ] || { echo "FAIL: the RT Structure Set's metadata: $metadata"; failures=$((failures + 1)); }
expect 404 "instance '1.2.3' not found" "$rt/instances/1.2.3"
expect 404 "is an RT Structure Set: it has no pixel data or frames" "$rt/instances/$rt_instance/frames/1"
expect 404 "is an RT Structure Set" "$rt/instances/$rt_instance/bulkdata"
expect 406 "not acceptable" -H 'Accept: multipart/related; type="application/dicom"; transfer-syntax=1.2.840.10008.1.2.4.50' "$rt"
expect 404 "not found in study '1.2.3'" "$base/studies/1.2.3/series/$rt_series"
expect_file 200 image/jpeg $jpeg "$rt/rendered"
expect 406 "not acceptable" -H 'Accept: image/gif' "$seg/rendered"
gtv=$(curl -s "$root/soiq/v1/query?name=GTV*" | /usr/bin/python3 -c 'import json,sys; print(json.load(sys.stdin)["rows"][0]["id"])')
expect_file 200 image/jpeg $jpeg "$root/soiq/v1/structures/$gtv/thumbnail"
expect_file 200 image/png $png -H 'Accept: image/png' "$root/soiq/v1/structures/$gtv/rendered?plane=coronal&through=centroid"
expect_file 200 image/svg+xml $svg -H 'Accept: image/svg+xml' "$root/soiq/v1/structures/$gtv/rendered?montage=true"
expect_file 200 application/dicom "" "$root/soiq/v1/structures/$gtv/seg"
[ "$(dd if="$tmp/file" bs=1 skip=128 count=4 2>/dev/null)" = DICM ] || { echo "FAIL: /seg is not a DICOM file"; failures=$((failures + 1)); }
expect_file 200 application/gzip 1f8b "$root/soiq/v1/structures/$gtv/mask"
expect_file 200 model/stl "" "$root/soiq/v1/structures/$gtv/surface"
/usr/bin/python3 -c 'import struct,sys,os; d=open(sys.argv[1],"rb").read(84); n=struct.unpack("<I", d[80:84])[0]; sys.exit(0 if os.path.getsize(sys.argv[1]) == 84 + 50 * n and n > 0 else 1)' "$tmp/file" ||
  { echo "FAIL: /surface is not a binary STL of its triangle count"; failures=$((failures + 1)); }
disposition=$(curl -s -D - -o /dev/null "$root/soiq/v1/structures/$gtv/mask" | tr -d '\r' | grep -i '^Content-Disposition:' || true)
[ "$disposition" = "Content-Disposition: attachment; filename=\"structure-$gtv-mask.nii.gz\"" ] ||
  { echo "FAIL: the mask's file name: '$disposition'"; failures=$((failures + 1)); }
expect 404 "structure 999999 not found" "$root/soiq/v1/structures/999999/thumbnail"
expect 404 "structure 'abc' not found" "$root/soiq/v1/structures/abc/seg"
expect 400 "slice 100000 is outside 0.." "$root/soiq/v1/structures/$gtv/rendered?slice=100000"
expect 400 "unsupported parameter 'x'" "$root/soiq/v1/structures/$gtv/mask?x=1"

# The query as rows streamed one JSON line at a time (chunked): columns first, the rows of the plain
# JSON answer, the summary last; a bad argument still a 400 before anything is streamed.
curl -s -D "$tmp/ndjson.head" -H 'Accept: application/x-ndjson' "$root/soiq/v1/query?name=GTV*&select=sphericity" >"$tmp/ndjson"
curl -s "$root/soiq/v1/query?name=GTV*&select=sphericity" >"$tmp/whole.json"
/usr/bin/python3 - "$tmp/ndjson" "$tmp/whole.json" <<'PY' || { echo "FAIL: the NDJSON answer differs from the JSON one"; failures=$((failures + 1)); }
import json, sys
lines = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
whole = json.load(open(sys.argv[2]))
assert lines[0] == {"columns": whole["columns"]}, lines[0]
rows = sorted((l["row"] for l in lines[1:-1]), key=lambda r: r["id"])
assert rows == whole["rows"], (rows, whole["rows"])
assert "summary" in lines[-1] and lines[-1]["summary"]["returned"] == len(rows), lines[-1]
PY
grep -qi '^Transfer-Encoding: chunked' "$tmp/ndjson.head" || { echo "FAIL: the NDJSON answer is not chunked"; failures=$((failures + 1)); }
expect 400 "unknown feature 'spherity'" -H 'Accept: application/x-ndjson' "$root/soiq/v1/query?select=spherity"
expect_file 200 image/svg+xml $svg "$root/soiq/v1/query/plot?name=GTV*&select=voxel_volume_mm3"
expect_file 200 image/png $png -H 'Accept: image/png' "$root/soiq/v1/query/plot?select=voxel_volume_mm3&select=sphericity"
expect 400 "the plot needs a feature" "$root/soiq/v1/query/plot?name=GTV*"
info=$(curl -s "$root/soiq/v1/info" | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); print(len(d["features"]) > 20, [o["name"] for o in d["query_options"]][:2], d["viewer_url"] == "")')
[ "$info" = "True ['patient', 'sex'] True" ] || { echo "FAIL: /soiq/v1/info: $info"; failures=$((failures + 1)); }

# With a token: none or a wrong one is 401 with WWW-Authenticate.
echo "curl-test-token-0123456789abcdef" >"$tmp/token"
start_soiqd tok --http 127.0.0.1:0 --http-port-file "$tmp/tok.http-port" --token-file "$tmp/token"
tok="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/tok.http-port")/dicom-web"
expect 401 "needs 'Authorization: Bearer TOKEN'" "$tok/studies"
expect 401 "not valid" -H 'Authorization: Bearer wrong' "$tok/studies"
[ "$(curl -s -o /dev/null -w '%{http_code}' -H 'Authorization: Bearer curl-test-token-0123456789abcdef' "$tok/studies")" = 200 ] ||
  { echo "FAIL: the right token was refused"; failures=$((failures + 1)); }
# The query page's files need no token (they hold nothing of the store); its API calls do.
tok_root=${tok%/dicom-web}
[ "$(curl -s -o /dev/null -w '%{http_code} %{content_type}' "$tok_root/")" = "200 text/html; charset=utf-8" ] ||
  { echo "FAIL: the query page needs no token"; failures=$((failures + 1)); }
expect 401 "needs 'Authorization: Bearer TOKEN'" "$tok_root/soiq/v1/info"
expect 401 "needs 'Authorization: Bearer TOKEN'" "$tok_root/soiq/v1/structures/1/thumbnail"
challenge=$(curl -s -D - -o /dev/null "$tok/studies" | tr -d '\r' | grep -i '^WWW-Authenticate:' || true)
[ "$challenge" = "WWW-Authenticate: Bearer" ] || { echo "FAIL: no Bearer challenge: '$challenge'"; failures=$((failures + 1)); }

[ "$failures" = 0 ] || exit 1
echo "PASS"
