#!/usr/bin/env bash
# README.md's command table ("## The command line") agrees with soiq's command table: every command
# soiq has (as its man page lists them) has a row, every row names a command, and every option a
# row shows is one that command's help lists.
# Usage: readme_commands_test.sh SOURCE_DIR SOIQ
src=$1
soiq=$2
source "$(dirname "$0")/../cli/lib.sh"

awk '/^## The command line/ { on = 1; next } /^## / { on = 0 } on && /^\| `soiq /' "$src/README.md" >"$tmp/rows"
[ -s "$tmp/rows" ] || fail "README.md has no command table under '## The command line'"
"$soiq" man | sed -n 's/^\.SS "soiq \(.*\)"$/\1/p' | sed 's/\\-/-/g' >"$tmp/names"
[ "$(wc -l <"$tmp/names")" -ge 20 ] || fail "soiq man lists $(wc -l <"$tmp/names") commands"

while read -r name; do
  grep -qE "^\| \`soiq $name( |\`)" "$tmp/rows" || fail "README.md's command table lacks 'soiq $name'"
done <"$tmp/names"

while read -r row; do
  cell=${row#| \`soiq }
  cell=${cell%%\` |*}
  command=''
  while read -r name; do # the longest command name the row starts with ("pacs find", not "pacs")
    if [[ "$cell" == "$name" || "$cell" == "$name "* ]] && [ ${#name} -gt ${#command} ]; then command=$name; fi
  done <"$tmp/names"
  if [ -z "$command" ]; then
    fail "README.md row names no soiq command: $row"
    continue
  fi
  "$soiq" help $command >"$tmp/help" || fail "soiq help $command exited $?"
  for option in $(printf '%s' "${cell#"$command"}" | tr -c 'a-z0-9-' '\n' | grep -E '^--?[a-z]' | sort -u); do
    grep -qE -- "^  $option([ ,]|$)|, $option( |$)" "$tmp/help" ||
      fail "README.md shows 'soiq $command $option', which 'soiq help $command' does not list"
  done
done <"$tmp/rows"

finish readme_commands_test
