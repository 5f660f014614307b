#!/usr/bin/env bash
# dicomweb-client (npm, as OHIF uses it) against a real soiqd --http: starts soiqd, imports STS_002's
# CT and RT Structure Set with the CLI, exports the structure's SEG and RT Structure Set with the
# CLI, then runs dicomweb_client_test.js with Node's test runner; after it, the RT Structure Set it
# retrieved must fill (pydicom) to the SEG's voxels with export-rtstruct's contour count, and
# `soiq query` must find the structure of the PET structure set the Node test sent by STOW-RS.
#   run_test.sh SOIQ SOIQD
set -euo pipefail
soiq=$1
soiqd=$2
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../data
tmp=$(mktemp -d)
source "$here/../cli_remote/soiqd.sh"
if [ ! -d "$here/node_modules/dicomweb-client" ]; then
  echo "FAIL: tests/dicomweb_client/node_modules is missing: scripts/install-deps installs it (npm ci)"
  exit 1
fi
start_soiqd dw --http 127.0.0.1:0 --http-port-file "$tmp/dw.http-port" --keep-patient-names on
http="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/dw.http-port")/dicom-web"
"$soiq" --server "$server" import "$data/sts/STS_002/dicom/CT" >/dev/null
"$soiq" --server "$server" import "$data/dicom/CT_small.dcm" >/dev/null
"$soiq" --server "$server" export-seg 1 -o "$tmp/gtv.dcm" >/dev/null
exported=$("$soiq" --server "$server" export-rtstruct 1 -o "$tmp/gtv-rt.dcm" | sed -n 's/.*: 1 ROI, \([0-9]*\) contours,.*/\1/p')
SOIQ_DICOMWEB=$http SOIQ_DATA=$data SOIQ_EXPORTED_SEG=$tmp/gtv.dcm SOIQ_OUT=$tmp node --test "$here/dicomweb_client_test.js"
# The RT Structure Set dicomweb-client retrieved, read by pydicom: its contours are the SEG's voxels.
checked=$(/usr/bin/python3 "$here/../dicomweb_orthanc/rt_struct_matches_seg.py" "$tmp/rtstruct.dcm" "$tmp/seg.dcm" \
  "$data/sts/STS_002/dicom/CT/image" GTV_Mass_CT)
if [ "$(cut -d' ' -f2 <<<"$checked")" != "$exported" ] || [ -z "$exported" ]; then
  echo "FAIL: the retrieved RT Structure Set has $(cut -d' ' -f2 <<<"$checked") contours, export-rtstruct wrote '$exported'"
  exit 1
fi
# The PET structure set came in by STOW-RS: a query finds its structure.
rows=$("$soiq" --server "$server" query --name 'GTV_Mass_PET' --format csv | tail -n +2 | wc -l)
if [ "$rows" != "1" ]; then
  echo "FAIL: the query found $rows rows for the structure sent by STOW-RS, not 1"
  exit 1
fi
echo "PASS"
