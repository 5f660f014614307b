#!/usr/bin/env bash
# The query page (web/, served by soiqd --http at /) in a real headless Chromium: starts soiqd with a
# token, loads the demo cohort with the CLI, then runs query_page_test.mjs (playwright-core driving
# Debian's /usr/bin/chromium; no browser is downloaded), which types the demo's queries into the
# page and checks what it shows against GET /soiq/v1/query.
#   run_test.sh SOIQ SOIQD
# SOIQ_SCREENSHOTS=DIR keeps the screenshots (default: in the test's temporary folder, removed).
set -euo pipefail
soiq=$1
soiqd=$2
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
source "$here/../cli_remote/soiqd.sh"
# shellcheck source=SCRIPTDIR/browser_checks.sh
source "$here/browser_checks.sh"
# A random token, as soiqd asks (at least 16 characters).
head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/token"
# A viewer link, so that the page shows "open in viewer" (the host is never contacted).
start_soiqd web --http 127.0.0.1:0 --http-port-file "$tmp/web.http-port" --token-file "$tmp/token" \
  --viewer-url 'http://viewer.invalid:3000/viewer?StudyInstanceUIDs={study}'
# README's demo cohort (20 patients, 2 s); its "try:" lines are the queries the test types.
"$soiq" --server "$server" --token-file "$tmp/token" demo-load >"$tmp/demo-load.txt"
SOIQ_HTTP="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/web.http-port")" \
  SOIQ_TOKEN_FILE="$tmp/token" \
  SOIQ_DEMO_OUTPUT="$tmp/demo-load.txt" \
  SOIQ_CHROMIUM="$chromium" \
  SOIQ_TMP="$tmp" \
  SOIQ_SCREENSHOTS="${SOIQ_SCREENSHOTS:-$tmp/screenshots}" \
  node --test --test-reporter=spec "$here/query_page_test.mjs"
echo "PASS"
