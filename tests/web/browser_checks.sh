# Sourced by the browser tests (run_test.sh, run_viewer_test.sh) after setting $here: fails at once,
# in one line, when what scripts/install-deps installs for them is missing, and sets $chromium.
if [ ! -d "$here/node_modules/playwright-core" ]; then
  echo "FAIL: tests/web/node_modules is missing: scripts/install-deps installs it (npm ci)"
  exit 1
fi
chromium=${SOIQ_CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$chromium" ]; then
  echo "FAIL: $chromium is missing: scripts/install-deps installs Debian's chromium"
  exit 1
fi
