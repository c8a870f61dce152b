// bench/gcs_link: what the scripted vehicle and ground station share — node-mavlink encoding and
// decoding, and per-message counters of frames and bytes that can be reset at the start of the
// measured window.
'use strict';

const {
  MavLinkPacketSplitter, MavLinkPacketParser, MavLinkProtocolV2, minimal, common, standard,
  ardupilotmega,
} = require('node-mavlink');

const REGISTRY = {
  ...minimal.REGISTRY, ...standard.REGISTRY, ...common.REGISTRY, ...ardupilotmega.REGISTRY,
};

/// Bytes of a packet on the wire: header, payload, CRC and the signature if any.
function wireBytes(packet) {
  const v2 = packet.header.magic === 0xfd;
  const signed = v2 && (packet.header.incompatibilityFlags & 1) !== 0;
  return (v2 ? 10 : 6) + packet.header.payloadLength + 2 + (signed ? 13 : 0);
}

/// Decodes a byte stream; `onPacket(packet, message)` for every packet that passes its CRC
/// (message undefined for ids node-mavlink does not know).
class Decoder {
  constructor(onPacket) {
    this.splitter = new MavLinkPacketSplitter();
    this.parser = new MavLinkPacketParser();
    this.splitter.pipe(this.parser);
    this.parser.on('data', (packet) => {
      const clazz = REGISTRY[packet.header.msgid];
      onPacket(packet, clazz ? packet.protocol.data(packet.payload, clazz) : undefined);
    });
  }
  write(buffer) { this.splitter.write(buffer); }
  get invalid() { return this.splitter.invalidPackages; }
}

/// Serializes messages as one system/component, with its own sequence numbers.
class Speaker {
  constructor(sysid, compid) {
    this.protocol = new MavLinkProtocolV2(sysid, compid);
    this.seq = 0;
  }
  frame(message) {
    const bytes = this.protocol.serialize(message, this.seq);
    this.seq = (this.seq + 1) & 255;
    return bytes;
  }
}

/// Frames and bytes per message name; `mark()` starts a new window.
class Counter {
  constructor() { this.mark(); }
  mark() {
    this.byName = {};
    this.frames = 0;
    this.bytes = 0;
    this.since = process.hrtime.bigint();
  }
  add(msgid, bytes) {
    const clazz = REGISTRY[msgid];
    const name = clazz ? clazz.MSG_NAME : `#${msgid}`;
    const entry = this.byName[name] || (this.byName[name] = { frames: 0, bytes: 0 });
    entry.frames += 1;
    entry.bytes += bytes;
    this.frames += 1;
    this.bytes += bytes;
  }
  report() {
    return { frames: this.frames, bytes: this.bytes, by_message: this.byName,
             seconds: Number(process.hrtime.bigint() - this.since) / 1e9 };
  }
}

/// Builds a message of class `clazz` with the given fields.
function make(clazz, fields) {
  return Object.assign(new clazz(), fields);
}

module.exports = { common, minimal, standard, ardupilotmega, Counter, Decoder, Speaker, make, wireBytes };
