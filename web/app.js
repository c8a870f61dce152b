// The dashboard page: the Station card, one card per vehicle (the original's Sender window),
// live plots and alerts, all from the /api/events stream; changes go out at once as PATCH/POST/
// DELETE (docs/api.md). Plain ES module, no framework, no build step.
import { ApiError, followEvents, loadToken, request, saveToken } from './api.js';
import { Colors, History, drawTopDown, drawXYZ } from './plots.js';

const $ = (selector, root = document) => root.querySelector(selector);

const state = {
  token: loadToken(),
  status: null,
  history: new History(),
  colors: new Colors(),
  cards: new Map(),   // vehicle name → card elements
  plotBody: '',       // body chosen for the x/y/z plot
  stopEvents: null,
};

// ---- formatting ---------------------------------------------------------------------------

const num = (v, digits = 1, unit = '') => (v === null || v === undefined ? '–' : `${Number(v).toFixed(digits)}${unit}`);
// "agree on tilt only", "agree on tilt and compass": what an agreement was measured against (the
// reason names what came from mocap).
const agreedOn = (ag) => {
  const c = ag.checked || [];
  if (c.length === 0) return ag.verdict;
  const list = c.length === 1 ? `${c[0]} only` : `${c.slice(0, -1).join(', ')} and ${c[c.length - 1]}`;
  return `agree on ${list}`;
};
const int = (v) => (v === null || v === undefined ? '–' : Number(v).toLocaleString('en-US'));

/** Shows `text` in a coloured pill; `role` is the element's own class, kept across updates. */
function pill(el, text, kind, role = '') {
  el.textContent = text;
  el.className = `${role} pill pill-${kind}`.trim();
}

function duration(s) {
  s = Math.floor(s);
  const h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60), sec = s % 60;
  return h ? `${h}h ${m}m` : m ? `${m}m ${sec}s` : `${sec}s`;
}

// ---- Station --------------------------------------------------------------------------------

function renderStation(station) {
  $('#st-source').textContent = station.source;
  const stateEl = $('#st-state');
  stateEl.textContent = station.connected ? 'connected' : `disconnected${station.error ? `: ${station.error}` : ''}`;
  stateEl.className = station.connected ? 'ok' : 'bad';
  $('#st-rate').textContent = `${num(station.frame_rate_hz, 1, ' Hz')}${station.nominal_rate_hz ? ` / ${num(station.nominal_rate_hz, 0)}` : ''}`;
  $('#st-latency').textContent = station.latency_ms === null ? 'not reported' : num(station.latency_ms, 2, ' ms');
  const bridge = station.bridge_latency_ms;
  $('#st-bridge-latency').textContent = bridge === null ? '–' : `${num(bridge.last, 2, ' ms')} (p99 ${num(bridge.p99, 2, ' ms')})`;
  $('#st-frames').textContent = int(station.frames);
  $('#st-dropped').textContent = int(station.dropped);
  const rejected = $('#st-rejected');
  rejected.textContent = int(station.rejected);
  rejected.className = station.rejected > 0 ? 'bad' : '';
  rejected.title = station.rejected_reason || 'packets the source dropped unread (malformed, or from another sender than configured)';
  const late = $('#st-late');
  late.textContent = int(station.late_frames_skipped);
  late.className = station.late_frames_skipped > 0 ? 'bad' : '';
  const superseded = $('#st-superseded');
  superseded.textContent = int(station.superseded_frames);
  superseded.className = station.superseded_frames > 0 ? 'bad' : '';

  const tbody = $('#bodies tbody');
  const rows = station.bodies.map((b) => {
    const tr = document.createElement('tr');
    tr.dataset.body = b.name;
    if (b.state === 'lost' || b.mirrored) tr.className = 'lost';
    const p = b.p_m || [null, null, null];
    // A mirrored rotation (left-handed matrix) is a set-up mistake no axis setting fixes: say so.
    const shown = b.mirrored ? 'MIRRORED' : b.state === 'lost' ? 'LOST' : b.state;
    if (b.mirrored) tr.title = 'the source sends a left-handed rotation (determinant -1): not a pose; no axis setting can fix it — check the handedness of the mocap system\'s frame';
    const cells = [b.name, shown, num(p[0], 3), num(p[1], 3), num(p[2], 3), int(b.rejected)];
    cells.forEach((text, i) => {
      const td = document.createElement('td');
      if (i === 0) {
        const dot = document.createElement('span');
        dot.className = 'swatch';
        dot.style.background = state.colors.of(b.name);
        td.append(dot);
      }
      td.append(text);
      if (i >= 2) td.className = 'num';
      tr.append(td);
    });
    return tr;
  });
  tbody.replaceChildren(...rows);

  // Body chooser for the x/y/z plot and the add-vehicle form's suggestions.
  const names = station.bodies.map((b) => b.name);
  const select = $('#plot-body');
  if ([...select.options].map((o) => o.value).join('\n') !== names.join('\n')) {
    select.replaceChildren(...names.map((n) => new Option(n, n)));
    $('#body-names').replaceChildren(...names.map((n) => new Option(n, n)));
  }
  if (!names.includes(state.plotBody)) state.plotBody = names[0] || '';
  select.value = state.plotBody;
}

// ---- Vehicles -------------------------------------------------------------------------------

async function patchVehicle(card, name, change) {
  card.error.textContent = '';
  try {
    const vehicle = await request('PATCH', `/api/vehicles/${encodeURIComponent(name)}`, change, state.token);
    renderVehicle(card, vehicle, true);
  } catch (e) {
    card.error.textContent = e instanceof ApiError ? e.message : String(e);
    if (e.status === 401) showTokenForm();
  }
}

function createCard(name) {
  const root = $('#vehicle-template').content.firstElementChild.cloneNode(true);
  root.dataset.vehicle = name;
  const card = {
    root,
    rate: $('.v-rate', root),
    rateOut: $('.v-rate-out', root),
    pause: $('.v-pause', root),
    messages: $('.v-messages', root),
    remove: $('.v-remove', root),
    error: $('.v-error', root),
    apply: $('.v-apply', root),
    reboot: $('.v-reboot', root),
    dragging: false,
    messageKey: '',
    vehicle: null,
  };
  card.rate.setAttribute('aria-label', `${name} send rate`);
  card.rate.addEventListener('input', () => {
    card.dragging = true;
    card.rateOut.textContent = `${card.rate.value} Hz`;
  });
  card.rate.addEventListener('change', async () => {
    await patchVehicle(card, name, { rate_hz: Number(card.rate.value) });
    card.dragging = false;
  });
  card.pause.addEventListener('click', () => patchVehicle(card, name, { paused: !card.vehicle.paused }));
  card.messages.addEventListener('change', () => {
    const ticked = [...card.messages.querySelectorAll('input:checked')].map((i) => i.value);
    patchVehicle(card, name, { messages: ticked });
  });
  // Apply writes exactly the wrong parameters this card shows, by name (the daemon refuses any
  // other); reboot is a separate, confirmed action.
  card.apply.addEventListener('click', async () => {
    const names = fixable(card.vehicle).map((i) => i.parameter);
    if (!names.length) return;
    const list = fixable(card.vehicle).map((i) => `${i.parameter} = ${i.fix}`).join('\n');
    if (!window.confirm(`Write to ${name}?\n\n${list}`)) return;
    await setupRequest(card, name, { apply: names });
  });
  card.reboot.addEventListener('click', async () => {
    if (!window.confirm(`Reboot ${name}'s autopilot now?`)) return;
    await setupRequest(card, name, { reboot: true });
  });
  // Two-step remove: the first click arms the button for 3 s.
  let disarm = null;
  card.remove.addEventListener('click', async () => {
    if (!card.remove.classList.contains('armed')) {
      card.remove.classList.add('armed');
      card.remove.textContent = 'Really remove?';
      disarm = setTimeout(() => {
        card.remove.classList.remove('armed');
        card.remove.textContent = 'Remove';
      }, 3000);
      return;
    }
    clearTimeout(disarm);
    try {
      await request('DELETE', `/api/vehicles/${encodeURIComponent(name)}`, undefined, state.token);
      root.remove();
      state.cards.delete(name);
    } catch (e) {
      card.error.textContent = e.message;
    }
  });
  $('#vehicles').append(root);
  return card;
}

/// The set-up items Apply would write: wrong, with a fix, and not a profile item.
function fixable(v) {
  return (v && v.setup ? v.setup.items : []).filter((i) => i.status === 'wrong' && i.fix !== null);
}

async function setupRequest(card, name, body) {
  card.error.textContent = '';
  try {
    const v = await request('POST', `/api/vehicles/${encodeURIComponent(name)}/setup`, body, state.token);
    renderVehicle(card, v, true);
  } catch (e) {
    card.error.textContent = e.message;
  }
}

function renderSetup(card, v) {
  const r = card.root;
  const setup = v.setup;
  const ap = v.autopilot;
  $('.v-autopilot', r).textContent = ap.name === 'unknown'
    ? 'not identified yet'
    : `${ap.name}${ap.version ? ` ${ap.version}` : ''} · rules of profile ${ap.profile_in_effect}`;
  const kind = { ready: 'ok', blocked: 'bad', 'no answer': 'warn', unsupported: 'warn', unavailable: 'warn' }[setup.state] || 'warn';
  pill($('.v-setup-state', r), setup.state, kind, 'v-setup-state');
  // Rows are kept and only their text changes, so a row the operator is reading
  // (or selecting) is not replaced by a copy on every status update.
  const tbody = $('.v-setup-items tbody', r);
  const kept = new Map([...tbody.rows].map((tr) => [tr.dataset.parameter, tr]));
  const rows = setup.items.map((i) => {
    const tr = kept.get(i.parameter) || document.createElement('tr');
    const className = `setup-item ${i.status} ${i.severity}`;
    if (tr.className !== className) tr.className = className;
    tr.dataset.parameter = i.parameter;
    const cells = [
      i.parameter,
      i.current === null ? (i.status === 'missing' ? 'no answer' : '…') : String(i.current),
      i.needed,
      i.status === 'ok' ? 'ok' : i.severity,
      i.why + (i.reboot ? ' (after a reboot)' : '') + (i.apply !== 'none' ? ` — ${i.apply}${i.apply_note ? `: ${i.apply_note}` : ''}` : ''),
    ];
    while (tr.cells.length < cells.length) tr.insertCell();
    cells.forEach((c, k) => {
      if (tr.cells[k].textContent !== c) tr.cells[k].textContent = c;
    });
    return tr;
  });
  if (rows.length !== tbody.rows.length || rows.some((tr, k) => tbody.rows[k] !== tr)) tbody.replaceChildren(...rows);
  const d = v.delay_ms;
  $('.v-delay', r).textContent = d.parameter
    ? `Delay: measured ${num(d.measured, 0, ' ms')}, recommended ${d.parameter} = ${num(d.recommended, 0, ' ms')} (now ${num(d.current, 0, ' ms')})${d.basis ? ` — ${d.basis}` : ''}`
    : '';
  const e = v.estimator;
  // Asked for and not sent: say so, rather than show nothing.
  const asked = Object.entries(v.streams || {})
    .find(([m, s]) => ['EKF_STATUS_REPORT', 'ESTIMATOR_STATUS'].includes(m) && ['refused', 'silent'].includes(s));
  $('.v-estimator', r).textContent = e
    ? `Estimator (${e.source}): ${e.problems.length ? e.problems.join(', ') : 'no problem reported'}${e.good.length ? ` · good: ${e.good.join(', ')}` : ''}`
    : (asked ? `Estimator: the vehicle sends no ${asked[0]} (asked at 1 Hz, ${asked[1]})` : '');
  $('.v-statustext', r).replaceChildren(...v.statustext.slice(-5).map((t) => {
    const li = document.createElement('li');
    li.className = `statustext ${t.severity}`;
    li.textContent = `${t.severity}: ${t.text} (${num(t.age_s, 0, ' s')} ago)`;
    return li;
  }));
  const armed = v.heartbeat && v.heartbeat.armed;
  const fixes = fixable(v);
  card.apply.disabled = armed || !fixes.length || !['ready', 'blocked'].includes(setup.state);
  card.apply.textContent = fixes.length ? `Apply ${fixes.length} fix${fixes.length > 1 ? 'es' : ''}` : 'Apply fixes';
  card.apply.title = armed ? 'the vehicle is armed: nothing is written' : '';
  card.reboot.disabled = armed || v.link_state !== 'up' || setup.state === 'unavailable';
  // A link without parameters (PX4 over uXRCE-DDS): the list is what to check over MAVLink.
  $('.v-setup-why', r).textContent = setup.note ? `${setup.note}.` : '';
  const notes = [];
  if (setup.reboot_for.length) notes.push(`Reboot the vehicle for ${setup.reboot_for.join(', ')} to take effect.`);
  if (v.origin.advice) notes.push(`Origin: ${v.origin.advice}.`);
  if (setup.last_refusal) notes.push(`Refused: ${setup.last_refusal}`);
  $('.v-setup-note', r).textContent = notes.join(' ');
}

function renderVehicle(card, v, fromPatch = false) {
  card.vehicle = v;
  const r = card.root;
  $('.v-name', r).textContent = v.name;
  const linkKind = { up: 'ok', silent: 'warn', down: 'bad' }[v.link_state] || 'warn';
  pill($('.v-link-state', r), v.link_state === 'up' ? 'link up' : `link ${v.link_state}`, linkKind, 'v-link-state');
  $('.v-body', r).textContent = v.body;
  $('.v-link', r).textContent = v.link;
  $('.v-sysid', r).textContent = v.system_id;
  $('.v-profile', r).textContent = v.profile;
  $('.v-sent', r).textContent = int(v.sent_total);
  $('.v-actual', r).textContent = v.paused ? 'paused' : num(v.send_rate_hz, 1, ' Hz');

  const hb = v.heartbeat;
  $('.v-heartbeat', r).textContent = hb
    ? `${hb.type} · ${hb.autopilot} · ${hb.armed ? 'ARMED' : 'disarmed'} · ${hb.mode} (${num(hb.age_s, 1, ' s')} ago)`
    : 'none received';
  const ts = $('.v-timesync', r);
  ts.textContent = v.timesync.state === 'synced' ? `synced, ${num(v.timesync.rtt_ms, 1, ' ms')} rtt` : v.timesync.state;
  ts.className = `v-timesync ${v.timesync.state}`;
  const clock = $('.v-clock', r);
  const c = v.clock;
  const stamps = c.pose_stamps ? ` · poses stamped at ${c.pose_stamps}` : '';
  const verdict = c.verdict === null ? 'not measured on this link' : c.verdict;
  clock.textContent = c.rate_ppm === null ? `${verdict}${stamps}` : `${verdict}, ${num(c.rate_ppm, 0, ' ppm')}${stamps}`;
  clock.title = c.text;
  clock.className = `v-clock ${c.verdict === null ? 'off' : c.verdict}`;
  const origin = $('.v-origin', r);
  origin.textContent = { not_needed: 'not needed', sending: 'not confirmed', confirmed: 'confirmed', unconfirmed: 'never confirmed (no longer sent)', withheld: 'not sent (PX4 before 1.15)' }[v.origin.state] || v.origin.state;
  origin.className = `v-origin ${v.origin.state}`;
  const ag = v.agreement;
  const box = $('.v-agreement-box', r);
  box.className = `span2 v-agreement-box ${ag.verdict}`;
  // Unknown: say why (the daemon's reason: no heartbeat, body not tracked, what it asked the
  // vehicle for and what came of it), with the offsets known so far.
  // With a verdict the reason says what was not checked (mocap compared with itself) and, for a
  // disagreement, the axis settings that fix it.
  const offsets = `tilt ${num(ag.tilt_offset_deg, 1, '°')} · yaw ${num(ag.yaw_offset_deg, 1, '°')} · position ${num(ag.position_offset_m, 3, ' m')}${ag.heading_offset_deg == null ? '' : ` · compass ${num(ag.heading_offset_deg, 1, '°')}`}`;
  $('.v-agreement', r).textContent = ag.verdict === 'unknown'
    ? `unknown: ${ag.reason || 'waiting for the vehicle\'s estimate'}${ag.yaw_offset_deg === null && ag.position_offset_m === null && ag.tilt_offset_deg == null ? '' : ` · ${offsets}`}`
    : `${ag.verdict === 'disagree' ? '⚠ DISAGREES' : agreedOn(ag)} · ${offsets}${ag.reason ? ` · ${ag.reason}` : ''}`;

  // Inputs: never overwrite what the user is doing.
  if (!card.dragging && document.activeElement !== card.rate) {
    card.rate.value = Math.round(v.rate_hz);
    card.rateOut.textContent = `${num(v.rate_hz, v.rate_hz % 1 ? 1 : 0)} Hz`;
  }
  card.pause.textContent = v.paused ? 'Resume' : 'Pause';
  card.pause.classList.toggle('secondary', !v.paused);
  card.pause.setAttribute('aria-pressed', String(v.paused));
  const offered = v.available_messages.length ? v.available_messages : v.messages;
  const key = offered.join(',');
  if (card.messageKey !== key) {
    card.messageKey = key;
    card.messages.replaceChildren(...offered.map((m) => {
      const label = document.createElement('label');
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.value = m;
      label.append(box, m);
      return label;
    }));
  }
  if (fromPatch || !card.messages.contains(document.activeElement)) {
    for (const input of card.messages.querySelectorAll('input')) input.checked = v.messages.includes(input.value);
  }
  renderGroundStations(card, v);
  renderSetup(card, v);
}

// Ground stations sharing the vehicle's link (docs/api.md "link_share", "gcs"): one line per
// endpoint, and what the link carries for whom (poses first).
function renderGroundStations(card, v) {
  const r = card.root;
  const endpoints = v.gcs || [];
  $('.v-gcs-box', r).hidden = endpoints.length === 0;
  $('.v-share-box', r).hidden = endpoints.length === 0;
  if (endpoints.length === 0) return;
  $('.v-gcs', r).textContent = endpoints.map((e) => {
    const drops = e.dropped + e.no_route + e.bad_frames;
    return `${e.url} · ${e.state} · ${e.peers} connected · ↓${int(e.frames_to_gcs)} ↑${int(e.frames_from_gcs)}` +
      (drops ? ` · ${int(drops)} dropped` : '');
  }).join('\n');
  const s = v.link_share;
  const budget = s.capacity_bytes_per_s === null ? 'budget unknown' : `${int(Math.round(s.capacity_bytes_per_s))} B/s budget`;
  $('.v-share', r).textContent = `${budget} · mocaplink ${int(Math.round(s.own_bytes_per_s))} B/s · ground stations ` +
    `${int(Math.round(s.forwarded_bytes_per_s))} B/s` + (s.forwarded_dropped ? ` · ${int(s.forwarded_dropped)} of theirs dropped` : '') +
    (s.queued_bytes ? ` · ${int(s.queued_bytes)} B waiting` : '');
}

function renderVehicles(vehicles) {
  const seen = new Set();
  for (const v of vehicles) {
    seen.add(v.name);
    const card = state.cards.get(v.name) || createCard(v.name);
    state.cards.set(v.name, card);
    renderVehicle(card, v);
  }
  for (const [name, card] of state.cards) {
    if (!seen.has(name)) {
      card.root.remove();
      state.cards.delete(name);
    }
  }
}

// ---- Alerts ---------------------------------------------------------------------------------

function renderAlerts(alerts) {
  $('#alerts').replaceChildren(...alerts.map((a) => {
    const div = document.createElement('div');
    div.className = `alert ${a.level}`;
    div.dataset.kind = a.kind;
    const b = document.createElement('b');
    b.textContent = a.kind.replaceAll('_', ' ');
    div.append(b, a.message);
    return div;
  }));
}

// ---- Plots ----------------------------------------------------------------------------------

function renderPlots() {
  const s = state.status;
  if (!s) return;
  drawTopDown($('#topdown'), s.station.bodies, state.history, state.colors);
  drawXYZ($('#xyz'), state.history.samples(state.plotBody), state.history.now);
}

// ---- Wiring ---------------------------------------------------------------------------------

/// The [ros2] side: domain, topics, subscribers matched, samples written, problems.
function renderRos2(ros2) {
  $('#st-ros2-row').hidden = ros2 === null || ros2 === undefined;
  if (!ros2) return;
  const el = $('#st-ros2');
  if (!ros2.running) {
    el.textContent = `not running: ${ros2.error}`;
    el.className = 'bad';
    return;
  }
  const subscribers = ros2.topics.reduce((n, t) => n + t.subscribers, 0);
  const problems = [];
  if (ros2.error) problems.push(ros2.error);
  if (ros2.frames_dropped > 0) problems.push(`${int(ros2.frames_dropped)} frames dropped`);
  if (ros2.write_errors > 0) problems.push(`${int(ros2.write_errors)} write errors`);
  if (ros2.unnamed.length > 0) problems.push(`no ROS name: ${ros2.unnamed.join(', ')}`);
  if (ros2.clashes.length > 0) problems.push(`name taken: ${ros2.clashes.join(', ')}`);
  el.textContent = `domain ${ros2.domain_id}, /${ros2.namespace}, ${ros2.topics.length} topics, ` +
    `${subscribers} subscribers, ${int(ros2.frames_published)} frames` +
    (problems.length ? ` — ${problems.join('; ')}` : '');
  el.className = problems.length ? 'bad' : '';
  el.title = ros2.topics.map((t) => `${t.name} (${t.type}): ${t.subscribers} subscribers, ${t.published} published`).join('\n');
}

function onStatus(status) {
  state.status = status;
  state.history.add(status);
  $('#uptime').textContent = `up ${duration(status.uptime_s)}`;
  renderStation(status.station);
  renderRos2(status.ros2);
  renderVehicles(status.vehicles);
  renderAlerts(status.alerts);
  requestAnimationFrame(renderPlots);
}

function onStreamState(s) {
  if (s === 'live') pill($('#live'), 'live', 'ok');
  else if (s === 'unauthorized') showTokenForm();
  else pill($('#live'), 'offline — retrying', 'bad');
}

function showTokenForm() {
  pill($('#live'), 'token required', 'warn');
  $('#token-form').hidden = false;
  $('main').hidden = true;
}

function start() {
  state.stopEvents?.();
  state.stopEvents = followEvents(() => state.token, onStatus, onStreamState);
}

$('#token-form').addEventListener('submit', (e) => {
  e.preventDefault();
  state.token = $('#token-input').value.trim();
  saveToken(state.token);
  $('#token-form').hidden = true;
  $('main').hidden = false;
  start();
});

$('#plot-body').addEventListener('change', (e) => {
  state.plotBody = e.target.value;
  renderPlots();
});

$('#add-vehicle').addEventListener('submit', async (e) => {
  e.preventDefault();
  const form = e.target;
  const error = $('#add-error');
  error.textContent = '';
  for (const input of form.querySelectorAll('[aria-invalid]')) input.removeAttribute('aria-invalid');
  const data = Object.fromEntries(new FormData(form));
  const spec = {
    name: data.name.trim(),
    body: data.body.trim(),
    link: data.link.trim(),
    system_id: Number(data.system_id),
    profile: data.profile,
    rate_hz: Number(data.rate_hz),
  };
  try {
    const vehicle = await request('POST', '/api/vehicles', spec, state.token);
    form.reset();
    const card = state.cards.get(vehicle.name) || createCard(vehicle.name);
    state.cards.set(vehicle.name, card);
    renderVehicle(card, vehicle);
  } catch (err) {
    error.textContent = err.message;
    const field = err.field && form.elements.namedItem(err.field);
    if (field) {
      field.setAttribute('aria-invalid', 'true');
      field.focus();
    }
  }
});

window.addEventListener('resize', () => requestAnimationFrame(renderPlots));
start();
