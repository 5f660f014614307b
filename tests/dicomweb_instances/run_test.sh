#!/usr/bin/env bash
# The original instances soiqd keeps, served by WADO-RS to a real HTTP client and judged by pydicom
# (an independent DICOM reader): instances byte for byte, metadata, frames (also decoded from
# JPEG-LS), CORS, the count in `soiq info`, and a soiqd that keeps none saying so.
#   run_test.sh SOIQ SOIQD
set -euo pipefail
soiq=$1
soiqd=$2
here=$(cd "$(dirname "$0")" && pwd)
data=$here/../data
tmp=$(mktemp -d)
source "$here/../cli_remote/soiqd.sh"

origin=http://127.0.0.1:9
start_soiqd kept --http 127.0.0.1:0 --http-port-file "$tmp/kept.http-port" --http-cors-origin "$origin"
base="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/kept.http-port")/dicom-web"
"$soiq" --server "$server" import "$data/sts/STS_002/dicom/CT" "$data/sts/STS_002/dicom_jpegls/MR_T1" >/dev/null
# The same files again store nothing twice.
"$soiq" --server "$server" import "$data/sts/STS_002/dicom/CT" >/dev/null
"$soiq" --server "$server" info >"$tmp/info"

start_soiqd none --http 127.0.0.1:0 --http-port-file "$tmp/none.http-port" --keep-instances off
none="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/none.http-port")/dicom-web"
"$soiq" --server "$server" import "$data/sts/STS_002/dicom/CT" >/dev/null

# With a token: the preflight needs none (browsers never send it there), every answer still does.
head -c 24 /dev/urandom | od -An -tx1 | tr -d ' \n' >"$tmp/token"
start_soiqd tok --http 127.0.0.1:0 --http-port-file "$tmp/tok.http-port" --http-cors-origin "$origin" \
  --token-file "$tmp/token"
tok="http://127.0.0.1:$(tr -d '[:space:]' <"$tmp/tok.http-port")/dicom-web"

SOIQ_TOKEN_BASE="$tok" SOIQ_TOKEN="$(cat "$tmp/token")" \
  /usr/bin/python3 "$here/wado_instances_test.py" "$base" "$none" "$origin" "$tmp/info" \
  "$data/sts/STS_002/dicom/CT/image" "$data/sts/STS_002/dicom_jpegls/MR_T1/image"
