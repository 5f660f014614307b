#!/usr/bin/env bash
# The `soiq pacs` and `soiq export-seg` commands end to end: a real PACS (DCMTK's dcmqrscp on a
# free loopback port, loaded with storescu), a real soiqd started with --pacs, the real `soiq`.
# echo, find (patient and study level, csv), pull (rows as `soiq import`), export-seg (checked with
# DCMTK's dcmdump), push and the push seen on the PACS; errors with their exit codes and one line:
# no PACS configured 4, our AE title unknown to the PACS 7, PACS down 6, uploaded structure 4,
# unknown id 3, bad usage 2.
# Usage: pacs_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"
sts_study=1.3.6.1.4.1.14519.5.2.1.5168.1900.190311276211389538203367070477

for tool in dcmqrscp storescu dcmdump findscu; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is not installed (Debian package dcmtk; scripts/install-deps)"; exit 1; }
done

# A loopback port nobody listens on (a connect to it is refused); dcmqrscp cannot bind port 0.
free_port() {
  local port
  while :; do
    port=$((20000 + RANDOM % 40000))
    (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null || { echo "$port"; return; }
  done
}

pacs_port=$(free_port)
mkdir -p "$tmp/pacs/SOIQTEST" "$tmp/pacs/PICKY"
cat >"$tmp/pacs/dcmqrscp.cfg" <<CFG
NetworkTCPPort = $pacs_port
MaxPDUSize = 65536
MaxAssociations = 16
HostTable BEGIN
soiqonly = (SOIQ, localhost, 0)
HostTable END
VendorTable BEGIN
VendorTable END
AETable BEGIN
SOIQTEST $tmp/pacs/SOIQTEST RW (1000, 1024mb) ANY
PICKY $tmp/pacs/PICKY RW (10, 16mb) soiqonly
AETable END
CFG
TCP_NODELAY=1 setsid dcmqrscp -c "$tmp/pacs/dcmqrscp.cfg" "$pacs_port" >"$tmp/pacs.log" 2>&1 &
pacs_pid=$!
trap 'kill -- -$pacs_pid 2>/dev/null; for p in "${soiqd_pids[@]}"; do kill "$p" 2>/dev/null; wait "$p" 2>/dev/null; done; rm -rf "$tmp"' EXIT
for _ in $(seq 1 100); do
  echoscu -aec SOIQTEST 127.0.0.1 "$pacs_port" >/dev/null 2>&1 && break
  sleep 0.05
done
TCP_NODELAY=1 storescu -aec SOIQTEST +sd +r 127.0.0.1 "$pacs_port" "$data/sts/STS_002/dicom" "$data/dicom/CT_small.dcm" \
  >"$tmp/storescu.log" 2>&1 || { echo "FAIL: storescu: $(cat "$tmp/storescu.log")"; exit 1; }

# Without --pacs every pacs command is a failed precondition naming the flag.
start_soiqd nopacs
export SOIQ_SERVER=$server
expect 4 "start it with --pacs" -- "$soiq" pacs echo
stop_soiqd

start_soiqd main --pacs "SOIQTEST@127.0.0.1:$pacs_port" --pacs-timeout 5
export SOIQ_SERVER=$server
"$soiq" pacs echo >"$tmp/echo" || fail "pacs echo: $(cat "$tmp/echo")"
grep -q "PACS 'SOIQTEST' at 127.0.0.1:$pacs_port answered C-ECHO" "$tmp/echo" || fail "echo says: $(cat "$tmp/echo")"
grep -q "SOIQTEST" <<<"$("$soiq" info)" || fail "soiq info does not name the PACS"

"$soiq" pacs find --level patient --patient 'STS*' --format csv >"$tmp/patients.csv" 2>"$tmp/find.err" ||
  fail "pacs find patients: $(cat "$tmp/find.err")"
[ "$(sed -n 2p "$tmp/patients.csv" | cut -d, -f1)" = STS_002 ] || fail "find STS*: $(cat "$tmp/patients.csv")"
[ "$(wc -l <"$tmp/patients.csv")" -eq 2 ] || fail "find STS* is not one patient: $(cat "$tmp/patients.csv")"
"$soiq" pacs find --study-date 20060101-20060131 --format csv >"$tmp/studies.csv" 2>/dev/null || fail "find by date"
grep -q ",$sts_study,20060128," "$tmp/studies.csv" || fail "find by date range: $(cat "$tmp/studies.csv")"
"$soiq" pacs find --study-date 20070101- --format csv >"$tmp/none.csv" 2>"$tmp/none.err" || fail "find after 2007"
grep -q "$sts_study" "$tmp/none.csv" && fail "a 2006 study matched 2007-: $(cat "$tmp/none.csv")"
grep -q "^0 matches on PACS 'SOIQTEST'" "$tmp/none.err" || fail "find summary: $(cat "$tmp/none.err")"
expect 2 "study_date" -- "$soiq" pacs find --study-date 2006-01-28
expect 2 "--study UID" -- "$soiq" pacs pull
expect 2 "unknown pacs command" -- "$soiq" pacs fetch

"$soiq" pacs pull --study "$sts_study" --format csv >"$tmp/pull.csv" 2>"$tmp/pull.err" ||
  fail "pacs pull: $(cat "$tmp/pull.err")"
grep -q "imported 2 series and 2 structures from 98 files" "$tmp/pull.err" || fail "pull summary: $(cat "$tmp/pull.err")"
ct_id=$(sed -n 's/^structure,\([0-9]*\),STS_002,"GTV_Mass_CT,.*/\1/p' "$tmp/pull.csv")
pt_id=$(sed -n 's/^structure,\([0-9]*\),STS_002,"GTV_Mass_PET,.*/\1/p' "$tmp/pull.csv")
[ -n "$ct_id" ] && [ -n "$pt_id" ] || fail "pull rows lack the GTVs: $(cat "$tmp/pull.csv")"
"$soiq" pacs pull --patient STS_002 --format csv >/dev/null 2>"$tmp/pull2.err" || fail "pull by patient"
grep -q "2 of the structures were there already and were updated" "$tmp/pull2.err" ||
  fail "re-pull summary: $(cat "$tmp/pull2.err")"
expect 3 "has no instances" -- "$soiq" pacs pull --study 1.2.3.4.5.6.7.8.9

# export-seg: a DICOM Segmentation of the CT GTV that DCMTK reads, referencing the CT series.
"$soiq" export-seg "$ct_id" -o "$tmp/gtv.dcm" --description "GTV review" >"$tmp/seg.out" ||
  fail "export-seg: $(cat "$tmp/seg.out")"
grep -q "1 segment, .* frames" "$tmp/seg.out" || fail "export-seg says: $(cat "$tmp/seg.out")"
dcmdump "$tmp/gtv.dcm" >"$tmp/gtv.dump" 2>&1 || fail "dcmdump cannot read the SEG: $(head "$tmp/gtv.dump")"
grep -q "(0008,0060) CS \[SEG\]" "$tmp/gtv.dump" || fail "SEG modality missing"
grep -q "(0062,0005) LO \[GTV_Mass_CT\]" "$tmp/gtv.dump" || fail "segment label missing"
grep -q "(0008,103e) LO \[GTV review\]" "$tmp/gtv.dump" || fail "series description missing"
expect 4 "one SEG references one series" -- "$soiq" export-seg "$ct_id" "$pt_id" -o "$tmp/both.dcm"
[ -e "$tmp/both.dcm" ] && fail "a refused export left a file"
expect 3 "999999" -- "$soiq" export-seg 999999 -o "$tmp/x.dcm"
expect 2 "missing -o" -- "$soiq" export-seg "$ct_id"
"$soiq" mesh "$data/ibsi_digital_phantom/mask.nii.gz" -o "$tmp/phantom.stl" >/dev/null || fail "soiq mesh"
up=$("$soiq" upload "$tmp/phantom.stl" --patient P1 --study 1.2.3 --name phantom -q) || fail "upload: $up"
expect 4 "soiq import" -- "$soiq" export-seg "$up" -o "$tmp/up.dcm"

# push: the SEG is stored on the PACS: DCMTK's own findscu finds its SOP instance in the study.
"$soiq" pacs push "$ct_id" >"$tmp/push.out" || fail "pacs push: $(cat "$tmp/push.out")"
seg_uid=$(sed -n 's/^stored DICOM SEG \([0-9.]*\) .*/\1/p' "$tmp/push.out")
[ -n "$seg_uid" ] || fail "push says: $(cat "$tmp/push.out")"
findscu -v -S +sr -aec SOIQTEST -k QueryRetrieveLevel=IMAGE -k StudyInstanceUID="$sts_study" -k SeriesInstanceUID -k SOPInstanceUID="$seg_uid" \
  127.0.0.1 "$pacs_port" >"$tmp/findscu.log" 2>&1 || fail "findscu: $(cat "$tmp/findscu.log")"
grep -q "Find Response: 1 (Pending)" "$tmp/findscu.log" || fail "the pushed SEG is not on the PACS: $(cat "$tmp/findscu.log")"

# A PACS that does not know our calling AE title: exit 7, the PACS's reason kept.
main_server=$server main_pid=$soiqd_pid
start_soiqd picky --pacs "PICKY@127.0.0.1:$pacs_port" --pacs-calling-ae STRANGER --pacs-timeout 5
expect 7 "rejected the C-ECHO association (calling AE 'STRANGER')" -- "$soiq" pacs echo --server "$server"
stop_soiqd
server=$main_server soiqd_pid=$main_pid

# A PACS that is down: unavailable, exit 6, naming where it was looked for.
kill -- -"$pacs_pid" 2>/dev/null
wait "$pacs_pid" 2>/dev/null
expect 6 "127.0.0.1:$pacs_port" -- "$soiq" pacs echo
expect 6 "127.0.0.1:$pacs_port" -- "$soiq" pacs push "$ct_id"
# ... and the message blames the PACS, not soiqd (which answered).
"$soiq" pacs echo 2>"$tmp/down.err"
grep -q "cannot reach soiqd" "$tmp/down.err" && fail "a PACS that is down is reported as soiqd: $(cat "$tmp/down.err")"
grep -q "PACS" "$tmp/down.err" || fail "a PACS that is down is not named: $(cat "$tmp/down.err")"

finish pacs_test
