#!/usr/bin/env node
// mocaplink's MAVLink codec against node-mavlink 2.3.0 (an independent implementation):
//   A. frames we encode (`mocaplink mavlink encode`) are accepted by node-mavlink's splitter (CRC,
//      crc_extra) and decode to the values we put in, for every message and random values;
//   B. frames node-mavlink encodes decode (`mocaplink mavlink decode`) to the values it was given;
//   C. node-mavlink's signature check accepts our signed frames, and ours accepts its.
// Not used as an oracle for its documented deviations (mavlink-wire.md §9): all-zero payload
// truncation, the signed flag of sign(), per-frame timestamps, replay, unknown incompat flags.
// Usage (CTest, repository root as working directory): node node_mavlink_conformance.cjs MOCAPLINK
'use strict';

const { execFileSync } = require('node:child_process');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');
const { Readable } = require('node:stream');
const mavlink = require('node-mavlink');
const { makeChecker, makeRandom, INT_RANGES } = require('./support.cjs');

const bin = process.argv[2];
if (!bin) throw new Error('usage: node_mavlink_conformance.cjs PATH_TO_MOCAPLINK');
// AUTOPILOT_VERSION is in node-mavlink's `standard` dialect, EKF_STATUS_REPORT in `ardupilotmega`
// (message ids are unique across dialects, so the merge replaces nothing).
const REGISTRY = {
  ...mavlink.minimal.REGISTRY, ...mavlink.standard.REGISTRY, ...mavlink.common.REGISTRY,
  ...mavlink.ardupilotmega.REGISTRY,
};
const golden = JSON.parse(fs.readFileSync('tests/libs/mavlink/data/golden-vectors.json', 'utf8'));
const defs = JSON.parse(fs.readFileSync('libs/mavlink/definitions/messages.json', 'utf8')).messages;
const key = Buffer.from(golden.key_hex, 'hex');
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'mocaplink-conf-'));
const SAMPLES = 25;

const { check, finish } = makeChecker();
const rand = makeRandom(0x5eed1234);
const pick = (a) => a[Math.floor(rand() * a.length)];

// A random value for one element: { node: value for node-mavlink, json: value for our JSON }.
function randomElement(type) {
  const zero = rand() < 0.3;
  if (type === 'float') {
    const v = zero ? 0 : pick([NaN, -0, Infinity, -Infinity, 3.4028234663852886e38, Math.fround(1e-45),
      Math.fround(rand() * 2000 - 1000), Math.fround(rand() * 2 - 1), Math.fround(rand() * 1e6)]);
    const json = Number.isNaN(v) ? 'NaN' : v === Infinity ? 'Infinity' : v === -Infinity ? '-Infinity'
      : Object.is(v, -0) ? '-0' : v;
    return { node: v, json };
  }
  if (type === 'uint64_t' || type === 'int64_t') {
    const signed = type === 'int64_t';
    let v = 0n;
    if (!zero) {
      const extremes = signed ? [-(1n << 63n), (1n << 63n) - 1n, -1n, (1n << 53n) + 1n]
        : [(1n << 64n) - 1n, (1n << 53n) + 1n, 1n];
      v = rand() < 0.4 ? pick(extremes)
        : BigInt.asIntN(64, (BigInt(Math.floor(rand() * 2 ** 32)) << 32n) | BigInt(Math.floor(rand() * 2 ** 32)));
      if (!signed) v = BigInt.asUintN(64, v);
    }
    return { node: v, json: v.toString() };
  }
  const [lo, hi] = INT_RANGES[type];
  const v = zero ? 0 : rand() < 0.3 ? pick([lo, hi]) : lo + Math.floor(rand() * (hi - lo + 1));
  return { node: v, json: v };
}

// Random values for every field of node-mavlink class `clazz`: { node: {name: v}, json: {source: v} }.
function randomFields(clazz) {
  const node = {};
  const json = {};
  const zeroExtensions = rand() < 0.3;
  for (const f of clazz.FIELDS) {
    if (f.extension && zeroExtensions) {
      continue;  // left at node-mavlink's default / absent in our JSON: both 0
    }
    if (f.type === 'char[]') {
      const n = Math.floor(rand() * (f.length + 1));
      let s = '';
      for (let i = 0; i < n; i++) s += String.fromCharCode(32 + Math.floor(rand() * 95));
      node[f.name] = s;
      json[f.source] = s;
    } else if (f.type.endsWith('[]')) {
      const elems = Array.from({ length: f.length }, () => randomElement(f.type.slice(0, -2)));
      node[f.name] = elems.map((e) => e.node);
      json[f.source] = elems.map((e) => e.json);
    } else {
      const e = randomElement(f.type);
      node[f.name] = e.node;
      json[f.source] = e.json;
    }
  }
  return { node, json };
}

// Same value, float32-aware: `ours` is what we print (number, "NaN", "-0", decimal string).
function sameValue(type, nodeValue, ours) {
  if (Array.isArray(nodeValue)) {
    return Array.isArray(ours) && ours.length === nodeValue.length &&
      nodeValue.every((v, i) => sameValue(type.slice(0, -2), v, ours[i]));
  }
  if (type === 'char[]' || type === 'char') return nodeValue === ours;
  if (type.startsWith('float')) {
    if (Number.isNaN(nodeValue)) return ours === 'NaN';
    if (Object.is(nodeValue, -0)) return ours === '-0';
    if (nodeValue === Infinity) return ours === 'Infinity';
    if (nodeValue === -Infinity) return ours === '-Infinity';
    return typeof ours === 'number' && Math.fround(ours) === nodeValue;
  }
  if (typeof nodeValue === 'bigint') return ours === nodeValue.toString();
  return nodeValue === ours;
}

// The value of an unset field on the wire: 0 (0n for 64-bit, '' for strings, zeros for arrays).
function zeroOf(f) {
  const scalar = f.type.replace('[]', '');
  const zero = scalar === 'char' ? '' : scalar.endsWith('64_t') ? 0n : 0;
  if (f.type === 'char[]') return '';
  return f.type.endsWith('[]') ? Array.from({ length: f.length }, () => zero) : zero;
}

function nodeParse(buffers) {
  return new Promise((resolve, reject) => {
    const packets = [];
    const stream = mavlink.createMavLinkStream(Readable.from([Buffer.concat(buffers)]));
    stream.on('data', (p) => packets.push(p));
    stream.on('end', () => resolve(packets));
    stream.on('error', reject);
  });
}

function run(args) {
  return execFileSync(bin, args, { encoding: 'utf8', maxBuffer: 64 << 20 });
}

async function oursToNode() {
  const vectors = [];
  const expected = [];
  let seq = 0;
  for (const name of Object.keys(defs)) {
    const clazz = REGISTRY[defs[name].id];
    check(clazz && clazz.MSG_NAME === name, `node-mavlink knows ${name}`);
    if (!clazz) continue;
    for (let i = 0; i < SAMPLES; i++) {
      const { node, json } = randomFields(clazz);
      const v = { id: `${name}_${i}`, msg: name, seq: seq++ & 255, sysid: 1 + (i % 255), compid: 197, fields: json };
      if (i % 5 === 4) v.sign = { link_id: i % 256, timestamp: String(1000 + i) };
      vectors.push(v);
      expected.push({ clazz, node, signed: !!v.sign });
    }
  }
  const file = path.join(tmp, 'vectors.json');
  fs.writeFileSync(file, JSON.stringify({ key_hex: golden.key_hex, vectors }));
  const lines = run(['mavlink', 'encode', file]).trim().split('\n');
  check(lines.length === vectors.length, `encode printed ${lines.length} of ${vectors.length} frames`);
  const buffers = lines.map((l) => Buffer.from(l.split(' ')[1], 'hex'));
  const packets = await nodeParse(buffers);
  // node-mavlink's splitter drops frames with a wrong CRC: every frame must come through.
  check(packets.length === buffers.length, `node-mavlink accepted ${packets.length} of ${buffers.length}`);
  packets.forEach((p, i) => {
    const { clazz, node, signed } = expected[i];
    check(p.header.msgid === clazz.MSG_ID, `${vectors[i].id}: msgid`);
    check(p.header.seq === vectors[i].seq && p.header.sysid === vectors[i].sysid, `${vectors[i].id}: header`);
    const data = p.protocol.data(p.payload, clazz);
    for (const f of clazz.FIELDS) {
      const want = f.name in node ? node[f.name] : zeroOf(f);
      const got = data[f.name];
      const ok = Array.isArray(want)
        ? want.length === got.length && want.every((w, k) => Object.is(w, got[k]) || (Number.isNaN(w) && Number.isNaN(got[k])))
        : Object.is(want, got) || (Number.isNaN(want) && Number.isNaN(got));
      check(ok, `${vectors[i].id}.${f.source}: node-mavlink read ${String(got)}, we wrote ${String(want)}`);
    }
    check(!!p.signature === signed, `${vectors[i].id}: signed flag`);
    if (signed) check(p.signature.matches(key), `${vectors[i].id}: node-mavlink rejects our signature`);
  });
  // Golden frames (C library / pymavlink bytes) through our encoder, signed ones checked by node.
  const goldenLines = run(['mavlink', 'encode', 'tests/libs/mavlink/data/golden-vectors.json']).trim().split('\n');
  const goldenPackets = await nodeParse(goldenLines.map((l) => Buffer.from(l.split(' ')[1], 'hex')));
  check(goldenPackets.length === golden.vectors.length, 'node-mavlink accepts every golden frame we encode');
  goldenPackets.filter((p) => p.signature).forEach((p) => check(p.signature.matches(key), 'golden signature'));
}

function nodeToOurs() {
  const lines = [];
  const expected = [];
  let seq = 0;
  for (const name of Object.keys(defs)) {
    const clazz = REGISTRY[defs[name].id];
    if (!clazz) continue;
    for (let i = 0; i < SAMPLES; i++) {
      const { node } = randomFields(clazz);
      const msg = new clazz();
      for (const f of clazz.FIELDS) if (f.name in node) msg[f.name] = node[f.name];
      const signed = i % 5 === 4;
      const proto = new mavlink.MavLinkProtocolV2(1 + (i % 200), 190,
        signed ? mavlink.MavLinkProtocolV2.IFLAG_SIGNED : 0);
      let buf = proto.serialize(msg, seq++ & 255);
      const unixMs = 1700000000000 + i;
      if (signed) buf = proto.sign(buf, i, key, unixMs);
      lines.push(buf.toString('hex'));
      expected.push({ clazz, msg, node, signed, sigTimestamp: String(BigInt(unixMs - Date.UTC(2015, 0, 1)) * 100n), linkId: i });
    }
  }
  const file = path.join(tmp, 'frames.hex');
  fs.writeFileSync(file, lines.join('\n') + '\n');
  const out = run(['mavlink', 'decode', '--key', golden.key_hex, file]).trim().split('\n');
  check(out.length === lines.length, `we decoded ${out.length} of ${lines.length} node-mavlink frames`);
  out.forEach((line, i) => {
    const got = JSON.parse(line);
    const { clazz, msg, signed } = expected[i];
    check(got.msgid === clazz.MSG_ID && got.name === clazz.MSG_NAME, `frame ${i}: ${got.name} is ${clazz.MSG_NAME}`);
    for (const f of clazz.FIELDS) {
      // Fields we did not set keep node-mavlink's defaults, which for enum fields are enum name
      // strings serialised as 0 (mavlink-wire.md §9.6): expect 0 there.
      const want = f.name in expected[i].node ? msg[f.name] : zeroOf(f);
      check(sameValue(f.type, want, got.fields[f.source]),
        `${clazz.MSG_NAME}#${i}.${f.source}: node-mavlink wrote ${String(want)}, we read ${JSON.stringify(got.fields[f.source])}`);
    }
    if (signed) {
      check(got.signature_valid === true, `${clazz.MSG_NAME}#${i}: node-mavlink signature rejected`);
      check(got.sig_timestamp === expected[i].sigTimestamp && got.link_id === expected[i].linkId,
        `${clazz.MSG_NAME}#${i}: signature block`);
    } else {
      check(!('signature_valid' in got), `${clazz.MSG_NAME}#${i}: unsigned`);
    }
  });
}

(async () => {
  try {
    await oursToNode();
    nodeToOurs();
  } finally {
    fs.rmSync(tmp, { recursive: true, force: true });
  }
  finish('node-mavlink conformance');
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
