#!/usr/bin/env bash
# OHIF's published build (npm @ohif/app, a ready-built static site in package/dist) into
# tests/web/ohif/, for the viewer test (web.viewer) and `make viewer`. The tarball is pinned by its
# sha512 (npm's integrity string), so a changed upload is refused rather than run. Not `npm i`: that
# pulls OHIF's whole dependency tree and asks for Node >= 24, while dist/ is all a browser needs.
#   install_ohif.sh            (does nothing when tests/web/ohif/ holds this version already)
set -euo pipefail
version=3.13.2
# `npm view @ohif/app@3.13.2 dist.integrity`
integrity=sha512-WZdxmpmG7rqFgW9ZJLcbgr3XCtLi1KDNPoMaeY5PPe6j4G4fjEjjkycZM6C6Zk2F87BKxFfpq+jd5xXZB9E8EA==
here=$(cd "$(dirname "$0")" && pwd)
dest=$here/ohif
marker=$dest/.soiq-ohif-version

if [ "$(cat "$marker" 2>/dev/null)" = "$version" ]; then
  exit 0
fi
for tool in npm openssl tar; do
  command -v "$tool" >/dev/null || { echo "install_ohif: $tool is missing (scripts/install-deps installs it)" >&2; exit 1; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "install_ohif: fetching @ohif/app@$version (50 MB)"
if ! (cd "$tmp" && npm pack "@ohif/app@$version" --loglevel=error >npm-pack.out 2>npm-pack.err); then
  # npm's second error line says why (the first is only its code).
  echo "install_ohif: npm pack @ohif/app@$version failed: $(grep -m 1 -v 'error code' "$tmp/npm-pack.err")" >&2
  exit 1
fi
tarball=$tmp/$(tail -n 1 "$tmp/npm-pack.out")
got=sha512-$(openssl dgst -sha512 -binary "$tarball" | base64 -w0)
if [ "$got" != "$integrity" ]; then
  echo "install_ohif: @ohif/app@$version's tarball has sha512 $got, not the pinned $integrity: refused" >&2
  exit 1
fi
tar -xzf "$tarball" -C "$tmp" package/dist
if [ ! -f "$tmp/package/dist/index.html" ]; then
  echo "install_ohif: @ohif/app@$version's tarball has no package/dist/index.html" >&2
  exit 1
fi
# onnxruntime's wasm for OHIF's AI tools (about 100 MB): viewing images never loads it.
rm -rf "$tmp/package/dist/ort"
# Replaced whole, then marked last: an interrupted run leaves no marker and is done again.
rm -rf "$dest"
mv "$tmp/package/dist" "$dest"
echo "$version" >"$marker"
echo "install_ohif: OHIF $version in $dest"
