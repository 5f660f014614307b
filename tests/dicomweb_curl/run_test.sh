#!/usr/bin/env bash
# curl against a real soiqd --http: each bad request gets its HTTP status and a JSON error body whose
# message names the problem, and nothing of a refused request is stored.
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
expect 404 "kept by soiq as voxels" "$base/studies/$study/series/1.3.6.1.4.1.5962.1.3.1.1.20040119072730.12322"
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

# With a token: none or a wrong one is 401 with WWW-Authenticate.
echo "curl-test-token-0123456789abcdef" >"$tmp/token"
start_soiqd tok --http 127.0.0.1:0 --http-port-file "$tmp/tok.http-port" --token-file "$tmp/token"
tok="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/tok.http-port")/dicom-web"
expect 401 "needs 'Authorization: Bearer TOKEN'" "$tok/studies"
expect 401 "not valid" -H 'Authorization: Bearer wrong' "$tok/studies"
[ "$(curl -s -o /dev/null -w '%{http_code}' -H 'Authorization: Bearer curl-test-token-0123456789abcdef' "$tok/studies")" = 200 ] ||
  { echo "FAIL: the right token was refused"; failures=$((failures + 1)); }
challenge=$(curl -s -D - -o /dev/null "$tok/studies" | tr -d '\r' | grep -i '^WWW-Authenticate:' || true)
[ "$challenge" = "WWW-Authenticate: Bearer" ] || { echo "FAIL: no Bearer challenge: '$challenge'"; failures=$((failures + 1)); }

[ "$failures" = 0 ] || exit 1
echo "PASS"
