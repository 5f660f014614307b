// The results table: rows appended as soiqd streams them (arrival order until a heading is
// clicked), each with its thumbnail (fetched with the token, a few at a time, when the row comes
// into view), its downloads and, when soiqd has a viewer configured, a link to it.

import { apiFetch, errorFrom, fileNameOf } from './api.js';

// The identity columns soiqd sends before the features (GET /soiq/v1/query "columns").
const LABELS = { id: 'id', patient_id: 'patient', study_uid: 'study', name: 'structure', laterality: 'side' };
const THUMBNAIL_CSS_PX = 64;
// Six at a time: a browser's own limit of connections per host, so thumbnails never queue behind
// each other inside the browser while the query's stream holds a connection too.
const THUMBNAIL_CONCURRENCY = 6;
const DOWNLOADS = [
  ['seg', 'SEG', 'the structure as DICOM SEG (structures imported from DICOM)'],
  ['mask', 'mask', 'the voxel mask as gzipped NIfTI'],
  ['surface', 'STL', 'the stored surface as binary STL'],
];

// A number as `soiq query` prints it (%.10g): what the CLI and the page show is the same text.
export function formatValue(value) {
  if (value === null || value === undefined) return '—';
  if (Array.isArray(value)) return value.map(formatValue).join(', ');
  if (typeof value === 'number') return Number.isInteger(value) ? String(value) : String(Number(value.toPrecision(10)));
  return String(value);
}

// At most `limit` jobs running; the rest wait in order. clear() drops the waiting ones.
class LimitedQueue {
  constructor(limit) {
    this.limit = limit;
    this.running = 0;
    this.waiting = [];
  }
  push(job) {
    this.waiting.push(job);
    this.#next();
  }
  clear() {
    this.waiting = [];
  }
  #next() {
    while (this.running < this.limit && this.waiting.length) {
      const job = this.waiting.shift();
      this.running++;
      job().finally(() => {
        this.running--;
        this.#next();
      });
    }
  }
}

export class ResultsTable {
  // onError(error): how the page shows a failure (a download soiqd refused, say).
  constructor(table, { viewerUrl = '', features = [], onError }) {
    this.table = table;
    this.viewerUrl = viewerUrl;
    this.featureInfo = new Map(features.map((f) => [f.name, f]));
    this.onError = onError;
    this.queue = new LimitedQueue(THUMBNAIL_CONCURRENCY);
    this.observer = new IntersectionObserver((entries) => this.#visible(entries), { rootMargin: '200px' });
    this.objectUrls = [];
    this.reset();
  }

  // Empties the table for a new query: pending thumbnails dropped, their blob URLs freed.
  reset() {
    this.controller?.abort();
    this.controller = new AbortController();
    this.queue.clear();
    this.observer.disconnect();
    for (const url of this.objectUrls) URL.revokeObjectURL(url);
    this.objectUrls = [];
    this.columns = [];
    this.rows = [];
    this.sort = null;
    this.table.tHead.replaceChildren();
    this.table.tBodies[0].replaceChildren();
    this.table.hidden = true;
  }

  get rowCount() {
    return this.rows.length;
  }

  setColumns(columns) {
    this.columns = columns;
    const tr = document.createElement('tr');
    const th = (text, extra = {}) => {
      const cell = document.createElement('th');
      cell.scope = 'col';
      cell.textContent = text;
      Object.assign(cell.dataset, extra);
      tr.append(cell);
      return cell;
    };
    th('image', { static: '' }).className = 'col-thumb';
    for (const column of columns) {
      const cell = th('');
      cell.dataset.column = column;
      cell.className = column in LABELS ? `col-${column}` : 'col-feature';
      // A button inside the heading: sortable by keyboard as well as by click.
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'sort';
      button.textContent = LABELS[column] || column;
      button.title = this.#describe(column);
      button.addEventListener('click', () => this.#sortBy(column));
      cell.append(button);
    }
    th('files', { static: '' }).className = 'col-files';
    this.table.tHead.replaceChildren(tr);
    this.table.hidden = false;
  }

  // The tooltip of a feature column: the catalogue's summary and unit ("mean[inside,MR]" is "mean").
  #describe(column) {
    if (column in LABELS) return `sort by ${LABELS[column]}`;
    const name = /^(?:asym\()?([A-Za-z0-9_]+)/.exec(column)?.[1];
    const f = this.featureInfo.get(name);
    const about = f ? `${f.summary}${f.unit ? ` [${f.unit}]` : ''}` : column;
    return `${column}: ${column.startsWith('asym(') ? `asymmetry of ${about}` : about}. Click to sort.`;
  }

  addRow(row) {
    const record = { row, arrival: this.rows.length, tr: this.#render(row) };
    this.rows.push(record);
    const body = this.table.tBodies[0];
    if (!this.sort) body.append(record.tr);
    else this.#place(record);
    this.observer.observe(record.tr);
  }

  #render(row) {
    const tr = document.createElement('tr');
    tr.dataset.id = row.id;
    const thumbCell = document.createElement('td');
    thumbCell.className = 'col-thumb';
    const img = document.createElement('img');
    img.className = 'thumb';
    img.alt = `${row.name || 'structure'}${row.laterality ? ` (${row.laterality})` : ''} of ${row.patient_id} over its image slice`;
    img.width = THUMBNAIL_CSS_PX;
    img.height = THUMBNAIL_CSS_PX;
    img.dataset.state = 'waiting';
    thumbCell.append(img);
    tr.append(thumbCell);
    for (const column of this.columns) {
      const td = document.createElement('td');
      const value = row[column];
      td.dataset.column = column;
      td.textContent = formatValue(value);
      if (typeof value === 'number' || value === null) td.className = 'num';
      if (Array.isArray(value)) td.className = 'num vector';
      if (value === null) td.title = 'no value (see the summary for why)';
      if (column === 'study_uid') {
        td.className = 'uid';
        td.title = value;
      }
      tr.append(td);
    }
    tr.append(this.#files(row));
    return tr;
  }

  #files(row) {
    const td = document.createElement('td');
    td.className = 'col-files';
    const buttons = document.createElement('div');
    buttons.className = 'files';
    td.append(buttons);
    for (const [what, label, title] of DOWNLOADS) {
      const button = document.createElement('button');
      button.type = 'button';
      button.className = 'file';
      button.dataset.download = what;
      button.textContent = label;
      button.title = `download ${title}`;
      button.setAttribute('aria-label', `download structure ${row.id} ${label}`);
      button.addEventListener('click', () => this.#download(row.id, what, button));
      buttons.append(button);
    }
    if (this.viewerUrl && row.study_uid) {
      const a = document.createElement('a');
      a.className = 'viewer';
      // {seg_series}: the structure's SEG, which a viewer such as OHIF opens over its images.
      a.href = this.viewerUrl
        .replaceAll('{study}', encodeURIComponent(row.study_uid))
        .replaceAll('{seg_series}', encodeURIComponent(row.seg_series_uid || ''));
      a.target = '_blank';
      a.rel = 'noopener';
      a.textContent = 'open in viewer ↗';
      a.title = `study ${row.study_uid} in the viewer (a new tab)`;
      td.append(a);
    }
    return td;
  }

  // A download with the token: fetched, then handed to the browser under soiqd's file name.
  async #download(id, what, button) {
    button.disabled = true;
    button.classList.add('busy');
    try {
      const response = await apiFetch(`soiq/v1/structures/${encodeURIComponent(id)}/${what}`, { accept: '*/*' });
      if (!response.ok) {
        const error = await errorFrom(response);
        error.context = `Structure ${id}'s ${what} could not be downloaded`;
        throw error;
      }
      const blob = await response.blob();
      const url = URL.createObjectURL(blob);
      const a = document.createElement('a');
      a.href = url;
      a.download = fileNameOf(response, `structure-${id}-${what}`);
      document.body.append(a);
      a.click();
      a.remove();
      // The browser has started the download by now; the URL is freed a little later.
      setTimeout(() => URL.revokeObjectURL(url), 10_000);
    } catch (error) {
      error.context ||= `Structure ${id}'s ${what} could not be downloaded`;
      this.onError(error);
    } finally {
      button.disabled = false;
      button.classList.remove('busy');
    }
  }

  #visible(entries) {
    for (const entry of entries) {
      if (!entry.isIntersecting) continue;
      this.observer.unobserve(entry.target);
      const img = entry.target.querySelector('img.thumb');
      const id = entry.target.dataset.id;
      const signal = this.controller.signal;
      img.dataset.state = 'queued';
      this.queue.push(() => this.#loadThumbnail(img, id, signal));
    }
  }

  async #loadThumbnail(img, id, signal) {
    if (signal.aborted) return;
    img.dataset.state = 'loading';
    // Drawn for the screen's pixels, so the slice stays sharp on a high-density display.
    const px = Math.round(THUMBNAIL_CSS_PX * Math.min(window.devicePixelRatio || 1, 3));
    try {
      const response = await apiFetch(`soiq/v1/structures/${encodeURIComponent(id)}/thumbnail?viewport=${px},${px}`, {
        accept: 'image/*',
        signal,
      });
      if (!response.ok) throw await errorFrom(response);
      const url = URL.createObjectURL(await response.blob());
      this.objectUrls.push(url);
      await new Promise((resolve) => {
        img.onload = img.onerror = resolve;
        img.src = url;
      });
      img.dataset.state = img.naturalWidth > 0 ? 'loaded' : 'failed';
    } catch (error) {
      if (signal.aborted) return;
      // A missing thumbnail is not worth an alert; the cell says so and its tooltip says why.
      img.dataset.state = 'failed';
      img.title = `no thumbnail: ${error.message}`;
      img.alt = 'no thumbnail';
    }
  }

  // Click: ascending, again: descending, a third time: back to arrival order.
  #sortBy(column) {
    if (!this.sort || this.sort.column !== column) this.sort = { column, direction: 1 };
    else if (this.sort.direction === 1) this.sort = { column, direction: -1 };
    else this.sort = null;
    for (const th of this.table.tHead.querySelectorAll('th[data-column]')) {
      const sorted = this.sort && th.dataset.column === this.sort.column;
      if (sorted) th.setAttribute('aria-sort', this.sort.direction === 1 ? 'ascending' : 'descending');
      else th.removeAttribute('aria-sort');
    }
    const ordered = [...this.rows].sort((a, b) => this.#compare(a, b));
    this.table.tBodies[0].append(...ordered.map((r) => r.tr));
  }

  // Numbers by value, text by locale; no value sorts last either way; ties keep arrival order.
  #compare(a, b) {
    if (!this.sort) return a.arrival - b.arrival;
    const { column, direction } = this.sort;
    const key = (r) => (Array.isArray(r.row[column]) ? r.row[column][0] : r.row[column]);
    const x = key(a);
    const y = key(b);
    const xNone = x === null || x === undefined;
    const yNone = y === null || y === undefined;
    if (xNone || yNone) return xNone === yNone ? a.arrival - b.arrival : xNone ? 1 : -1;
    const order = typeof x === 'number' && typeof y === 'number' ? x - y : String(x).localeCompare(String(y), undefined, { numeric: true });
    return order * direction || a.arrival - b.arrival;
  }

  // A row arriving while the table is sorted goes before the first row the sort puts after it.
  #place(record) {
    const later = this.rows.filter((r) => r !== record && this.#compare(record, r) < 0);
    const body = this.table.tBodies[0];
    const before = [...body.children].find((tr) => later.some((r) => r.tr === tr));
    body.insertBefore(record.tr, before || null);
  }
}
