#!/usr/bin/env bash
# Orthanc (Debian's, with its DICOMweb plugin orthanc-dicomweb) with soiqd configured as a remote
# DICOMweb server, bearer token included: Orthanc lists soiqd's studies and series through QIDO-RS and
# retrieves a structure's SEG and RT Structure Set through WADO-RS into its own store: the SEG's Pixel
# Data must be what `soiq export-seg` writes, the RT Structure Set must be one dciodvfy finds no error
# in, with as many contours as `soiq export-rtstruct` writes, whose even-odd fill (pydicom, on the
# CT's slices) is exactly the SEG's voxels.
#   run_test.sh SOIQ SOIQD
set -euo pipefail
soiq=$1
soiqd=$2
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../data
tmp=$(mktemp -d)
source "$here/../cli_remote/soiqd.sh"
fail() { echo "FAIL: $*"; [ -f "$tmp/orthanc.log" ] && tail -20 "$tmp/orthanc.log"; exit 1; }
plugin=$(ls /usr/lib/orthanc/libOrthancDicomWeb.so* 2>/dev/null | head -1)
command -v Orthanc >/dev/null || fail "Orthanc is not installed: scripts/install-deps installs it"
[ -n "$plugin" ] || fail "Orthanc's DICOMweb plugin is not installed: scripts/install-deps installs orthanc-dicomweb"

token=soiq-orthanc-test-token-0123456789
echo "$token" >"$tmp/token"
start_soiqd dw --http 127.0.0.1:0 --http-port-file "$tmp/dw.http-port" --token-file "$tmp/token"
http_port=$(tr -d '[:space:]' <"$tmp/dw.http-port")
"$soiq" --server "$server" --token-file "$tmp/token" import "$data/sts/STS_002/dicom/CT" >/dev/null
"$soiq" --server "$server" --token-file "$tmp/token" export-seg 1 -o "$tmp/gtv.dcm" >/dev/null
"$soiq" --server "$server" --token-file "$tmp/token" export-rtstruct 1 -o "$tmp/gtv-rt.dcm" >"$tmp/rt.out"
exported_contours=$(sed -n 's/^DICOM RT Structure Set [0-9.]*: 1 ROI, \([0-9]*\) contours,.*/\1/p' "$tmp/rt.out")
[ -n "$exported_contours" ] || fail "export-rtstruct says: $(cat "$tmp/rt.out")"

free_port() { /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
orthanc_http=$(free_port)
orthanc_dicom=$(free_port)
mkdir -p "$tmp/orthanc-db"
cat >"$tmp/orthanc.json" <<JSON
{
  "Name": "soiq-test",
  "StorageDirectory": "$tmp/orthanc-db",
  "IndexDirectory": "$tmp/orthanc-db",
  "HttpPort": $orthanc_http,
  "DicomPort": $orthanc_dicom,
  "RemoteAccessAllowed": false,
  "AuthenticationEnabled": false,
  "Plugins": ["$plugin"],
  "DicomWeb": {
    "Enable": true,
    "Root": "/dicom-web/",
    "Servers": {
      "soiq": {
        "Url": "http://127.0.0.1:$http_port/dicom-web/",
        "HttpHeaders": { "Authorization": "Bearer $token" }
      }
    }
  }
}
JSON
Orthanc "$tmp/orthanc.json" >"$tmp/orthanc.log" 2>&1 &
orthanc_pid=$!
soiqd_pids+=("$orthanc_pid")
orthanc="http://127.0.0.1:$orthanc_http"
for _ in $(seq 1 200); do
  curl -sf "$orthanc/system" >/dev/null 2>&1 && break
  kill -0 "$orthanc_pid" 2>/dev/null || fail "Orthanc did not start"
  sleep 0.1
done
curl -sf "$orthanc/system" >/dev/null || fail "Orthanc did not answer"

# QIDO-RS through Orthanc: soiqd's studies, then the study's series.
studies=$(curl -sf -X POST "$orthanc/dicom-web/servers/soiq/get" -d '{"Uri": "/studies"}') ||
  fail "Orthanc could not list soiqd's studies"
study=$(echo "$studies" | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); assert len(d)==1, d; print(d[0]["0020000D"]["Value"][0])')
series=$(curl -sf -X POST "$orthanc/dicom-web/servers/soiq/get" -d "{\"Uri\": \"/studies/$study/series\"}") ||
  fail "Orthanc could not list the study's series"
read -r seg rt < <(echo "$series" | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
mods = [s["00080060"]["Value"][0] for s in d]
assert mods == ["CT", "SEG", "RTSTRUCT"], mods
print(d[1]["0020000E"]["Value"][0], d[2]["0020000E"]["Value"][0])')
[ -n "$rt" ] || fail "no RTSTRUCT series listed"

# WADO-RS through Orthanc: the SEG retrieved into Orthanc's own store.
curl -sf -X POST "$orthanc/dicom-web/servers/soiq/retrieve" \
  -d "{\"Resources\": [{\"Study\": \"$study\", \"Series\": \"$seg\"}]}" >"$tmp/retrieve.json" ||
  fail "Orthanc could not retrieve the SEG series"
instances=$(curl -sf "$orthanc/instances")
id=$(echo "$instances" | /usr/bin/python3 -c 'import json,sys; d=json.load(sys.stdin); assert len(d)==1, d; print(d[0])')
curl -sf "$orthanc/instances/$id/simplified-tags" >"$tmp/tags.json"
curl -sf "$orthanc/instances/$id/file" >"$tmp/orthanc-seg.dcm"
/usr/bin/python3 - "$tmp/tags.json" "$tmp/orthanc-seg.dcm" "$tmp/gtv.dcm" "$seg" <<'PY'
import json, sys
import pydicom
tags = json.load(open(sys.argv[1]))
assert tags["SOPClassUID"] == "1.2.840.10008.5.1.4.1.1.66.4", tags["SOPClassUID"]
assert tags["SeriesInstanceUID"] == sys.argv[4], (tags["SeriesInstanceUID"], sys.argv[4])
stored = pydicom.dcmread(sys.argv[2])
exported = pydicom.dcmread(sys.argv[3])
assert stored.PixelData == exported.PixelData, "the SEG Orthanc holds differs from soiq export-seg's"
assert stored.NumberOfFrames == exported.NumberOfFrames
PY

# The RT Structure Set retrieved the same way, beside the SEG.
curl -sf -X POST "$orthanc/dicom-web/servers/soiq/retrieve" \
  -d "{\"Resources\": [{\"Study\": \"$study\", \"Series\": \"$rt\"}]}" >"$tmp/retrieve-rt.json" ||
  fail "Orthanc could not retrieve the RT Structure Set series"
rt_id=$(curl -sf "$orthanc/series" | /usr/bin/python3 -c '
import json, sys, urllib.request
base = sys.argv[1]
for s in json.load(sys.stdin):
    info = json.load(urllib.request.urlopen(base + "/series/" + s))
    if info["MainDicomTags"].get("SeriesInstanceUID") == sys.argv[2]:
        assert len(info["Instances"]) == 1, info
        print(info["Instances"][0])' "$orthanc" "$rt")
[ -n "$rt_id" ] || fail "Orthanc holds no instance of the RT Structure Set series $rt"
curl -sf "$orthanc/instances/$rt_id/file" >"$tmp/orthanc-rt.dcm"
dciodvfy "$tmp/orthanc-rt.dcm" >"$tmp/dciodvfy.log" 2>&1 || true
grep -q "RTStructureSet" "$tmp/dciodvfy.log" || fail "dciodvfy did not check an RT Structure Set: $(cat "$tmp/dciodvfy.log")"
! grep "^Error" "$tmp/dciodvfy.log" || fail "dciodvfy finds errors in the RT Structure Set Orthanc retrieved"
checked=$(/usr/bin/python3 "$here/rt_struct_matches_seg.py" "$tmp/orthanc-rt.dcm" "$tmp/orthanc-seg.dcm" \
  "$data/sts/STS_002/dicom/CT/image" GTV_Mass_CT) || fail "the RT Structure Set Orthanc holds: $checked"
[ "$(cut -d' ' -f2 <<<"$checked")" = "$exported_contours" ] ||
  fail "the RT Structure Set has $(cut -d' ' -f2 <<<"$checked") contours, export-rtstruct wrote $exported_contours"
/usr/bin/python3 - "$tmp/orthanc-rt.dcm" "$rt" <<'PY' || fail "the RT Structure Set Orthanc holds has other UIDs than QIDO listed"
import sys
import pydicom
assert pydicom.dcmread(sys.argv[1]).SeriesInstanceUID == sys.argv[2]
PY
echo "PASS"
