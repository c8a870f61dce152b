// bench/gcs_link: the scripted vehicle, an ArduPilot-like autopilot on the far end of the emulated
// serial cable (forked by run_gcs_link.js; the pty's slave path and the baud rate in argv).
//
// It sends HEARTBEAT (ArduPilot, quadrotor) and SYS_STATUS at 1 Hz, ATTITUDE and
// LOCAL_POSITION_NED at 5 Hz and EKF_STATUS_REPORT at 1 Hz (what mocaplink's bandwidth estimate
// assumes), and answers what mocaplink and a ground station ask: AUTOPILOT_VERSION (ArduPilot
// 4.5.7), COMMAND_LONG with COMMAND_ACK, TIMESYNC, SET_GPS_GLOBAL_ORIGIN with GPS_GLOBAL_ORIGIN,
// PARAM_REQUEST_READ (by name or index) and PARAM_SET with PARAM_VALUE, PARAM_REQUEST_LIST with all
// of its parameters (PARAMS, default 1000, among them the vision set-up mocaplink reads, all
// right), LOG_REQUEST_LIST with LOG_ENTRY (LOGS, default 50), MISSION_REQUEST_LIST with
// MISSION_COUNT and MISSION_REQUEST_INT with MISSION_ITEM_INT, and a mission upload (MISSION_COUNT)
// with MISSION_REQUEST_INT for each item in turn (asked again after 1 s without it) and
// MISSION_ACK at the end.
// The parameter and log lists go out at most at 30% of the link's baud/10 bytes/s, as ArduPilot's
// queued_param_send paces parameters on a port without flow control; the vehicle's other frames
// go out when due. So the vehicle offers at most ~45% of the link toward mocaplink.
//
// IPC with the parent: {cmd: 'mark'} starts the measured window; {cmd: 'report'} is answered
// with the window's counters and the receive time (CLOCK_MONOTONIC ns) of every ODOMETRY, by its
// time_usec.
'use strict';

const fs = require('node:fs');
const tty = require('node:tty');
const { common, minimal, standard, ardupilotmega, Counter, Decoder, Speaker, make, wireBytes } =
  require('./mav');

const [ttyPath, baudText] = process.argv.slice(2);
const baud = Number(baudText);
const PARAM_COUNT = Number(process.env.PARAMS || 1000);
const LOG_COUNT = Number(process.env.LOGS || 50);
const SYSID = 1;
const COMPID = 1;
const GCS_SYSID = 255;

const me = new Speaker(SYSID, COMPID);
const input = new tty.ReadStream(fs.openSync(ttyPath, fs.constants.O_RDONLY | fs.constants.O_NOCTTY));
const output = new tty.WriteStream(fs.openSync(ttyPath, fs.constants.O_WRONLY | fs.constants.O_NOCTTY));
input.setRawMode(true);

const sent = new Counter();
const fromGcs = new Counter();
const fromOthers = new Counter();  // mocaplink's own frames (poses, requests)
let odometry = [];  // [time_usec string, receive ns string]
let events = { param_lists_started: 0, log_lists_started: 0, mission_uploads_done: 0,
               mission_items_rerequested: 0 };

function send(message) {
  const bytes = me.frame(message);
  sent.add(message.constructor.MSG_ID, bytes.length);
  output.write(bytes);
}

// --- Parameters: the vision set-up mocaplink's ardupilot rules read, then fillers. -------------
const params = [
  ['AHRS_EKF_TYPE', 3], ['VISO_TYPE', 1], ['EK3_SRC1_POSXY', 6], ['EK3_SRC1_VELXY', 6],
  ['EK3_SRC1_VELZ', 6], ['EK3_SRC1_POSZ', 6], ['EK3_SRC1_YAW', 6], ['GPS1_TYPE', 0],
  ['GPS_TYPE', 0], ['VISO_DELAY_MS', 10], ['SYSID_THISMAV', SYSID],
];
for (let i = params.length; i < PARAM_COUNT; i += 1) {
  params.push([`BENCH_P${String(i).padStart(4, '0')}`, i * 0.5]);
}
const paramIndex = new Map(params.map(([name], i) => [name, i]));

function paramValue(i, index = i) {
  return make(common.ParamValue, { paramId: params[i][0], paramValue: params[i][1],
                                   paramType: 9 /* REAL32 */, paramCount: params.length,
                                   paramIndex: index });
}

// --- Paced lists (parameters, log entries): 30% of baud/10 bytes/s. ---------------------------
const listBytesPerS = 0.3 * baud / 10;
let listTokens = 0;
let listQueue = [];  // functions that build the next message
let lastRefill = process.hrtime.bigint();
setInterval(() => {
  const now = process.hrtime.bigint();
  listTokens = Math.min(listTokens + listBytesPerS * Number(now - lastRefill) / 1e9, 200);
  lastRefill = now;
  while (listQueue.length > 0 && listTokens > 0) {
    const message = listQueue.shift()();
    listTokens -= 12 + message.constructor.PAYLOAD_LENGTH;
    send(message);
  }
}, 5);

// --- Telemetry. ---------------------------------------------------------------------------------
const started = Date.now();
const bootMs = () => (Date.now() - started) >>> 0;
setInterval(() => {
  send(make(minimal.Heartbeat, { type: 2, autopilot: 3, baseMode: 81, customMode: 0,
                                 systemStatus: 3, mavlinkVersion: 3 }));
  send(make(common.SysStatus, { voltageBattery: 12600, currentBattery: 500,
                                batteryRemaining: 90 }));
  send(make(ardupilotmega.EkfStatusReport, { flags: 0x1ff, velocityVariance: 0.1,
                                             posHorizVariance: 0.1, posVertVariance: 0.1,
                                             compassVariance: 0.1 }));
}, 1000);
setInterval(() => {
  send(make(common.Attitude, { timeBootMs: bootMs(), roll: 0.01, pitch: -0.01, yaw: 0.5 }));
  send(make(common.LocalPositionNed, { timeBootMs: bootMs(), x: 1, y: 2, z: -1 }));
}, 200);

// --- Missions. -----------------------------------------------------------------------------------
let mission = [];  // MISSION_ITEM_INT fields
let upload = null;  // {count, next, items, timer, from}

function requestItem() {
  clearTimeout(upload.timer);
  send(make(common.MissionRequestInt, { seq: upload.next, targetSystem: upload.from.sysid,
                                        targetComponent: upload.from.compid, missionType: 0 }));
  upload.timer = setTimeout(() => {
    events.mission_items_rerequested += 1;
    requestItem();
  }, 1000);
}

function ack(command, from) {
  send(make(common.CommandAck, { command, result: 0, targetSystem: from.sysid,
                                 targetComponent: from.compid }));
}

// --- What arrives. ------------------------------------------------------------------------------
const decoder = new Decoder((packet, m) => {
  const { msgid, sysid, compid } = packet.header;
  (sysid === GCS_SYSID ? fromGcs : fromOthers).add(msgid, wireBytes(packet));
  const from = { sysid, compid };
  switch (msgid) {
    case common.Odometry.MSG_ID:
      odometry.push([m.timeUsec.toString(), decoder.chunkNs]);
      break;
    case common.CommandLong.MSG_ID:
      if (m.command === 512 && Math.round(m._param1) === 148) {  // REQUEST_MESSAGE(AUTOPILOT_VERSION)
        send(make(standard.AutopilotVersion, { capabilities: 2n | 4n | 8192n,
                                               flightSwVersion: (4 << 24) | (5 << 16) | (7 << 8) | 255 }));
      }
      ack(m.command, from);
      break;
    case common.TimeSync.MSG_ID:
      if (m.tc1 === 0n) {
        send(make(common.TimeSync, { tc1: process.hrtime.bigint(), ts1: m.ts1,
                                     targetSystem: sysid, targetComponent: compid }));
      }
      break;
    case common.SetGpsGlobalOrigin.MSG_ID:
      send(make(common.GpsGlobalOrigin, { latitude: m.latitude, longitude: m.longitude,
                                          altitude: m.altitude, timeUsec: 0n }));
      break;
    case common.ParamRequestRead.MSG_ID: {
      const i = m.paramIndex >= 0 ? m.paramIndex : paramIndex.get(m.paramId.replace(/\0.*$/, ''));
      if (i !== undefined && i < params.length) send(paramValue(i, m.paramIndex >= 0 ? i : 65535));
      break;
    }
    case common.ParamSet.MSG_ID: {
      const i = paramIndex.get(m.paramId.replace(/\0.*$/, ''));
      if (i !== undefined) {
        params[i][1] = m.paramValue;
        send(paramValue(i, 65535));
      }
      break;
    }
    case common.ParamRequestList.MSG_ID:
      // Like ArduPilot: a new request restarts the list from the first parameter.
      events.param_lists_started += 1;
      listQueue = listQueue.filter((f) => f.kind !== 'param');
      for (let i = 0; i < params.length; i += 1) {
        listQueue.push(Object.assign(() => paramValue(i), { kind: 'param' }));
      }
      break;
    case common.LogRequestList.MSG_ID: {
      events.log_lists_started += 1;
      listQueue = listQueue.filter((f) => f.kind !== 'log');
      for (let id = Math.max(1, m.start); id <= Math.min(LOG_COUNT, m.end); id += 1) {
        listQueue.push(Object.assign(() => make(common.LogEntry, {
          id, numLogs: LOG_COUNT, lastLogNum: LOG_COUNT, timeUtc: 1700000000 + id,
          size: 1000000 + id }), { kind: 'log' }));
      }
      break;
    }
    case common.MissionRequestList.MSG_ID:
      send(make(common.MissionCount, { count: mission.length, targetSystem: sysid,
                                       targetComponent: compid, missionType: 0 }));
      break;
    case common.MissionRequestInt.MSG_ID:
    case common.MissionRequest.MSG_ID:
      if (m.seq < mission.length) {
        send(make(common.MissionItemInt, { ...mission[m.seq], targetSystem: sysid,
                                           targetComponent: compid }));
      }
      break;
    case common.MissionCount.MSG_ID:
      if (upload) clearTimeout(upload.timer);
      upload = { count: m.count, next: 0, items: [], timer: null, from };
      if (m.count === 0) {
        mission = [];
        upload = null;
        send(make(common.MissionAck, { targetSystem: sysid, targetComponent: compid, type: 0 }));
      } else {
        requestItem();
      }
      break;
    case common.MissionItemInt.MSG_ID:
      if (upload && m.seq === upload.next) {
        upload.items.push({ seq: m.seq, frame: m.frame, command: m.command, current: m.current,
                            autocontinue: m.autocontinue, param1: m.param1, param2: m.param2,
                            param3: m.param3, param4: m.param4, x: m.x, y: m.y, z: m.z,
                            missionType: 0 });
        upload.next += 1;
        if (upload.next < upload.count) {
          requestItem();
        } else {
          clearTimeout(upload.timer);
          mission = upload.items;
          upload = null;
          events.mission_uploads_done += 1;
          send(make(common.MissionAck, { targetSystem: sysid, targetComponent: compid, type: 0 }));
        }
      }
      break;
    default:
      break;
  }
});
input.on('data', (chunk) => {
  decoder.chunkNs = process.hrtime.bigint().toString();  // the frames in it arrived complete now
  decoder.write(chunk);
});

process.on('message', (message) => {
  if (message.cmd === 'mark') {
    for (const c of [sent, fromGcs, fromOthers]) c.mark();
    odometry = [];
    events = Object.fromEntries(Object.keys(events).map((k) => [k, 0]));
    process.send({ cmd: 'marked' });
  } else if (message.cmd === 'report') {
    process.send({ cmd: 'report', sent: sent.report(), from_gcs: fromGcs.report(),
                   from_others: fromOthers.report(), odometry, events,
                   crc_failures: decoder.invalid });
  } else if (message.cmd === 'exit') {
    process.exit(0);
  }
});
process.send({ cmd: 'ready' });
