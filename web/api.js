// Talking to soiqd's /soiq/v1: the bearer token (asked once, when soiqd first answers 401, and kept
// for the tab in sessionStorage), soiqd's JSON errors turned into ApiError with their words, and a
// query's NDJSON answer read line by line as it streams.

const TOKEN_KEY = 'soiq.token';

// An error to show the user: soiqd's own message, and the field it names when it names one.
export class ApiError extends Error {
  constructor(message, { status = 0, code = '', field = '', reason = '' } = {}) {
    super(message);
    this.name = 'ApiError';
    this.status = status;
    this.code = code;
    this.field = field;
    this.reason = reason;
  }
}

// The ApiError of a failed response: soiqd's {"error": {...}} when the body is that, else the
// HTTP status and whatever text came (a proxy's page, say), so no failure is ever wordless.
export async function errorFrom(response) {
  const text = await response.text().catch(() => '');
  let error = null;
  try {
    error = JSON.parse(text).error;
  } catch {
    // Not JSON: the text itself is the best message there is.
  }
  if (error && typeof error.message === 'string')
    return new ApiError(error.message, {
      status: response.status,
      code: error.code || '',
      field: error.field || '',
      reason: error.reason || '',
    });
  const detail = text.trim().slice(0, 300);
  return new ApiError(`HTTP ${response.status} ${response.statusText}${detail ? `: ${detail}` : ''}`, {
    status: response.status,
  });
}

// The page supplies how to ask: (message) => Promise<string|null>, null when the user declines.
let askForToken = async () => null;
export function setTokenAsker(ask) {
  askForToken = ask;
}

// One prompt at a time: the thumbnails of a page may all get 401 at once, and the user should see
// one question, not twelve.
let pendingPrompt = null;
function promptOnce(message) {
  if (!pendingPrompt) pendingPrompt = askForToken(message).finally(() => (pendingPrompt = null));
  return pendingPrompt;
}

export function currentToken() {
  return sessionStorage.getItem(TOKEN_KEY) || '';
}

// fetch() with the token; on 401 asks for a token and tries again, until soiqd accepts one or the
// user cancels (then an ApiError saying so). Other statuses are returned as they are.
export async function apiFetch(path, { accept = 'application/json', signal } = {}) {
  for (;;) {
    const token = currentToken();
    const headers = { Accept: accept };
    if (token) headers.Authorization = `Bearer ${token}`;
    const response = await fetch(path, { headers, signal, cache: 'no-store' });
    if (response.status !== 401) return response;
    const refused = await errorFrom(response);
    // Another request may have been given a new token while this one was in flight: use that.
    if (currentToken() !== token && currentToken()) continue;
    // A refused token is forgotten, so a reload asks again rather than failing the same way.
    if (token) sessionStorage.removeItem(TOKEN_KEY);
    const message = token
      ? `soiqd refused the token: ${refused.message}. Check it against soiqd's --token-file.`
      : `soiqd asks for a bearer token: ${refused.message}.`;
    const given = await promptOnce(message);
    if (given === null || given === undefined) {
      if (currentToken()) continue;  // a concurrent prompt got one
      throw new ApiError(`${message} No token was given, so the request was not sent again.`, {
        status: 401,
        code: 'UNAUTHENTICATED',
      });
    }
    sessionStorage.setItem(TOKEN_KEY, given.trim());
  }
}

// The parsed JSON lines of an NDJSON response, each yielded as soon as its newline arrives.
export async function* ndjsonLines(response) {
  const reader = response.body.pipeThrough(new TextDecoderStream()).getReader();
  let buffer = '';
  const parse = (line) => {
    try {
      return JSON.parse(line);
    } catch {
      throw new ApiError(`soiqd sent a line that is not JSON: ${line.slice(0, 200)}`);
    }
  };
  try {
    for (;;) {
      const { value, done } = await reader.read();
      if (done) break;
      buffer += value;
      let newline;
      while ((newline = buffer.indexOf('\n')) >= 0) {
        const line = buffer.slice(0, newline).trim();
        buffer = buffer.slice(newline + 1);
        if (line) yield parse(line);
      }
    }
    if (buffer.trim()) yield parse(buffer.trim());
  } finally {
    reader.releaseLock();
  }
}

// The file name a download response says (Content-Disposition: attachment; filename="x.nii.gz").
export function fileNameOf(response, fallback) {
  const disposition = response.headers.get('Content-Disposition') || '';
  const star = /filename\*\s*=\s*UTF-8''([^;]+)/i.exec(disposition);
  if (star) return decodeURIComponent(star[1]);
  const plain = /filename\s*=\s*"?([^";]+)"?/i.exec(disposition);
  return plain ? plain[1] : fallback;
}
