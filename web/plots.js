// Live plots on <canvas>, no library: a top-down view of every body with its trail, and x/y/z of
// one body over the last 30 s. Positions are the Station's: metres in the mocap world frame as the
// source reports it (z up for Vicon/QTM), so "top-down" shows x to the right and y up.

export const HISTORY_S = 30;   // how long the x/y/z plot looks back
export const TRAIL_S = 10;     // how long a trail in the top-down view is

const PALETTE = ['#1f6feb', '#d1242f', '#1a7f37', '#bf8700', '#8250df', '#0a7ea4', '#cf222e', '#57606a'];
const AXIS_COLORS = { x: '#d1242f', y: '#1a7f37', z: '#1f6feb' };

/** A stable colour per body name (by order of first appearance). */
export class Colors {
  constructor() { this.map = new Map(); }
  of(name) {
    if (!this.map.has(name)) this.map.set(name, PALETTE[this.map.size % PALETTE.length]);
    return this.map.get(name);
  }
}

/** Positions of every body over the last HISTORY_S seconds of daemon time (status.uptime_s). */
export class History {
  constructor() { this.bodies = new Map(); this.now = 0; }

  add(status) {
    const t = status.uptime_s;
    if (t < this.now) this.bodies.clear();  // the daemon restarted
    this.now = t;
    for (const body of status.station.bodies) {
      if (!body.p_m) continue;
      let samples = this.bodies.get(body.name);
      if (!samples) this.bodies.set(body.name, (samples = []));
      const last = samples[samples.length - 1];
      if (last && last.t === t) continue;
      samples.push({ t, p: body.p_m, tracked: body.state === 'tracking' });
      while (samples.length && samples[0].t < t - HISTORY_S) samples.shift();
    }
  }

  samples(name) { return this.bodies.get(name) || []; }
}

/** Sizes the canvas backing store to its CSS size × devicePixelRatio; returns the 2D context. */
function prepare(canvas) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(1, Math.round(canvas.clientWidth * dpr));
  const h = Math.max(1, Math.round(canvas.clientHeight * dpr));
  if (canvas.width !== w || canvas.height !== h) {
    canvas.width = w;
    canvas.height = h;
  }
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.clearRect(0, 0, canvas.clientWidth, canvas.clientHeight);
  ctx.font = '11px system-ui, sans-serif';
  return { ctx, w: canvas.clientWidth, h: canvas.clientHeight };
}

/** A "nice" grid step (1, 2 or 5 × 10^n) giving about `count` lines over `span`. */
function niceStep(span, count) {
  const raw = span / count;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const n = raw / mag;
  return (n < 1.5 ? 1 : n < 3.5 ? 2 : n < 7.5 ? 5 : 10) * mag;
}

function fmt(v, step) {
  const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  return v.toFixed(digits);
}

/** Top-down view: bodies as dots (hollow when not tracking), trails of the last TRAIL_S. */
export function drawTopDown(canvas, bodies, history, colors) {
  const { ctx, w, h } = prepare(canvas);
  const pad = 28;
  let minX = -1, maxX = 1, minY = -1, maxY = 1;  // at least 2 m × 2 m around the origin
  for (const body of bodies) {
    for (const s of history.samples(body.name)) {
      minX = Math.min(minX, s.p[0]); maxX = Math.max(maxX, s.p[0]);
      minY = Math.min(minY, s.p[1]); maxY = Math.max(maxY, s.p[1]);
    }
  }
  // Same scale on both axes, centred.
  const scale = Math.min((w - 2 * pad) / (maxX - minX), (h - 2 * pad) / (maxY - minY));
  const cx = (minX + maxX) / 2, cy = (minY + maxY) / 2;
  const X = (x) => w / 2 + (x - cx) * scale;
  const Y = (y) => h / 2 - (y - cy) * scale;

  const step = niceStep(Math.max(maxX - minX, maxY - minY), 6);
  ctx.strokeStyle = '#e3e8ee';
  ctx.fillStyle = '#6b7785';
  ctx.lineWidth = 1;
  const x0 = cx - (w / 2) / scale, x1 = cx + (w / 2) / scale;
  const y0 = cy - (h / 2) / scale, y1 = cy + (h / 2) / scale;
  for (let gx = Math.ceil(x0 / step) * step; gx <= x1; gx += step) {
    ctx.beginPath(); ctx.moveTo(X(gx), 0); ctx.lineTo(X(gx), h); ctx.stroke();
    ctx.fillText(fmt(gx, step), X(gx) + 2, h - 4);
  }
  for (let gy = Math.ceil(y0 / step) * step; gy <= y1; gy += step) {
    ctx.beginPath(); ctx.moveTo(0, Y(gy)); ctx.lineTo(w, Y(gy)); ctx.stroke();
    ctx.fillText(fmt(gy, step), 3, Y(gy) - 2);
  }
  // Origin axes.
  ctx.strokeStyle = '#9aa5b1';
  ctx.beginPath(); ctx.moveTo(X(0), Y(0)); ctx.lineTo(X(0) + 30, Y(0)); ctx.stroke();
  ctx.beginPath(); ctx.moveTo(X(0), Y(0)); ctx.lineTo(X(0), Y(0) - 30); ctx.stroke();
  ctx.fillText('x', X(0) + 33, Y(0) + 4);
  ctx.fillText('y', X(0) - 3, Y(0) - 34);
  ctx.textAlign = 'right';
  ctx.fillText('metres, mocap frame, from above', w - 6, 14);
  ctx.textAlign = 'left';

  for (const body of bodies) {
    const color = colors.of(body.name);
    const trail = history.samples(body.name).filter((s) => s.t >= history.now - TRAIL_S);
    ctx.strokeStyle = color;
    ctx.globalAlpha = 0.45;
    ctx.lineWidth = 2;
    ctx.beginPath();
    trail.forEach((s, i) => (i ? ctx.lineTo(X(s.p[0]), Y(s.p[1])) : ctx.moveTo(X(s.p[0]), Y(s.p[1]))));
    ctx.stroke();
    ctx.globalAlpha = 1;
    if (!body.p_m) continue;
    const px = X(body.p_m[0]), py = Y(body.p_m[1]);
    ctx.beginPath();
    ctx.arc(px, py, 6, 0, 2 * Math.PI);
    if (body.state === 'tracking') {
      ctx.fillStyle = color;
      ctx.fill();
    } else {
      ctx.lineWidth = 2;
      ctx.strokeStyle = '#b42318';
      ctx.stroke();
    }
    ctx.fillStyle = '#17202b';
    const label = body.state === 'tracking' ? body.name : `${body.name} (${body.state})`;
    const width = ctx.measureText(label).width;
    // Labels stay inside the canvas: left of the dot when there is no room on the right.
    ctx.fillText(label, px + 9 + width > w ? px - 9 - width : px + 9, Math.max(11, py - 7));
  }
}

/** x, y, z of one body against time over the last HISTORY_S seconds. */
export function drawXYZ(canvas, samples, now) {
  const { ctx, w, h } = prepare(canvas);
  const left = 40, right = 8, top = 18, bottom = 20;
  let lo = Infinity, hi = -Infinity;
  for (const s of samples) for (const v of s.p) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
  if (!Number.isFinite(lo)) { lo = -1; hi = 1; }
  if (hi - lo < 0.2) { const mid = (hi + lo) / 2; lo = mid - 0.1; hi = mid + 0.1; }
  const margin = (hi - lo) * 0.08;
  lo -= margin; hi += margin;
  const T = (t) => left + ((t - (now - HISTORY_S)) / HISTORY_S) * (w - left - right);
  const V = (v) => top + ((hi - v) / (hi - lo)) * (h - top - bottom);

  ctx.strokeStyle = '#e3e8ee';
  ctx.fillStyle = '#6b7785';
  ctx.lineWidth = 1;
  const step = niceStep(hi - lo, 5);
  for (let v = Math.ceil(lo / step) * step; v <= hi; v += step) {
    ctx.beginPath(); ctx.moveTo(left, V(v)); ctx.lineTo(w - right, V(v)); ctx.stroke();
    ctx.fillText(fmt(v, step), 2, V(v) + 4);
  }
  for (let s = 0; s <= HISTORY_S; s += 5) {
    const x = T(now - HISTORY_S + s);
    ctx.beginPath(); ctx.moveTo(x, top); ctx.lineTo(x, h - bottom); ctx.stroke();
    ctx.fillText(s === HISTORY_S ? 'now' : `-${HISTORY_S - s}s`, x - 10, h - 5);
  }
  ['x', 'y', 'z'].forEach((axis, i) => {
    ctx.strokeStyle = AXIS_COLORS[axis];
    ctx.lineWidth = 1.8;
    ctx.beginPath();
    let pen = false;
    for (const s of samples) {
      if (!s.tracked) { pen = false; continue; }  // gaps while not tracking
      const x = T(s.t), y = V(s.p[i]);
      if (pen) ctx.lineTo(x, y); else ctx.moveTo(x, y);
      pen = true;
    }
    ctx.stroke();
    ctx.fillStyle = AXIS_COLORS[axis];
    ctx.fillText(`${axis} m`, left + 6 + i * 36, 12);
  });
}
