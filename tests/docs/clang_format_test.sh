#!/usr/bin/env bash
# Every tracked C++ file is as clang-format (the repository's .clang-format) writes it, so that
# `make format` is a no-op on a clean tree and a diff never mixes formatting with change.
# Usage: clang_format_test.sh SOURCE_DIR
# Exits 77 (ctest's SKIP_RETURN_CODE) when git or clang-format is missing or SOURCE_DIR is not a
# git work tree (a source tarball): there is nothing to list the files by.
set -uo pipefail
src=${1:?usage: clang_format_test.sh SOURCE_DIR}
format=${CLANG_FORMAT:-clang-format}
command -v git >/dev/null || { echo "SKIP: git is not installed"; exit 77; }
command -v "$format" >/dev/null || { echo "SKIP: $format is not installed"; exit 77; }
[ "$(git -C "$src" rev-parse --is-inside-work-tree 2>/dev/null)" = true ] ||
  { echo "SKIP: $src is not a git work tree"; exit 77; }
cd "$src" || exit 1
mapfile -d '' files < <(git ls-files -z '*.h' '*.cpp')
[ "${#files[@]}" -gt 0 ] || { echo "SKIP: no C++ files tracked"; exit 77; }
out=$(printf '%s\0' "${files[@]}" | xargs -0 "$format" --dry-run -Werror 2>&1)
rc=$?
if [ $rc -ne 0 ]; then
  echo "$out" | head -40
  echo "FAIL: these files are not clang-formatted ($("$format" --version)); run \`make format\`:"
  echo "$out" | grep -o '^[^: ]*\.\(h\|cpp\):' | sed 's/:$//' | sort -u | sed 's/^/  /'
  exit 1
fi
echo "clang_format_test: ${#files[@]} files clean ($("$format" --version))"
