#!/usr/bin/env bash
# OHIF (its published build, tests/web/ohif/ from install_ohif.sh) reading soiqd in a real headless
# Chromium: serves OHIF on a free port, starts soiqd allowing that origin (CORS) and linking the
# query page's rows to it, imports STS_002's CT and its RT Structure Set with the CLI, computes the
# GTV SEG's voxels with pydicom (viewer_expected_mask.py, from soiqd's WADO-RS), then runs
# viewer_test.mjs (playwright-core driving Debian's /usr/bin/chromium).
#   run_viewer_test.sh SOIQ SOIQD
# SOIQ_SCREENSHOTS=DIR keeps the screenshots (default: in the test's temporary folder, removed).
set -euo pipefail
soiq=$1
soiqd=$2
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
# shellcheck source=SCRIPTDIR/../cli_remote/soiqd.sh
source "$here/../cli_remote/soiqd.sh"
if [ ! -f "$here/ohif/index.html" ]; then
  echo "FAIL: OHIF is missing in tests/web/ohif: scripts/install-deps installs it (tests/web/install_ohif.sh)"
  exit 1
fi
# shellcheck source=SCRIPTDIR/browser_checks.sh
source "$here/browser_checks.sh"

# OHIF first, on a free port: soiqd must name its origin. Its app-config.js is written once soiqd's
# HTTP port is known (it is read when the browser loads it, not now).
node "$here/serve_ohif.mjs" --config "$tmp/app-config.js" --port-file "$tmp/ohif.port" >"$tmp/ohif.log" 2>&1 &
soiqd_pids+=("$!") # stopped with soiqd by soiqd.sh's trap
for _ in $(seq 1 100); do
  [ -s "$tmp/ohif.port" ] && break
  sleep 0.05
done
if [ ! -s "$tmp/ohif.port" ]; then
  echo "FAIL: serve_ohif.mjs did not start: $(cat "$tmp/ohif.log")"
  exit 1
fi
ohif="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/ohif.port")"

# No token: OHIF's study list cannot send one (docs/INTEROP.md), as with `make run`.
start_soiqd viewer --http 127.0.0.1:0 --http-port-file "$tmp/viewer.http-port" --http-cors-origin "$ohif" \
  --viewer-url "$ohif/viewer?StudyInstanceUIDs={study}&initialSeriesInstanceUID={seg_series}"
http="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/viewer.http-port")"
sed "s|@DICOMWEB_ROOT@|$http/dicom-web|g" "$here/ohif_app_config.js.in" >"$tmp/app-config.js"
"$soiq" --server "$server" import "$here/../data/sts/STS_002/dicom/CT" >"$tmp/import.txt"
/usr/bin/python3 "$here/viewer_expected_mask.py" "$http/dicom-web" "$tmp/expected.json"

SOIQ_HTTP="$http" \
  SOIQ_OHIF="$ohif" \
  SOIQ_EXPECTED="$tmp/expected.json" \
  SOIQ_CHROMIUM="$chromium" \
  SOIQ_TMP="$tmp" \
  SOIQ_SCREENSHOTS="${SOIQ_SCREENSHOTS:-$tmp/screenshots}" \
  node --test --test-reporter=spec "$here/viewer_test.mjs"
echo "PASS"
