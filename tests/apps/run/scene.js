// A known mocap scene written as a mocaplink recording (DESIGN.md "Recording format"): the ground
// truth of the end-to-end tests, computed here independently of the bridge and the simulator.
//
// World frame as Vicon reports it: z up; the run config says up = "+z", north = "+x", so
// NED = (x, −y, −z) and a yaw of ψ about +z is a heading of −ψ.
'use strict';

const fs = require('node:fs');

const RATE_HZ = 200;

/// Body1 hovers still at (1, 2, 0.5) m, yawed 30° about +z. Body2 flies along +x at 0.1 m/s at
/// 1 m height. Body3 circles (r = 0.5 m, 0.5 rad/s) about (0, −3, 1.5) m. Body1 and Body2 are
/// occluded from OCCLUDE_FROM_S to OCCLUDE_TO_S (tracked = 0).
const OCCLUDE_FROM_S = 5.0;
const OCCLUDE_TO_S = 5.3;
const YAW1_RAD = (30 * Math.PI) / 180;

function truth(body, t) {
  switch (body) {
    case 'Body1':
      return { p: [1, 2, 0.5], q: [Math.cos(YAW1_RAD / 2), 0, 0, Math.sin(YAW1_RAD / 2)] };
    case 'Body2':
      return { p: [-1 + 0.1 * t, 0, 1], q: [1, 0, 0, 0] };
    case 'Body3':
      return { p: [0.5 * Math.cos(0.5 * t), -3 + 0.5 * Math.sin(0.5 * t), 1.5], q: [1, 0, 0, 0] };
    default:
      throw new Error(body);
  }
}

function occluded(body, t) {
  return (body === 'Body1' || body === 'Body2') && t >= OCCLUDE_FROM_S && t < OCCLUDE_TO_S;
}

/// Writes `seconds` of the scene to `file`.
function writeScene(file, seconds) {
  const lines = [`# mocaplink recording 1; source=test-scene; rate_hz=${RATE_HZ}`,
    'time_s,frame,body,tracked,x_m,y_m,z_m,qw,qx,qy,qz'];
  const n = Math.round(seconds * RATE_HZ);
  for (let i = 0; i < n; i += 1) {
    const t = i / RATE_HZ;
    for (const body of ['Body1', 'Body2', 'Body3']) {
      if (occluded(body, t)) {
        lines.push(`${t.toFixed(6)},${i + 1},${body},0,,,,,,,`);
      } else {
        const { p, q } = truth(body, t);
        lines.push([t.toFixed(6), i + 1, body, 1, ...p.map((v) => v.toFixed(6)),
          ...q.map((v) => v.toFixed(6))].join(','));
      }
    }
  }
  fs.writeFileSync(file, `${lines.join('\n')}\n`);
}

/// World (z up, x north) → NED.
const toNed = ([x, y, z]) => [x, -y, -z];

/// Smallest distance (m) from NED point `p` to the body's NED trajectory over [0, seconds].
function distanceToTrajectory(body, p, seconds) {
  let best = Infinity;
  for (let i = 0; i <= seconds * 1000; i += 1) {
    const q = toNed(truth(body, i / 1000).p);
    best = Math.min(best, Math.hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]));
  }
  return best;
}

/// NED offset → WGS84 latitude/longitude (deg) and altitude (m) near `origin`, with the
/// ellipsoid's meridional and prime-vertical radii (exact to well under 1 mm over a few metres).
function nedToGeodetic(origin, [n, e, d]) {
  const a = 6378137.0;
  const f = 1 / 298.257223563;
  const e2 = f * (2 - f);
  const phi = (origin.latitude_deg * Math.PI) / 180;
  const s = Math.sin(phi);
  const w = Math.sqrt(1 - e2 * s * s);
  const meridional = (a * (1 - e2)) / (w * w * w);
  const primeVertical = a / w;
  return {
    latitude_deg: origin.latitude_deg + ((n / (meridional + origin.altitude_m)) * 180) / Math.PI,
    longitude_deg: origin.longitude_deg +
      ((e / ((primeVertical + origin.altitude_m) * Math.cos(phi))) * 180) / Math.PI,
    altitude_m: origin.altitude_m - d,
  };
}

module.exports = {
  OCCLUDE_FROM_S, OCCLUDE_TO_S, RATE_HZ, YAW1_RAD, distanceToTrajectory, nedToGeodetic, occluded,
  toNed, truth, writeScene,
};
