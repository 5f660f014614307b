#!/usr/bin/env bash
# docs/ARCHITECTURE.md's dependency graph is CMake's: the block between its "targets:begin" and
# "targets:end" markers must equal scripts/target-graph's output.
# Usage: architecture_test.sh SOURCE_DIR
src=$1
source "$(dirname "$0")/../cli/lib.sh"
"$src/scripts/target-graph" "$src" >"$tmp/graph.txt" || fail "scripts/target-graph failed"
sed -n '/targets:begin/,/targets:end/p' "$src/docs/ARCHITECTURE.md" | sed '1d;$d' | sed '/^```/d' >"$tmp/doc.txt"
diff -u "$tmp/doc.txt" "$tmp/graph.txt" >"$tmp/graph.diff" ||
  fail "docs/ARCHITECTURE.md's target graph differs from CMake's (scripts/target-graph): $(cat "$tmp/graph.diff")"
finish architecture_test
