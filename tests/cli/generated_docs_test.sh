#!/usr/bin/env bash
# What the build generates from the programs: the bash completion is `soiq completion bash`, and
# soiq(1) and soiqd(8) carry a title and every command (soiq) or flag (soiqd), and render without
# a warning when groff is installed.
# Usage: generated_docs_test.sh SOIQ BUILD_DIR
soiq=$1
build=$2
source "$(dirname "$0")/lib.sh"

$soiq completion bash >"$tmp/completion" || fail "soiq completion bash exited $?"
cmp -s "$tmp/completion" "$build/completion/soiq" || fail "$build/completion/soiq is not 'soiq completion bash'"

man1=$build/man/soiq.1
man8=$build/man/soiqd.8
grep -q '^\.TH SOIQ 1' "$man1" || fail "soiq.1 has no .TH"
grep -q '^\.TH SOIQD 8' "$man8" || fail "soiqd.8 has no .TH"
for cmd in mesh convert features compare upload upload-image import export-seg export-rtstruct "pacs echo" "pacs find" \
  "pacs pull" "pacs push" ls show rm download query info health demo-load help completion; do
  escaped=${cmd//-/\\-}
  grep -qF ".SS \"soiq $escaped\"" "$man1" || fail "soiq.1 lacks 'soiq $cmd'"
done
for flag in listen db port-file tls-cert token-file pacs; do
  grep -qF -- "\\-\\-${flag//-/\\-}" "$man8" || fail "soiqd.8 lacks --$flag"
done
if command -v groff >/dev/null; then
  for page in "$man1" "$man8"; do
    LC_ALL=C.UTF-8 groff -man -Tutf8 -ww -z "$page" 2>"$tmp/groff.err" || fail "groff failed on $page"
    [ -s "$tmp/groff.err" ] && fail "groff warns on $page: $(head -3 "$tmp/groff.err")"
  done
else
  echo "groff not installed: the pages' rendering is not checked"
fi

finish generated_docs_test
