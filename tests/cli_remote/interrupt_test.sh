#!/usr/bin/env bash
# Ctrl-C during each long remote command: it exits 130 with one line saying what it kept, leaves no
# output file behind, and no record changes. Deterministic: soiqd is stopped (SIGSTOP) while the
# command waits on it, so the signal always lands mid-call; soiqd is resumed afterwards and must
# store nothing of the cancelled calls. demo-load is interrupted for real, while soiqd works: it
# stops between two patients, so every patient it reports is whole. Then progress: shown on a
# terminal (a pty from `script`), not in a pipe, not with --quiet.
# Usage: interrupt_test.sh SOIQ SOIQD TEST_DATA_DIR
soiq=$1
soiqd=$2
data=$3
source "$(dirname "$0")/../cli/lib.sh"
source "$(dirname "$0")/soiqd.sh"

start_soiqd main
export SOIQ_SERVER=$server
phantom="$data/ibsi_digital_phantom"

"$soiq" mesh "$phantom/mask.nii.gz" -o "$tmp/phantom.stl" >/dev/null || fail "soiq mesh"
record=(--patient P1 --study 1.2.3 --modality CT)
id=$("$soiq" upload -q "$tmp/phantom.stl" "${record[@]}" --name phantom) || fail "upload: $id"
"$soiq" upload-image "$phantom/phantom.nii.gz" "${record[@]}" --series 1.2.3.1 >/dev/null || fail "upload-image"

counts() {
  "$soiq" info --format json | grep -oE '"(patients|studies|series|structures|surfaces)":"[0-9]+"' | tr '\n' ' '
}
before=$(counts)
[[ "$before" == *'"structures":"1"'* ]] || fail "the store does not hold the one structure: $before"

# interrupted KEPT CMD...: CMD starts while soiqd is stopped, gets SIGINT once it waits on it, and must
# exit 130 with "interrupted; KEPT" as its one line on stderr; then soiqd resumes and no record changed.
interrupted() {
  local kept=$1
  shift
  kill -STOP "$soiqd_pid"
  "$@" >"$tmp/out" 2>"$tmp/err" &
  local pid=$!
  # Signal once it waits on soiqd: it has a socket (a connection to the stopped server), so it is
  # past its start-up and argument parsing even on a loaded machine; a moment more to be in the call.
  for _ in $(seq 1 200); do
    ls -l "/proc/$pid/fd" 2>/dev/null | grep -q "socket:" && break
    sleep 0.05
  done
  sleep 0.3
  kill -INT "$pid"
  wait "$pid"
  local rc=$?
  kill -CONT "$soiqd_pid"
  [ "$rc" -eq 130 ] || fail "'${*:2}' interrupted exits $rc, not 130: $(cat "$tmp/err")"
  grep -q -- "interrupted; $kept" "$tmp/err" || fail "'${*:2}' interrupted says: $(cat "$tmp/err")"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "'${*:2}' interrupted prints more than one line: $(cat "$tmp/err")"
  [ "$(counts)" = "$before" ] || fail "'${*:2}' interrupted changed the records: $before -> $(counts)"
}

interrupted "nothing was stored" "$soiq" upload "$tmp/phantom.stl" --patient P2 --study 2.2 --name other
interrupted "nothing was stored" "$soiq" upload-image "$phantom/phantom.nii.gz" --patient P2 --study 2.2 \
  --series 2.2.1 --modality CT
interrupted "nothing was imported" "$soiq" import "$data/dicom/CT_small.dcm"
interrupted "no output was written" "$soiq" convert "$id" -o "$tmp/c/out.nii.gz"
[ -e "$tmp/c/out.nii.gz" ] && fail "an interrupted convert left its output"
interrupted "no values were printed" "$soiq" features "$id"
interrupted "no file was written" "$soiq" download "$id" -o "$tmp/d.stl"
[ -e "$tmp/d.stl" ] && fail "an interrupted download left its output"
interrupted "no file was written" "$soiq" export-seg "$id" -o "$tmp/s.dcm"
[ -e "$tmp/s.dcm" ] && fail "an interrupted export-seg left its output"
interrupted "the rows printed are part of the answer only" "$soiq" query --name phantom --select voxel_volume_mm3
interrupted "nothing was imported" "$soiq" pacs pull --study 1.2.3.4
interrupted "the PACS may have stored the object already" "$soiq" pacs push "$id"

# Every interrupted call reached soiqd once it resumed; it still serves and stored nothing.
[ "$("$soiq" health)" = SERVING ] || fail "soiqd does not serve after the interrupted calls"
[ "$(counts)" = "$before" ] || fail "records changed after soiqd resumed: $before -> $(counts)"

# demo-load interrupted while it loads: it finishes the patient in progress and stops.
"$soiq" demo-load --patients 100 >"$tmp/demo.out" 2>"$tmp/demo.err" &
pid=$!
for _ in $(seq 1 600); do
  grep -q "^DEMO_" "$tmp/demo.out" && break
  sleep 0.05
done
kill -INT "$pid"
wait "$pid"
rc=$?
[ "$rc" -eq 130 ] || fail "interrupted demo-load exits $rc: $(cat "$tmp/demo.err")"
loaded=$(sed -n 's/.*interrupted; \([0-9]*\) of 100 patients were loaded, each whole.*/\1/p' "$tmp/demo.err")
[ -n "$loaded" ] && [ "$loaded" -ge 1 ] && [ "$loaded" -lt 100 ] || fail "demo-load says: $(cat "$tmp/demo.err")"
[ "$(grep -c "^DEMO_" "$tmp/demo.out")" -eq "$loaded" ] || fail "demo-load printed other than $loaded patients"
# Whole patients: each has the cohort's 6 structures (bilateral hippocampus, amygdala, caudate).
"$soiq" ls structures --patient 'DEMO_*' --all --format csv >"$tmp/demo.csv" || fail "ls demo structures"
[ "$(($(wc -l <"$tmp/demo.csv") - 1))" -eq $((6 * loaded)) ] ||
  fail "$loaded demo patients hold $(($(wc -l <"$tmp/demo.csv") - 1)) structures, not $((6 * loaded))"

# Progress: on a terminal it is drawn ('\r' redraws with the stage), in a pipe or with --quiet not.
script -qec "'$soiq' upload '$tmp/phantom.stl' ${record[*]} --name again" /dev/null >"$tmp/tty" ||
  fail "upload on a pty: $(cat "$tmp/tty")"
grep -q "sending  " "$tmp/tty" || fail "no progress on a terminal: $(cat -A "$tmp/tty" | head -3)"
script -qec "'$soiq' --quiet upload '$tmp/phantom.stl' ${record[*]} --name again" /dev/null >"$tmp/tty" ||
  fail "upload --quiet on a pty"
grep -q "sending" "$tmp/tty" && fail "progress on a terminal despite --quiet: $(cat -A "$tmp/tty" | head -3)"
[[ "$(tr -d '\r\n' <"$tmp/tty")" =~ ^[0-9]+$ ]] || fail "upload --quiet printed more than the id: $(cat -A "$tmp/tty")"
"$soiq" upload "$tmp/phantom.stl" "${record[@]}" --name again >"$tmp/pipe" 2>&1 || fail "upload in a pipe"
grep -q "sending" "$tmp/pipe" && fail "progress in a pipe: $(cat -A "$tmp/pipe" | head -3)"
# --quiet drops the query's summary line, not its rows.
"$soiq" -q query --name phantom --select voxel_volume_mm3 >"$tmp/q.out" 2>"$tmp/q.err" || fail "query -q"
grep -q "^$id " "$tmp/q.out" || fail "query -q lacks the row: $(cat "$tmp/q.out")"
[ -s "$tmp/q.err" ] && fail "query -q printed on stderr: $(cat "$tmp/q.err")"
finish interrupt_test
