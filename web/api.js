// Talking to the daemon: REST calls and the /api/events stream (docs/api.md).
//
// The stream is read with fetch() rather than EventSource because EventSource cannot send the
// Authorization header a token-protected dashboard needs.

const TOKEN_KEY = 'mocaplink.token';

/** The bearer token: from the URL fragment (#token=...), else this tab's session storage. */
export function loadToken() {
  const match = /(?:^|[#&])token=([^&]+)/.exec(location.hash);
  if (match) {
    sessionStorage.setItem(TOKEN_KEY, decodeURIComponent(match[1]));
    history.replaceState(null, '', location.pathname + location.search);  // keep it off screen
  }
  return sessionStorage.getItem(TOKEN_KEY) || '';
}

export function saveToken(token) {
  sessionStorage.setItem(TOKEN_KEY, token);
}

/** Thrown for a non-2xx answer; `field` names the request key at fault ("" if none). */
export class ApiError extends Error {
  constructor(status, message, field) {
    super(message);
    this.status = status;
    this.field = field || '';
  }
}

function headers(token, json) {
  const h = {};
  if (token) h.Authorization = `Bearer ${token}`;
  if (json) h['Content-Type'] = 'application/json';
  return h;
}

/** One JSON request. Resolves to the parsed body (null for 204), rejects with ApiError. */
export async function request(method, path, body, token) {
  const response = await fetch(path, {
    method,
    headers: headers(token, body !== undefined),
    body: body === undefined ? undefined : JSON.stringify(body),
    cache: 'no-store',
  });
  if (response.status === 204) return null;
  let parsed = null;
  try {
    parsed = await response.json();
  } catch {
    parsed = null;
  }
  if (!response.ok) {
    throw new ApiError(response.status, parsed?.error || `HTTP ${response.status}`, parsed?.field);
  }
  return parsed;
}

/**
 * Follows /api/events until stopped, calling onStatus(statusObject) for every event and
 * onState('live' | 'offline' | 'unauthorized') on changes. Reconnects after a second when the
 * stream ends. Returns a function that stops it.
 */
export function followEvents(getToken, onStatus, onState) {
  let stopped = false;
  let controller = null;

  async function runOnce() {
    controller = new AbortController();
    const response = await fetch('/api/events', {
      headers: headers(getToken(), false),
      signal: controller.signal,
      cache: 'no-store',
    });
    if (response.status === 401) {
      onState('unauthorized');
      return false;
    }
    if (!response.ok || !response.body) throw new Error(`HTTP ${response.status}`);
    const reader = response.body.pipeThrough(new TextDecoderStream()).getReader();
    let buffer = '';
    for (;;) {
      const { value, done } = await reader.read();
      if (done) break;
      buffer += value;
      let end;
      while ((end = buffer.indexOf('\n\n')) >= 0) {
        const block = buffer.slice(0, end);
        buffer = buffer.slice(end + 2);
        const data = block.split('\n').filter((l) => l.startsWith('data:'))
          .map((l) => l.slice(5).replace(/^ /, '')).join('\n');
        if (data) {
          onState('live');
          onStatus(JSON.parse(data));
        }
      }
    }
    return true;
  }

  (async () => {
    while (!stopped) {
      let retry = true;
      try {
        retry = await runOnce();
      } catch (e) {
        // Network trouble is expected (daemon restarting); anything else is a bug worth seeing.
        const network = e.name === 'AbortError' || /fetch|network/i.test(String(e.message));
        if (!network) console.error('dashboard:', e);
        retry = true;
      }
      if (stopped || !retry) return;
      onState('offline');
      await new Promise((resolve) => setTimeout(resolve, 1000));
    }
  })();

  return () => {
    stopped = true;
    controller?.abort();
  };
}
