// scripts/page-screenshot's browser side (that script says what it does).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

import { launchHeadlessChromium } from './headless_chromium.mjs';

const require = createRequire(path.join(process.env.NODE_PATH, 'index.js'));
const { chromium } = require('playwright-core');

const [url, out] = process.argv.slice(2);
const token = process.env.SOIQ_TOKEN_FILE ? fs.readFileSync(process.env.SOIQ_TOKEN_FILE, 'utf8').trim() : '';
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'soiq-page-'));
const context = await launchHeadlessChromium(chromium, profile);
try {
  const page = context.pages()[0] || (await context.newPage());
  // The token as the page keeps it for its tab (web/api.js), so that no dialog covers the picture.
  if (token) await page.addInitScript((t) => sessionStorage.setItem('soiq.token', t), token);
  const opened = Date.now();
  await page.goto(url);
  await page.waitForSelector('#results tbody tr', { timeout: 30_000 });
  const firstRowMs = Date.now() - opened;
  await page.waitForSelector('#summary:not([hidden])', { timeout: 60_000 });
  const error = await page.$('#error:not([hidden])');
  if (error) throw new Error(`the page shows an error: ${(await error.textContent()).trim()}`);
  // Every row's thumbnail drawn, and the plot when the query selects a feature.
  await page.waitForFunction(
    () => [...document.querySelectorAll('#results img.thumb')].every((i) => i.complete && i.naturalWidth > 0),
    null, { timeout: 60_000 });
  const plot = await page.$('#plot:not([hidden])');
  if (plot) await page.waitForFunction(() => {
    const img = document.querySelector('#plot img');
    return !img || (img.complete && img.naturalWidth > 0);
  }, null, { timeout: 30_000 });
  const rows = await page.$$eval('#results tbody tr', (r) => r.length);
  const thumbnails = await page.$$eval('#results img.thumb', (i) => i.length);
  await page.screenshot({ path: out, fullPage: true });
  console.log(`query page: ${rows} rows, ${thumbnails} thumbnails, ${plot ? 'a plot' : 'no plot'}; ` +
              `first row ${firstRowMs} ms after opening -> ${out}`);
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
