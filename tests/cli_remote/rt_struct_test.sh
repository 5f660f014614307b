#!/usr/bin/env bash
# `soiq export-rtstruct` and `soiq pacs push --as rtstruct` end to end: a real soiqd, a real PACS
# (DCMTK's dcmqrscp on a free loopback port), the real `soiq`. The STS_002 CT GTV exported as an
# RT Structure Set that dciodvfy finds no error in, imported back with the same voxel count, pushed
# to the PACS and found there by DCMTK's findscu; errors with their exit codes and one line:
# structures of different series 2, unknown id 3, uploaded structure 4, bad usage 2.
# Usage: rt_struct_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"
sts_study=1.3.6.1.4.1.14519.5.2.1.5168.1900.190311276211389538203367070477

for tool in dcmqrscp echoscu findscu dcmdump dciodvfy; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is not installed (dcmtk, dicom3tools; scripts/install-deps)"; exit 1; }
done

free_port() {
  local port
  while :; do
    port=$((20000 + RANDOM % 40000))
    (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null || { echo "$port"; return; }
  done
}
pacs_port=$(free_port)
mkdir -p "$tmp/pacs/SOIQTEST"
cat >"$tmp/pacs/dcmqrscp.cfg" <<CFG
NetworkTCPPort = $pacs_port
MaxPDUSize = 65536
MaxAssociations = 16
HostTable BEGIN
HostTable END
VendorTable BEGIN
VendorTable END
AETable BEGIN
SOIQTEST $tmp/pacs/SOIQTEST RW (100, 256mb) ANY
AETable END
CFG
TCP_NODELAY=1 setsid dcmqrscp -c "$tmp/pacs/dcmqrscp.cfg" "$pacs_port" >"$tmp/pacs.log" 2>&1 &
pacs_pid=$!
trap 'kill -- -$pacs_pid 2>/dev/null; for p in "${soiqd_pids[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done; rm -rf "$tmp"' EXIT
for _ in $(seq 1 100); do
  echoscu -aec SOIQTEST 127.0.0.1 "$pacs_port" >/dev/null 2>&1 && break
  sleep 0.05
done

start_soiqd main --pacs "SOIQTEST@127.0.0.1:$pacs_port" --pacs-timeout 5
export SOIQ_SERVER=$server
"$soiq" import "$data/sts/STS_002/dicom" --format csv >"$tmp/import.csv" 2>"$tmp/import.err" ||
  fail "import: $(cat "$tmp/import.err")"
ct_id=$(sed -n 's/^structure,\([0-9]*\),STS_002,"GTV_Mass_CT,.*/\1/p' "$tmp/import.csv")
pt_id=$(sed -n 's/^structure,\([0-9]*\),STS_002,"GTV_Mass_PET,.*/\1/p' "$tmp/import.csv")
[ -n "$ct_id" ] && [ -n "$pt_id" ] || fail "import rows lack the GTVs: $(cat "$tmp/import.csv")"
ct_row=$(grep "^structure,$ct_id," "$tmp/import.csv")

# The export: one line, a file dciodvfy finds no error in.
"$soiq" export-rtstruct "$ct_id" -o "$tmp/rt/gtv.dcm" --description "GTV contours" >"$tmp/rt.out" ||
  fail "export-rtstruct: $(cat "$tmp/rt.out")"
grep -q "^DICOM RT Structure Set [0-9.]*: 1 ROI, [0-9]* contours, [0-9]* points, [0-9]* bytes, on series" "$tmp/rt.out" ||
  fail "export-rtstruct says: $(cat "$tmp/rt.out")"
dciodvfy "$tmp/rt/gtv.dcm" >"$tmp/dciodvfy.log" 2>&1
grep -q "RTStructureSet" "$tmp/dciodvfy.log" || fail "dciodvfy did not check an RT Structure Set: $(cat "$tmp/dciodvfy.log")"
grep "^Error" "$tmp/dciodvfy.log" && fail "dciodvfy finds errors in the export"

# Imported back: a new structure set of one structure with the GTV's voxel count (the round trip's
# voxel-for-voxel comparison is tests/server/structure_rt_struct_test.cpp).
"$soiq" import "$tmp/rt/gtv.dcm" --format csv >"$tmp/back.csv" 2>"$tmp/back.err" || fail "import back: $(cat "$tmp/back.err")"
back_row=$(grep '^structure,[0-9]*,STS_002,"GTV_Mass_CT' "$tmp/back.csv")
[ -n "$back_row" ] || fail "import back has no GTV row: $(cat "$tmp/back.csv")"
back_id=$(cut -d, -f2 <<<"$back_row")
[ "$back_id" != "$ct_id" ] || fail "the RT Structure Set came back as the same structure $ct_id"
[ "$(cut -d, -f4- <<<"$back_row" | sed 's/,[^,]*$//')" = "$(cut -d, -f4- <<<"$ct_row" | sed 's/,[^,]*$//')" ] ||
  fail "import back differs: $back_row vs $ct_row"

# Refusals, one line each.
expect 2 "export them separately" -- "$soiq" export-rtstruct "$ct_id" "$pt_id" -o "$tmp/both.dcm"
[ -e "$tmp/both.dcm" ] && fail "a refused export left a file"
expect 3 "999999" -- "$soiq" export-rtstruct 999999 -o "$tmp/x.dcm"
expect 2 "missing -o" -- "$soiq" export-rtstruct "$ct_id"
"$soiq" mesh "$data/ibsi_digital_phantom/mask.nii.gz" -o "$tmp/phantom.stl" >/dev/null || fail "soiq mesh"
up=$("$soiq" upload "$tmp/phantom.stl" --patient P1 --study 1.2.3 --name phantom -q) || fail "upload: $up"
expect 4 "soiq import" -- "$soiq" export-rtstruct "$up" -o "$tmp/up.dcm"
expect 2 "--as takes seg or rtstruct" -- "$soiq" pacs push --as rt "$ct_id"

# push --as rtstruct: the RT Structure Set is on the PACS, in the GTV's study, as DCMTK's findscu sees it.
"$soiq" pacs push --as rtstruct "$ct_id" >"$tmp/push.out" || fail "pacs push: $(cat "$tmp/push.out")"
rt_uid=$(sed -n 's/^stored DICOM RT Structure Set \([0-9.]*\) (1 ROI, .*/\1/p' "$tmp/push.out")
[ -n "$rt_uid" ] || fail "push says: $(cat "$tmp/push.out")"
findscu -v -S +sr -aec SOIQTEST -k QueryRetrieveLevel=IMAGE -k StudyInstanceUID="$sts_study" -k SeriesInstanceUID \
  -k SOPInstanceUID="$rt_uid" -k SOPClassUID 127.0.0.1 "$pacs_port" >"$tmp/findscu.log" 2>&1 ||
  fail "findscu: $(cat "$tmp/findscu.log")"
grep -q "Find Response: 1 (Pending)" "$tmp/findscu.log" ||
  fail "the pushed RT Structure Set is not on the PACS: $(cat "$tmp/findscu.log")"
stored=$(grep -rlF --exclude=index.dat "$rt_uid" "$tmp/pacs/SOIQTEST" | head -1)
dcmdump "$stored" >"$tmp/stored.dump" 2>&1 || fail "dcmdump cannot read what the PACS stored: $(head "$tmp/stored.dump")"
grep -q "(0008,0016) UI =RTStructureSetStorage" "$tmp/stored.dump" || fail "the PACS holds it under another SOP class"
grep -q "(3006,0026) LO \[GTV_Mass_CT\]" "$tmp/stored.dump" || fail "the stored RT Structure Set lacks its ROI name"
# The default stays a SEG.
"$soiq" pacs push "$ct_id" >"$tmp/push_seg.out" || fail "pacs push: $(cat "$tmp/push_seg.out")"
grep -q "^stored DICOM SEG" "$tmp/push_seg.out" || fail "plain push says: $(cat "$tmp/push_seg.out")"

finish rt_struct_test
