# Shared by the command-line tests (sourced): a temporary folder, failure counting, and the checks
# every test makes of an error: its exit code, a phrase of its message, and that it is one line.
# Each test calls `finish NAME` last.
set -uo pipefail
# With pipefail, `cmd | grep -q` fails when grep leaves before cmd's last write (SIGPIPE): the tests
# capture output first and grep it (`grep -q X <<<"$(cmd)"`).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# expect CODE PHRASE -- command...: exit code, a phrase of stderr, and stderr one line long.
expect() {
  local code=$1 phrase=$2
  shift 3
  "$@" >"$tmp/out" 2>"$tmp/err"
  local got=$?
  [ "$got" -eq "$code" ] || fail "'$*' exited $got, expected $code: $(cat "$tmp/err")"
  grep -q -- "$phrase" "$tmp/err" || fail "'$*' stderr lacks '$phrase': $(cat "$tmp/err")"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "'$*' stderr is not one line: $(cat "$tmp/err")"
}

# within NAME VALUE REF TOL: |VALUE - REF| <= TOL
within() {
  awk -v v="$2" -v r="$3" -v t="$4" 'BEGIN { d = v - r; if (d < 0) d = -d; exit !(d <= t) }' ||
    fail "$1 = $2, expected $3 +- $4"
}

finish() {
  if [ "$failures" -eq 0 ]; then
    echo "$1: all passed"
  else
    echo "$1: $failures failed"
    exit 1
  fi
}
