#!/usr/bin/env node
// mocaplink's message_target (libs/mavlink routing.hpp) against node-mavlink 2.3.0's message tables
// (mavlink-mappings), for every message of its minimal, standard, common and ardupilotmega dialects:
//   A. MAVLink 2: node-mavlink serialises the message with random values (targets 0 often, so its
//      truncation removes target bytes); we must read back the target_system/target_component it
//      was given (component 0 where there is none), or no target where the message has no
//      target_system field;
//   B. payloads cut at a random length (bytes past it read 0): the expectation from node-mavlink's
//      field offsets;
//   C. MAVLink 1 (ids < 256): the payload cut to the base fields (node-mavlink's own V1 serialiser
//      writes the extensions too, so it is not used): targets that are extension fields are absent;
//   D. ids no message of those dialects has: no target.
// Usage (CTest, repository root as working directory): node node_mavlink_routing.cjs ROUTE_PROBE
'use strict';

const { execFileSync } = require('node:child_process');
const mavlink = require('node-mavlink');
const { makeChecker, makeRandom, INT_RANGES } = require('./support.cjs');

const probe = process.argv[2];
if (!probe) throw new Error('usage: node_mavlink_routing.cjs PATH_TO_ROUTE_PROBE');
const DIALECTS = ['minimal', 'standard', 'common', 'ardupilotmega'];
const SAMPLES = 12;

const { check, finish } = makeChecker();
const rand = makeRandom(0x7007e5);
const randInt = (lo, hi) => lo + Math.floor(rand() * (hi - lo + 1));

// A random element of `type`, zero half of the time (so that truncation reaches the targets).
function randomElement(type) {
  const zero = rand() < 0.5;
  if (type === 'float' || type === 'double') return zero ? 0 : Math.fround(rand() * 2000 - 1000);
  if (type === 'uint64_t') return zero ? 0n : BigInt(randInt(1, 2 ** 31)) << 20n;
  if (type === 'int64_t') return zero ? 0n : BigInt(randInt(-(2 ** 31), 2 ** 31)) << 20n;
  if (type === 'char') return zero ? '' : String.fromCharCode(randInt(32, 126));
  const [lo, hi] = INT_RANGES[type];
  return zero ? 0 : randInt(lo, hi);
}

function randomMessage(clazz) {
  const msg = new clazz();
  for (const f of clazz.FIELDS) {
    if (f.type === 'char[]') {
      msg[f.name] = Array.from({ length: rand() < 0.5 ? 0 : randInt(0, f.length) },
        () => String.fromCharCode(randInt(32, 126))).join('');
    } else if (f.type.endsWith('[]')) {
      msg[f.name] = Array.from({ length: f.length }, () => randomElement(f.type.slice(0, -2)));
    } else {
      msg[f.name] = randomElement(f.type);
    }
  }
  return msg;
}

const targetFields = (clazz) => ({
  system: clazz.FIELDS.find((f) => f.source === 'target_system'),
  component: clazz.FIELDS.find((f) => f.source === 'target_component'),
});

// What message_target must answer, from node-mavlink's definition and the values it was given;
// `present(field)` says whether the field's byte is in the payload (else it reads 0).
function expected(clazz, msg, present) {
  const { system, component } = targetFields(clazz);
  if (!system) return '-';
  const value = (f) => (f && present(f) ? msg[f.name] : 0);
  return `${value(system)} ${value(component)}`;
}

const lines = [];
const wants = [];
function ask(version, msgid, payload, want, what) {
  lines.push(`${version} ${msgid} ${payload.toString('hex')}`);
  wants.push({ want, what });
}

const known = new Set();
let addressed = 0;
for (const dialect of DIALECTS) {
  for (const clazz of Object.values(mavlink[dialect].REGISTRY)) {
    known.add(clazz.MSG_ID);
    const { system } = targetFields(clazz);
    if (system) addressed++;
    for (let i = 0; i < SAMPLES; i++) {
      const msg = randomMessage(clazz);
      const { system: ts, component: tc } = targetFields(clazz);
      if (ts && rand() < 0.3) msg[ts.name] = 0;
      if (tc && rand() < 0.3) msg[tc.name] = 0;
      const name = `${dialect}.${clazz.MSG_NAME}#${i}`;
      // A: node-mavlink's MAVLink 2 frame, truncated by node-mavlink.
      const frame = new mavlink.MavLinkProtocolV2(1, 1).serialize(msg, i);
      const payload = frame.subarray(10, 10 + frame[1]);
      ask(2, clazz.MSG_ID, payload, expected(clazz, msg, () => true), `${name} v2 len ${payload.length}`);
      // B: the untruncated payload (truncation removed only zeros) cut anywhere.
      const full = Buffer.concat([payload, Buffer.alloc(clazz.PAYLOAD_LENGTH - payload.length)]);
      const cut = randInt(0, full.length);
      ask(2, clazz.MSG_ID, full.subarray(0, cut), expected(clazz, msg, (f) => f.offset < cut),
        `${name} v2 cut at ${cut}`);
      // C: MAVLink 1: the base fields only.
      if (clazz.MSG_ID < 256) {
        const base = clazz.FIELDS.filter((f) => !f.extension)
          .reduce((n, f) => n + f.size * (f.type.endsWith('[]') ? f.length : 1), 0);
        const v1 = full.subarray(0, base);
        const want = ts && ts.extension ? '-' : expected(clazz, msg, (f) => !f.extension);
        ask(1, clazz.MSG_ID, v1, want, `${name} v1 len ${base}`);
      }
    }
  }
}
// D: ids no message of these dialects has, with payloads of every length.
for (let i = 0; i < 500; i++) {
  const id = i < 256 ? i : randInt(256, 0xffffff);
  if (known.has(id)) continue;
  const payload = Buffer.from(Array.from({ length: randInt(0, 255) }, () => randInt(0, 255)));
  ask(2, id, payload, '-', `unknown id ${id}`);
  if (id < 256) ask(1, id, payload, '-', `unknown id ${id} v1`);
}

// The Windows build (under Wine) writes its text lines with CR LF.
const out = execFileSync(probe, { input: lines.join('\n') + '\n', encoding: 'utf8', maxBuffer: 64 << 20 })
  .split(/\r?\n/).slice(0, -1);
check(out.length === lines.length, `route_probe answered ${out.length} of ${lines.length} lines`);
out.forEach((got, i) => check(got === wants[i].want,
  `${wants[i].what}: want ${wants[i].want}, got ${got} (${lines[i]})`));

finish(`node-mavlink routing (${known.size} messages, ${addressed} with target_system)`);
