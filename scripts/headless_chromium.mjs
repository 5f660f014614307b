// Debian's Chromium, headless, as soiq's browser tests and scripts/page-screenshot start it through
// playwright-core (which downloads no browser): a fresh profile in `profile`, and no network of the
// browser's own (updates, sync, QUIC, component downloads: this machine's closed network refuses
// them, many at a time), so only the pages under test and soiqd are reached.
//   launchHeadlessChromium(chromium, profile, options)  playwright-core's `chromium`; options are
//   added to launchPersistentContext's (viewport 1280 x 900 unless given). SOIQ_CHROMIUM overrides
//   /usr/bin/chromium.
export function launchHeadlessChromium(chromium, profile, options = {}) {
  return chromium.launchPersistentContext(profile, {
    executablePath: process.env.SOIQ_CHROMIUM || '/usr/bin/chromium',
    args: [
      '--headless',
      '--no-sandbox',
      '--disable-gpu',
      '--disable-quic',
      '--no-first-run',
      '--disable-background-networking',
      '--disable-component-update',
      '--disable-sync',
    ],
    viewport: { width: 1280, height: 900 },
    ...options,
  });
}
