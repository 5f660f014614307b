// soiq's query page: loads the form from GET /soiq/v1/info, runs a query with the NDJSON answer and
// shows its rows as they stream, then the summary and the plot. The URL holds the query's arguments
// (?name=hippocampus&select=...), so a query can be shared, reloaded and gone back to.

import { ApiError, apiFetch, errorFrom, ndjsonLines, setTokenAsker } from './api.js';
import { QueryForm } from './query_form.js';
import { ResultsTable } from './results.js';

const $ = (selector) => document.querySelector(selector);

let queryForm = null;

// --- The error box: every failure in words, soiqd's own, with the field it names. ---

// The field an error is about: soiqd's "field" when it sends one, else the option its message
// starts with ("min-age 'abc': ..."), so the input can be pointed at either way.
function fieldOf(error) {
  if (error.field) return error.field;
  const first = /^([a-z][a-z-]*)(\[\d+\])?[ :]/.exec(error.message || '');
  if (first && queryForm?.options.some((o) => o.name === first[1])) return first[1] + (first[2] || '');
  return '';
}

function showError(error) {
  const box = $('#error');
  const title = document.createElement('strong');
  title.textContent = error.context || (error.status ? 'soiqd refused the request' : 'The request failed');
  const message = document.createElement('p');
  message.className = 'error-message';
  message.textContent =
    error instanceof TypeError ? `soiqd could not be reached (${error.message}); is it running?` : error.message;
  box.replaceChildren(title, message);
  const code = [error.code, error.status ? `HTTP ${error.status}` : ''].filter(Boolean).join(', ');
  const field = fieldOf(error);
  if (field || code) {
    const detail = document.createElement('p');
    detail.className = 'error-detail';
    detail.textContent = [field ? `Field: ${field}` : '', code].filter(Boolean).join(' · ');
    detail.dataset.field = field;
    box.append(detail);
  }
  const input = field && queryForm ? queryForm.markInvalid(field) : null;
  if (input) {
    const actions = document.createElement('p');
    actions.className = 'error-actions';
    // soiqd's "did you mean" as one click: the misspelt name replaced in its input, the query rerun.
    const unknown = /unknown feature '([^']+)'/.exec(error.message)?.[1];
    const suggested = /did you mean '([^']+)'\?/.exec(error.message)?.[1];
    if (unknown && suggested && input.value.includes(unknown)) {
      const use = document.createElement('button');
      use.type = 'button';
      use.className = 'suggestion';
      use.textContent = `Use ${suggested}`;
      use.addEventListener('click', () => {
        input.value = input.value.replace(unknown, suggested);
        input.form.requestSubmit();
      });
      actions.append(use);
    }
    const go = document.createElement('button');
    go.type = 'button';
    go.className = 'link';
    go.textContent = `Go to ${input.name}`;
    go.addEventListener('click', () => input.focus());
    actions.append(go);
    box.append(actions);
  }
  box.hidden = false;
}

function clearError() {
  $('#error').hidden = true;
  $('#error').replaceChildren();
  queryForm?.markInvalid('');
}

// --- The token, asked in a dialog when soiqd says 401 (api.js decides when). ---

function askToken(message) {
  const dialog = $('#token-dialog');
  const input = $('#token-input');
  $('#token-message').textContent = message;
  // A refused token is said in the error box too, where it stays after the dialog closes.
  if (/refused/.test(message)) {
    const error = new ApiError(message, { status: 401, code: 'UNAUTHENTICATED' });
    error.context = 'Wrong token';
    showError(error);
  }
  input.value = '';
  return new Promise((resolve) => {
    dialog.addEventListener(
      'close',
      () => resolve(dialog.returnValue === 'ok' && input.value.trim() ? input.value.trim() : null),
      { once: true },
    );
    dialog.returnValue = '';
    dialog.showModal();
    input.focus();
  });
}

// --- Running a query. ---

let running = null;  // the AbortController of the query in progress

function setStatus(text) {
  $('#status').textContent = text;
}

const ms = (v) => `${Number(v).toFixed(1)} ms`;

// The summary in two parts: soiqd's counts, and the times (soiqd's stages, then this page's own:
// the first row and the whole answer, from the click).
function summaryParts(s, firstRowMs, browserMs) {
  const counts = [
    `${s.stage1_candidates} candidates`,
    `${s.computed} computed`,
    `${s.cache_hits} cache hits`,
    `${s.matched} matched`,
    `${s.returned} returned`,
  ];
  if (s.failed) counts.push(`${s.failed} failed`);
  const skipped = (s.skipped || []).reduce((n, k) => n + (k.count || 0), 0);
  if (skipped) counts.push(`${skipped} skipped (${s.skipped.map((k) => `${k.count}: ${k.reason}`).join('; ')})`);
  const first = firstRowMs === null ? '' : `first row ${ms(firstRowMs)}, `;
  const times = `stage 1 ${ms(s.stage1_ms)}, stage 2 ${ms(s.stage2_ms)}, total ${ms(s.total_ms)} · here: ${first}all ${ms(browserMs)}`;
  return [counts.join(', '), times].map((text) => {
    const span = document.createElement('span');
    span.textContent = text;
    return span;
  });
}

async function runQuery(args, table) {
  running?.abort();
  const controller = new AbortController();
  running = controller;
  const { signal } = controller;
  clearError();
  table.reset();
  $('#summary').hidden = true;
  $('#plot').hidden = true;
  $('#stop').disabled = false;
  setStatus('Running…');
  const started = performance.now();
  let firstRowMs = null;
  let summary = null;
  try {
    const response = await apiFetch(`soiq/v1/query?${args}`, { accept: 'application/x-ndjson', signal });
    if (!response.ok) {
      const error = await errorFrom(response);
      error.context = 'soiqd refused the query';
      throw error;
    }
    const onRow = (row) => {
      table.addRow(row);
      if (firstRowMs === null) firstRowMs = performance.now() - started;
      setStatus(`${table.rowCount} row${table.rowCount === 1 ? '' : 's'} so far…`);
    };
    if (/application\/x-ndjson/.test(response.headers.get('Content-Type') || '')) {
      for await (const line of ndjsonLines(response)) {
        if (line.columns) table.setColumns(line.columns);
        else if (line.row) onRow(line.row);
        else if (line.summary) summary = line.summary;
        else if (line.error) {
          const error = new ApiError(line.error.message, line.error);
          error.context = `The query failed after ${table.rowCount} row${table.rowCount === 1 ? '' : 's'}`;
          throw error;
        }
      }
    } else {
      // A soiqd that answers one JSON document (no streaming): the same rows, all at once.
      const whole = await response.json();
      table.setColumns(whole.columns);
      whole.rows.forEach(onRow);
      summary = whole.summary;
    }
    if (!summary)
      throw new ApiError("soiqd's answer ended before its summary: the connection was cut or soiqd stopped", {
        code: 'UNAVAILABLE',
      });
    const summaryBox = $('#summary');
    summaryBox.replaceChildren(...summaryParts(summary, firstRowMs, performance.now() - started));
    summaryBox.dataset.firstRowMs = firstRowMs ?? '';
    summaryBox.hidden = false;
    setStatus(table.rowCount ? `${table.rowCount} row${table.rowCount === 1 ? '' : 's'}` : 'No structure matched.');
    if (args.getAll('select').length) await showPlot(args, signal, queryForm.features);
  } catch (error) {
    if (signal.aborted) {
      setStatus(`Stopped after ${table.rowCount} rows.`);
      return;
    }
    setStatus(summary ? 'Done, with an error.' : 'The query failed.');
    showError(error);
  } finally {
    if (running === controller) {
      running = null;
      $('#stop').disabled = true;
    }
  }
}

// The plot of the query's first selected feature (histogram) or first two (scatter), as soiqd
// draws it; shown as an <img> of the SVG, so its styles and ids cannot touch the page's.
async function showPlot(args, signal, features) {
  const figure = $('#plot');
  const selected = args.getAll('select');
  // soiqd plots features of one value per structure; a centroid or a box is said, not asked for.
  const components = (expression) => {
    const name = /^(?:asym\()?\s*([A-Za-z][A-Za-z0-9_]*)/.exec(expression)?.[1];
    return features.find((f) => f.name === name)?.components ?? 1;
  };
  const several = selected.slice(0, 2).find((e) => components(e) > 1);
  if (several) {
    $('#plot-caption').textContent = 'No plot';
    const note = document.createElement('p');
    note.className = 'plot-note';
    note.textContent = `${several} has ${components(several)} values per structure; soiqd plots features of one value (select one first for a histogram, two for a scatter).`;
    figure.querySelector('.plot-body').replaceChildren(note);
    figure.hidden = false;
    return;
  }
  try {
    const response = await apiFetch(`soiq/v1/query/plot?${args}`, { accept: 'image/svg+xml', signal });
    if (!response.ok) {
      const error = await errorFrom(response);
      error.context = 'soiqd could not draw the plot';
      throw error;
    }
    const url = URL.createObjectURL(await response.blob());
    const img = new Image();
    img.alt =
      selected.length > 1 ? `scatter plot of ${selected[1]} against ${selected[0]}` : `histogram of ${selected[0]}`;
    await new Promise((resolve, reject) => {
      img.onload = resolve;
      img.onerror = () => reject(new ApiError('the plot soiqd sent is not an image the browser can show'));
      img.src = url;
    });
    $('#plot-caption').textContent = img.alt[0].toUpperCase() + img.alt.slice(1);
    figure.querySelector('.plot-body').replaceChildren(img);
    figure.hidden = false;
  } catch (error) {
    if (signal.aborted) return;
    error.context ||= 'soiqd could not draw the plot';
    showError(error);
  }
}

// --- Start: the form from soiqd's table, then the query the URL holds, if any. ---

async function start() {
  setTokenAsker(askToken);
  let info;
  try {
    const response = await apiFetch('soiq/v1/info');
    if (!response.ok) throw await errorFrom(response);
    info = await response.json();
  } catch (error) {
    error.context = "soiqd's query options could not be loaded";
    $('#form-loading').textContent = 'The form needs soiqd’s query options; reload the page to try again.';
    showError(error);
    return;
  }
  clearError();
  $('#server-version').textContent = `soiqd ${info.version}`;
  $('#form-loading').remove();
  const form = $('#query-form');
  queryForm = new QueryForm(form, info);
  const table = new ResultsTable($('#results'), {
    viewerUrl: info.viewer_url || '',
    features: info.features,
    onError: showError,
  });
  const fromUrl = () => {
    const args = new URLSearchParams(location.search);
    const unknown = queryForm.fill(args);
    if (unknown.length)
      showError(
        new ApiError(`The link has arguments soiqd's query does not know: ${unknown.join(', ')}; they were left out.`),
      );
    if ([...args.keys()].some((k) => !unknown.includes(k))) {
      runQuery(queryForm.args(), table);
    } else {
      // Back to the bare page: no query, so no rows of an earlier one either.
      running?.abort();
      table.reset();
      $('#summary').hidden = true;
      $('#plot').hidden = true;
      setStatus('Fill in the form and run a query.');
    }
  };
  form.addEventListener('submit', (event) => {
    event.preventDefault();
    const args = queryForm.args();
    const search = args.toString() ? `?${args}` : location.pathname;
    if (`?${args}` !== location.search) history.pushState(null, '', search);
    runQuery(args, table);
  });
  $('#stop').addEventListener('click', () => running?.abort());
  $('#clear').addEventListener('click', () => {
    queryForm.clear();
    queryForm.refreshFeatureNames();
  });
  window.addEventListener('popstate', fromUrl);
  $('#run').disabled = false;
  fromUrl();
}

start();
