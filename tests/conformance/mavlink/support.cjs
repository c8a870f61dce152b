// Shared by the node-mavlink scripts of this folder: a check counter and a seeded PRNG.
'use strict';

// check(ok, what) counts a check and prints the first 30 failures; finish(label) prints the tally
// and exits 0 only if every check passed.
function makeChecker() {
  let failures = 0;
  let checks = 0;
  return {
    check(ok, what) {
      checks++;
      if (!ok) {
        failures++;
        if (failures <= 30) console.error('FAIL:', what);
      }
    },
    finish(label) {
      console.log(`${label}: ${checks - failures}/${checks} checks passed`);
      process.exit(failures === 0 ? 0 : 1);
    },
  };
}

// Deterministic PRNG (mulberry32): a function returning numbers in [0, 1) from `seed`.
function makeRandom(seed) {
  let state = seed | 0;
  return () => {
    state = (state + 0x6d2b79f5) | 0;
    let t = state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// Value range of each integer field type of node-mavlink's tables.
const INT_RANGES = {
  int8_t: [-128, 127], uint8_t: [0, 255], uint8_t_mavlink_version: [0, 255], int16_t: [-32768, 32767],
  uint16_t: [0, 65535], int32_t: [-2147483648, 2147483647], uint32_t: [0, 4294967295],
};

module.exports = { makeChecker, makeRandom, INT_RANGES };
