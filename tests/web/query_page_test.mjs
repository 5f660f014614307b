// soiqd's query page (web/, served at /) in a real headless Chromium, driven by playwright-core as a
// user would drive it: the token asked on the first 401 (a wrong one said clearly), the demo's
// queries typed into the form, and what the page shows checked against GET /soiq/v1/query (the plain
// JSON answer, fetched here with the token): the rows and their values, every row's thumbnail (loaded,
// not black, with the structure's red), the plot, soiqd's "did you mean" for a misspelt feature,
// an error that comes mid-stream, the downloads, and a shared URL that runs its query again.
// Prints the time from the click on "Run query" to the first row in the table (the target is 300 ms;
// a figure, not an assertion).
//   SOIQ_HTTP=http://127.0.0.1:PORT SOIQ_TOKEN_FILE=F SOIQ_DEMO_OUTPUT=demo-load.txt SOIQ_TMP=DIR \
//     [SOIQ_SCREENSHOTS=DIR] [SOIQ_CHROMIUM=/usr/bin/chromium] node --test query_page_test.mjs
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { after, before, describe, test } from 'node:test';
import { chromium } from 'playwright-core';

import { launchHeadlessChromium } from '../../scripts/headless_chromium.mjs';

const base = process.env.SOIQ_HTTP;
const token = fs.readFileSync(process.env.SOIQ_TOKEN_FILE, 'utf8').trim();
const tmp = process.env.SOIQ_TMP || fs.mkdtempSync(path.join(os.tmpdir(), 'soiq-web-'));
const shots = process.env.SOIQ_SCREENSHOTS || path.join(tmp, 'screenshots');
fs.mkdirSync(shots, { recursive: true });

// The queries `soiq demo-load` suggests on its "try:" lines (README's first session), as the URL
// arguments the page should produce: `soiq query`'s options without dashes. `soiq ls structures
// --name hippocampus` is a listing whose filter the query takes too, so it is typed as that query.
function parseShellWords(line) {
  const words = [];
  for (const m of line.matchAll(/'([^']*)'|"([^"]*)"|(\S+)/g)) words.push(m[1] ?? m[2] ?? m[3]);
  return words;
}

function demoQueries(flags) {
  const text = fs.readFileSync(process.env.SOIQ_DEMO_OUTPUT, 'utf8');
  const tryAt = text.indexOf('\ntry:\n');
  assert.ok(tryAt >= 0, `no "try:" lines in soiq demo-load's output:\n${text}`);
  const queries = [];
  for (const line of text.slice(tryAt + 6).split('\n')) {
    const words = parseShellWords(line.trim());
    if (words[0] !== 'soiq') continue;
    let rest;
    if (words[1] === 'query') rest = words.slice(2);
    else if (words[1] === 'ls' && words[2] === 'structures') rest = words.slice(3);
    else continue;
    const args = [];
    for (let i = 0; i < rest.length; i++) {
      const name = rest[i].replace(/^--/, '');
      if (flags.has(name)) args.push([name, 'true']);
      else args.push([name, rest[++i]]);
    }
    queries.push({ command: line.trim(), args });
  }
  return queries;
}

async function api(pathAndQuery, accept = 'application/json') {
  const response = await fetch(`${base}${pathAndQuery}`, {
    headers: { Authorization: `Bearer ${token}`, Accept: accept },
  });
  const body = await response.text();
  assert.equal(response.status, 200, `GET ${pathAndQuery}: ${response.status} ${body}`);
  return JSON.parse(body);
}

// soiq query's number text (%.10g), the rule the page shows values by.
function shown(value) {
  if (value === null) return '—';
  if (Array.isArray(value)) return value.map(shown).join(', ');
  if (typeof value === 'number') return Number.isInteger(value) ? String(value) : String(Number(value.toPrecision(10)));
  return String(value);
}

let context;
let page;
let info;
const pageErrors = [];
const firstRowTimes = [];

// Types a query into the form as a user would: choices picked, flags ticked, "+" clicked for a
// second where or select.
async function typeQuery(args) {
  await page.click('#clear');
  const used = new Map();
  for (const [name, value] of args) {
    const option = info.query_options.find((o) => o.name === name);
    assert.ok(option, `the demo's option --${name} is not in soiqd's query table`);
    const index = used.get(name) || 0;
    used.set(name, index + 1);
    const field = page.locator(`.field[data-option="${name}"]`);
    if (index > 0) await field.locator('button.add').click();
    const input = field.locator(`[name="${name}"]`).nth(index);
    const tag = await input.evaluate((e) => (e.type === 'checkbox' ? 'checkbox' : e.tagName));
    if (tag === 'checkbox') await input.check();
    else if (tag === 'SELECT') await input.selectOption(value);
    else await input.fill(value);
  }
}

// Clicks "Run query" and measures, in the page, the time from the click to the first row in the
// table; waits for the summary (or the error box).
async function runQuery() {
  await page.evaluate(() => {
    window.__timing = { clicked: 0, firstRow: 0 };
    const body = document.querySelector('#results tbody');
    const observer = new MutationObserver(() => {
      if (!window.__timing.firstRow && body.querySelector('tr')) {
        window.__timing.firstRow = performance.now();
        observer.disconnect();
      }
    });
    observer.observe(body, { childList: true });
    document
      .querySelector('#run')
      .addEventListener('click', () => (window.__timing.clicked = performance.now()), { once: true, capture: true });
  });
  await page.click('#run');
  await page.waitForSelector('#summary:not([hidden]), #error:not([hidden])', { timeout: 60_000 });
  const t = await page.evaluate(() => window.__timing);
  return t.firstRow ? t.firstRow - t.clicked : null;
}

// Every row's thumbnail: scrolled into view (they load lazily), loaded, and drawn on a canvas to
// read its pixels: the image slice is not black, and the structure's red overlay is there.
async function checkThumbnails(ids) {
  for (const id of ids) {
    const img = page.locator(`#results tbody tr[data-id="${id}"] img.thumb`);
    await img.scrollIntoViewIfNeeded();
    await page.waitForFunction(
      (e) => ['loaded', 'failed'].includes(e.dataset.state),
      await img.elementHandle(),
      { timeout: 30_000 },
    );
    const pixels = await img.evaluate((e) => {
      const canvas = document.createElement('canvas');
      canvas.width = e.naturalWidth;
      canvas.height = e.naturalHeight;
      const g = canvas.getContext('2d');
      g.drawImage(e, 0, 0);
      const data = g.getImageData(0, 0, canvas.width, canvas.height).data;
      let lit = 0;
      let red = 0;
      for (let i = 0; i < data.length; i += 4) {
        const [r, gr, b] = [data[i], data[i + 1], data[i + 2]];
        if (r + gr + b > 30) lit++;
        if (r > 150 && r - gr > 60 && r - b > 60) red++;
      }
      return { state: e.dataset.state, title: e.title, width: e.naturalWidth, lit, red, total: data.length / 4 };
    });
    assert.equal(pixels.state, 'loaded', `structure ${id}'s thumbnail did not load: ${pixels.title}`);
    assert.ok(pixels.width > 0, `structure ${id}'s thumbnail has no width`);
    assert.ok(pixels.lit > 0, `structure ${id}'s thumbnail is all black`);
    assert.ok(pixels.red > 0, `structure ${id}'s thumbnail has no red overlay pixel (${JSON.stringify(pixels)})`);
  }
}

async function tableRows() {
  return page.$$eval('#results tbody tr', (trs) =>
    trs.map((tr) => ({
      id: Number(tr.dataset.id),
      cells: Object.fromEntries([...tr.querySelectorAll('td[data-column]')].map((td) => [td.dataset.column, td.textContent])),
    })),
  );
}

async function errorText() {
  await page.waitForSelector('#error:not([hidden])', { timeout: 30_000 });
  return page.textContent('#error');
}

describe('the query page', () => {
  before(async () => {
    context = await launchHeadlessChromium(chromium, fs.mkdtempSync(path.join(tmp, 'chromium-')), {
      acceptDownloads: true,
    });
    page = context.pages()[0] || (await context.newPage());
    page.on('pageerror', (error) => pageErrors.push(`uncaught: ${error.message}`));
    page.on('console', (m) => {
      // 4xx answers the tests ask for show up as console errors too; only script errors count.
      if (m.type() === 'error' && !/Failed to load resource/.test(m.text())) pageErrors.push(m.text());
    });
    info = await api('/soiq/v1/info');
  });

  after(async () => {
    await context?.close();
    if (firstRowTimes.length)
      console.log(
        `submit to first row (ms): ${firstRowTimes.map(([q, t]) => `${t === null ? 'no row' : t.toFixed(1)} (${q})`).join('; ')} (target <= 300)`,
      );
    console.log(`screenshots: ${shots}`);
  });

  test('the page comes without a token, asks for one, and says a wrong one is refused', async () => {
    const response = await page.goto(`${base}/`);
    assert.equal(response.status(), 200, 'GET / is not served without a token');
    await page.waitForSelector('#token-dialog[open]');
    await page.fill('#token-input', 'not-the-token-0123456789');
    await page.click('#token-dialog button[value="ok"]');
    const text = await errorText();
    assert.match(text, /refused the token/);
    assert.match(text, /not valid/, `the error box does not say why: ${text}`);
    await page.waitForSelector('#token-dialog[open]');
    assert.match(await page.textContent('#token-message'), /refused the token/);
    await page.screenshot({ path: path.join(shots, 'wrong-token.png') });
    await page.fill('#token-input', token);
    await page.click('#token-dialog button[value="ok"]');
    await page.waitForSelector('#run:not([disabled])');
    assert.equal(await page.isVisible('#error'), false, 'the error box stays after the right token');
    assert.equal(await page.evaluate(() => sessionStorage.getItem('soiq.token')), token);
    // The form is soiqd's table: every option has its labelled input.
    for (const o of info.query_options) {
      const labelled = await page.locator(`#opt-${o.name}`).evaluate((e) => e.labels.length > 0);
      assert.ok(labelled, `the ${o.name} input has no label`);
    }
  });

  test("the demo's queries: rows as the API gives them, thumbnails, plot", async () => {
    const flags = new Set(info.query_options.filter((o) => !o.placeholder).map((o) => o.name));
    const queries = demoQueries(flags);
    assert.equal(queries.length, 5, `expected the demo's five query lines, got ${queries.map((q) => q.command)}`);
    for (const [n, { command, args }] of queries.entries()) {
      await typeQuery(args);
      const firstRowMs = await runQuery();
      firstRowTimes.push([command.replace(/^soiq /, ''), firstRowMs]);
      assert.equal(await page.isVisible('#error'), false, `${command}: ${await page.textContent('#error')}`);
      // The URL holds the query: the form's arguments are the demo's (the form's order is soiqd's table's).
      const search = new URLSearchParams(new URL(page.url()).search);
      const sorted = (pairs) => pairs.map(([k, v]) => `${k}=${v}`).sort();
      assert.deepEqual(sorted([...search]), sorted(args), `${command}: the URL says ${search}`);
      const expected = await api(`/soiq/v1/query?${search}`);
      const rows = await tableRows();
      assert.ok(rows.length > 0, `${command}: no row in the table`);
      assert.equal(rows.length, expected.rows.length, `${command}: the table's rows against the API's`);
      // The streamed order is the query's when it has an order-by, else the workers'; compare by id.
      if (search.has('order-by'))
        assert.deepEqual(rows.map((r) => r.id), expected.rows.map((r) => r.id), `${command}: row order`);
      const byId = new Map(rows.map((r) => [r.id, r]));
      for (const want of expected.rows) {
        const got = byId.get(want.id);
        assert.ok(got, `${command}: structure ${want.id} is not in the table`);
        for (const column of expected.columns)
          assert.equal(got.cells[column], shown(want[column]), `${command}: structure ${want.id}'s ${column}`);
      }
      const headings = await page.$$eval('#results thead th[data-column]', (ths) => ths.map((th) => th.dataset.column));
      assert.deepEqual(headings, expected.columns, `${command}: the table's columns`);
      const summary = await page.textContent('#summary');
      assert.match(summary, new RegExp(`\\b${expected.summary.stage1_candidates} candidates\\b`), summary);
      assert.match(summary, new RegExp(`\\b${expected.summary.matched} matched\\b`), summary);
      assert.match(summary, /total [\d.]+ ms/, summary);
      await checkThumbnails(expected.rows.map((r) => r.id));
      // run_test.sh gives soiqd a viewer: each row links its study there, the UID URL-encoded.
      assert.ok(info.viewer_url.includes('{study}'), `soiqd's viewer_url: '${info.viewer_url}'`);
      for (const want of expected.rows) {
        const href = await page.getAttribute(`#results tbody tr[data-id="${want.id}"] a.viewer`, 'href');
        assert.equal(href, info.viewer_url.replaceAll('{study}', encodeURIComponent(want.study_uid)));
      }
      if (search.has('select')) {
        await page.waitForSelector('#plot:not([hidden]) .plot-body img', { timeout: 30_000 });
        const plot = await page.$eval('#plot .plot-body img', (img) => ({
          natural: img.naturalWidth,
          box: img.getBoundingClientRect().width * img.getBoundingClientRect().height,
        }));
        assert.ok(plot.natural > 0 && plot.box > 0, `${command}: the plot has no size ${JSON.stringify(plot)}`);
      }
      await page.evaluate(() => window.scrollTo(0, 0));
      await page.screenshot({ path: path.join(shots, `demo-query-${n + 1}.png`), fullPage: true });
    }
  });

  test('a column heading sorts the rows; a third click restores their arrival order', async () => {
    await typeQuery([['name', 'hippocampus'], ['select', 'voxel_volume_mm3']]);
    await runQuery();
    const arrival = (await tableRows()).map((r) => r.id);
    const sortButton = page.locator('#results thead th[data-column="voxel_volume_mm3"] button');
    await sortButton.click();
    const volumes = (await tableRows()).map((r) => Number(r.cells.voxel_volume_mm3));
    assert.deepEqual(volumes, [...volumes].sort((a, b) => a - b), 'ascending after one click');
    await sortButton.click();
    const down = (await tableRows()).map((r) => Number(r.cells.voxel_volume_mm3));
    assert.deepEqual(down, [...down].sort((a, b) => b - a), 'descending after two');
    await sortButton.click();
    assert.deepEqual((await tableRows()).map((r) => r.id), arrival, 'arrival order after three');
  });

  test("a misspelt feature: soiqd's message and its suggestion in the error box, the field marked", async () => {
    await typeQuery([['name', 'hippocampus'], ['select', 'voxel_volum_mm3']]);
    await runQuery();
    const text = await errorText();
    assert.match(text, /unknown feature 'voxel_volum_mm3'/, text);
    assert.match(text, /did you mean 'voxel_volume_mm3'\?/, text);
    assert.match(text, /select\[0\]/, `the error box does not name the field: ${text}`);
    assert.equal(await page.getAttribute('#opt-select', 'aria-invalid'), 'true', 'the select input is not marked');
    assert.equal(await page.getAttribute('#error', 'role'), 'alert');
    await page.evaluate(() => window.scrollTo(0, 0));
    await page.screenshot({ path: path.join(shots, 'did-you-mean.png') });
    // The suggestion, taken with one click, runs the query again with the name corrected.
    await page.click('#error button.suggestion');
    await page.waitForSelector('#summary:not([hidden])', { timeout: 30_000 });
    assert.equal(await page.inputValue('#opt-select'), 'voxel_volume_mm3');
    assert.equal(await page.isVisible('#error'), false, 'the error box stays after the corrected query');
    assert.ok((await tableRows()).length > 0, 'no row after the corrected query');
  });

  test('an error in the stream, after its first line, is shown in words', async () => {
    await typeQuery([['name', 'hippocampus'], ['where', 'mean[inside,XX]>1']]);
    await runQuery();
    const text = await errorText();
    assert.match(text, /modality 'XX'/, text);
  });

  test('downloads: the mask and the surface under soiqd\'s file names; a SEG soiqd cannot make is said', async () => {
    await typeQuery([['name', 'amygdala'], ['limit', '2']]);
    await runQuery();
    const row = page.locator('#results tbody tr').first();
    const id = await row.getAttribute('data-id');
    for (const [what, pattern] of [['mask', /\.nii\.gz$/], ['surface', /\.stl$/]]) {
      const [download] = await Promise.all([
        page.waitForEvent('download'),
        row.locator(`button[data-download="${what}"]`).click(),
      ]);
      assert.match(download.suggestedFilename(), pattern, `${what}: ${download.suggestedFilename()}`);
      const file = path.join(tmp, download.suggestedFilename());
      await download.saveAs(file);
      assert.ok(fs.statSync(file).size > 0, `${what}: an empty download`);
    }
    // The demo's structures were uploaded as surfaces: soiqd has no DICOM images for a SEG.
    await row.locator('button[data-download="seg"]').click();
    const text = await errorText();
    assert.match(text, new RegExp(`structure ${id}`), text);
    assert.match(text, /not imported from DICOM/, text);
  });

  test('a shared link runs its query on load, the form filled from it', async () => {
    await page.goto(`${base}/?name=hippocampus&min-age=60&select=voxel_volume_mm3&select=sphericity&order-by=voxel_volume_mm3&desc=true&limit=5`);
    await page.waitForSelector('#summary:not([hidden])', { timeout: 30_000 });
    assert.equal(await page.inputValue('#opt-name'), 'hippocampus');
    assert.equal(await page.isChecked('#opt-desc'), true);
    assert.equal(await page.locator('[name="select"]').count(), 2);
    const expected = await api('/soiq/v1/query?name=hippocampus&min-age=60&select=voxel_volume_mm3&select=sphericity&order-by=voxel_volume_mm3&desc=true&limit=5');
    assert.deepEqual((await tableRows()).map((r) => r.id), expected.rows.map((r) => r.id));
    await checkThumbnails(expected.rows.map((r) => r.id));
    await page.waitForSelector('#plot:not([hidden]) .plot-body img', { timeout: 30_000 });
    await page.evaluate(() => window.scrollTo(0, 0));
    // The README's picture: the form, the rows with their thumbnails, the summary and the plot
    // (the whole page: 1280 wide, a little over the window's 900 high).
    await page.screenshot({ path: path.join(shots, 'query-page.png'), fullPage: true });
  });

  test("the browser's back button returns to the previous query, its form and its rows", async () => {
    await typeQuery([['name', 'caudate'], ['laterality', 'R']]);
    await runQuery();
    // Without an order-by, rows come as the workers finish them: compare the sets of ids.
    const ids = async () => (await tableRows()).map((r) => r.id).sort((a, b) => a - b);
    const caudates = await ids();
    await typeQuery([['name', 'amygdala'], ['limit', '3']]);
    await runQuery();
    assert.equal((await tableRows()).length, 3);
    await page.goBack();
    await page.waitForFunction(() => document.querySelector('#opt-name').value === 'caudate');
    await page.waitForSelector('#summary:not([hidden])', { timeout: 30_000 });
    assert.equal(await page.inputValue('#opt-laterality'), 'R');
    assert.equal(await page.inputValue('#opt-limit'), '');
    assert.deepEqual(await ids(), caudates);
  });

  test('no script error on the page', () => {
    assert.deepEqual(pageErrors, []);
  });
});
