#!/usr/bin/env bash
# The CLI helps itself: help per command from the command table, "did you mean" for commands and
# options, and bash completion generated from the same table.
# Usage: help_test.sh SOIQ [DATA_DIR]
soiq=$1
source "$(dirname "$0")/lib.sh"

# Help per command, on stdout, exit 0, in each of its three spellings.
for form in "query --help" "query -h" "help query"; do
  $soiq $form >"$tmp/help" 2>"$tmp/err" || fail "'soiq $form' exited $?"
  grep -q -- "--where" "$tmp/help" || fail "'soiq $form' lacks --where: $(head -3 "$tmp/help")"
  grep -q "Exit codes" "$tmp/help" || fail "'soiq $form' lacks the exit codes"
  [ -s "$tmp/err" ] && fail "'soiq $form' wrote to stderr: $(cat "$tmp/err")"
done
for cmd in mesh convert features compare upload upload-image import export-seg export-rtstruct ls show rm download query info \
  health demo-load help completion "pacs echo" "pacs find" "pacs pull" "pacs push"; do
  $soiq $cmd --help >"$tmp/help" 2>&1 || fail "'soiq $cmd --help' exited $?"
  grep -q "^usage: soiq $cmd" "$tmp/help" || fail "'soiq $cmd --help': $(head -2 "$tmp/help")"
done
$soiq help >"$tmp/help" || fail "'soiq help' exited $?"
grep -q "Global options" "$tmp/help" || fail "'soiq help' lacks the global options"
grep -q "8 partial query answer" "$tmp/help" || fail "'soiq help' lacks the exit codes"

# Did you mean.
expect 2 "unknown command 'qeury'; did you mean 'query'?" -- $soiq qeury
expect 2 "did you mean 'query'?" -- $soiq help qeury
expect 2 "unknown option '--slect'; did you mean '--select'?" -- $soiq query --slect x
expect 2 "did you mean '--label'?" -- $soiq mesh m.nii.gz --lable 2 -o out.stl
expect 2 "did you mean 'find'?" -- $soiq pacs fnd
expect 2 "did you mean 'inside'?" -- $soiq query --where 'mean[insde,PT]>1'
expect 2 "unknown command 'frobnicate' (try 'soiq help')" -- $soiq frobnicate

# Bash completion from the same table.
$soiq completion bash >"$tmp/completion.bash" || fail "'soiq completion bash' exited $?"
complete_words() {  # complete_words WORD...: COMPREPLY for the last word, one per line
  bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _soiq; printf "%s\n" "${COMPREPLY[@]}"' \
    _ "$tmp/completion.bash" "$@"
}
[ "$(complete_words soiq qu)" = "query" ] || fail "soiq qu<TAB>: $(complete_words soiq qu)"
[ "$(complete_words soiq query --sel)" = "--select" ] || fail "soiq query --sel<TAB>: $(complete_words soiq query --sel)"
words=$(complete_words soiq query --select sphe)
grep -qx sphericity <<<"$words" || fail "--select sphe<TAB>: $words"
[ "$(complete_words soiq ls --format j)" = "json" ] || fail "ls --format j<TAB>: $(complete_words soiq ls --format j)"
[ "$(complete_words soiq pacs f)" = "find" ] || fail "soiq pacs f<TAB>: $(complete_words soiq pacs f)"
[ "$(complete_words soiq pacs find --lev)" = "--level" ] || fail "pacs find --lev<TAB>: $(complete_words soiq pacs find --lev)"
words=$(complete_words soiq features x.vtp --features voxel_count,sphe)
grep -qx voxel_count,sphericity <<<"$words" || fail "--features a,sphe<TAB>: $words"
# Inside a feature expression: regions after NAME[, names after asym( or an opening quote.
[ "$(complete_words soiq query --where 'mean[in')" = "mean[inside" ] ||
  fail "--where mean[in<TAB>: $(complete_words soiq query --where 'mean[in')"
[ "$(complete_words soiq query --select 'asym(voxel_vo')" = "asym(voxel_volume_mm3" ] ||
  fail "--select asym(voxel_vo<TAB>: $(complete_words soiq query --select 'asym(voxel_vo')"
words=$(complete_words soiq query --where "'sphe")
grep -qx "'sphericity" <<<"$words" || fail "--where 'sphe<TAB>: $words"
expect 2 "soiq completion bash" -- $soiq completion zsh

finish help_test
