// bench/gcs_link: the scripted ground station, behaving as QGroundControl does (forked by
// run_gcs_link.js; argv: mocaplink's gcs port on 127.0.0.1 and the task).
//
// Always: HEARTBEAT at 1 Hz as MAV_TYPE_GCS, system 255, component 190 (MAV_COMP_ID_MISSIONPLANNER,
// QGroundControl's), from one UDP socket to mocaplink's `gcs = ["udpin://127.0.0.1:PORT"]`; it
// starts its task once it hears the vehicle's HEARTBEAT through mocaplink.
// Task `download`: MISSION_REQUEST_LIST (answered with MISSION_COUNT; the items one by one if any, then
// MISSION_ACK), then
// over and over: PARAM_REQUEST_LIST; when PARAM_VALUEs stop for 1 s with some missing, the missing
// ones by index with PARAM_REQUEST_READ (10 at a time), the list again if none came at all; once
// all are in, LOG_REQUEST_LIST (0..0xffff) and, when LOG_ENTRYs stop for 1 s with some missing,
// the missing range again; once all are in, the parameters again.
// Task `upload`: over and over, a 200-item mission (MISSION_ITEMS): MISSION_COUNT, each
// MISSION_REQUEST_INT answered with its MISSION_ITEM_INT, until MISSION_ACK; MISSION_COUNT again
// after 1.5 s without a request.
//
// IPC with the parent: 'ready' once the vehicle was heard; {cmd: 'mark'} starts the measured
// window; {cmd: 'report'} is answered with the window's counters and completed tasks.
'use strict';

const dgram = require('node:dgram');
const { common, minimal, Counter, Decoder, Speaker, make, wireBytes } = require('./mav');

const [portText, task] = process.argv.slice(2);
const port = Number(portText);
const MISSION_ITEMS = Number(process.env.MISSION_ITEMS || 200);
const VEHICLE = { sysid: 1, compid: 1 };
const target = { targetSystem: VEHICLE.sysid, targetComponent: VEHICLE.compid };

const me = new Speaker(255, 190);
const socket = dgram.createSocket({ type: 'udp4', recvBufferSize: 1 << 20 });
const sent = new Counter();
const fromVehicle = new Counter();
const fromOthers = new Counter();
let done = { param_downloads: [], log_listings: [], mission_uploads: [], param_rerequests: 0,
             list_rerequests: 0, log_rerequests: 0, mission_count_resent: 0 };
const now = () => Number(process.hrtime.bigint()) / 1e6;  // ms

function send(message) {
  const bytes = me.frame(message);
  sent.add(message.constructor.MSG_ID, bytes.length);
  socket.send(bytes, port, '127.0.0.1');
}

// --- Download: parameters, then the log list, over and over. ----------------------------------
const dl = { phase: 'idle', values: new Map(), count: null, started: 0, lastHeard: 0,
             logs: new Map(), numLogs: null, missionCount: 0 };

function startParams() {
  Object.assign(dl, { phase: 'params', values: new Map(), count: null, started: now(),
                      lastHeard: now() });
  send(make(common.ParamRequestList, target));
}

function startLogs() {
  Object.assign(dl, { phase: 'logs', logs: new Map(), numLogs: null, started: now(),
                      lastHeard: now() });
  send(make(common.LogRequestList, { ...target, start: 0, end: 0xffff }));
}

function downloadTick() {
  if (now() - dl.lastHeard < 1000) return;
  dl.lastHeard = now();
  if (dl.phase === 'params') {
    if (dl.count === null) {
      done.list_rerequests += 1;
      send(make(common.ParamRequestList, target));
      return;
    }
    let asked = 0;
    for (let i = 0; i < dl.count && asked < 10; i += 1) {
      if (!dl.values.has(i)) {
        send(make(common.ParamRequestRead, { ...target, paramIndex: i, paramId: '' }));
        asked += 1;
      }
    }
    done.param_rerequests += asked;
  } else if (dl.phase === 'logs') {
    const missing = [];
    for (let id = 1; id <= (dl.numLogs ?? 1); id += 1) if (!dl.logs.has(id)) missing.push(id);
    done.log_rerequests += 1;
    send(make(common.LogRequestList, { ...target, start: missing[0] ?? 0,
                                       end: missing[missing.length - 1] ?? 0xffff }));
  }
}

function onDownload(msgid, m) {
  if (msgid === common.ParamValue.MSG_ID && dl.phase === 'params') {
    dl.lastHeard = now();
    dl.count = m.paramCount;
    if (m.paramIndex < m.paramCount) dl.values.set(m.paramIndex, m.paramValue);
    if (dl.values.size === dl.count) {
      done.param_downloads.push(now() - dl.started);
      startLogs();
    }
  } else if (msgid === common.LogEntry.MSG_ID && dl.phase === 'logs') {
    dl.lastHeard = now();
    dl.numLogs = m.numLogs;
    if (m.id >= 1) dl.logs.set(m.id, m.size);
    if (dl.logs.size === dl.numLogs) {
      done.log_listings.push(now() - dl.started);
      startParams();
    }
  } else if (msgid === common.MissionCount.MSG_ID) {
    dl.missionCount = m.count;
    if (m.count > 0) send(make(common.MissionRequestInt, { ...target, seq: 0, missionType: 0 }));
  } else if (msgid === common.MissionItemInt.MSG_ID && m.seq + 1 < dl.missionCount) {
    send(make(common.MissionRequestInt, { ...target, seq: m.seq + 1, missionType: 0 }));
  } else if (msgid === common.MissionItemInt.MSG_ID && m.seq + 1 === dl.missionCount) {
    send(make(common.MissionAck, { ...target, type: 0, missionType: 0 }));
  }
}

// --- Upload: a mission, over and over. ---------------------------------------------------------
const ul = { started: 0, lastHeard: 0 };
const item = (seq) => make(common.MissionItemInt, {
  ...target, seq, frame: 6 /* GLOBAL_RELATIVE_ALT_INT */, command: 16 /* NAV_WAYPOINT */,
  current: seq === 0 ? 1 : 0, autocontinue: 1, param1: 0, param2: 2, param3: 0, param4: 0,
  x: 473977420 + seq * 10, y: 85455940 + seq * 10, z: 10 + (seq % 5), missionType: 0 });

function startUpload() {
  Object.assign(ul, { started: now(), lastHeard: now() });
  send(make(common.MissionCount, { ...target, count: MISSION_ITEMS, missionType: 0 }));
}

function uploadTick() {
  if (now() - ul.lastHeard < 1500) return;
  done.mission_count_resent += 1;
  startUpload();
}

function onUpload(msgid, m) {
  if ((msgid === common.MissionRequestInt.MSG_ID || msgid === common.MissionRequest.MSG_ID) &&
      m.seq < MISSION_ITEMS) {
    ul.lastHeard = now();
    send(item(m.seq));
  } else if (msgid === common.MissionAck.MSG_ID) {
    if (m.type === 0) done.mission_uploads.push(now() - ul.started);
    startUpload();
  }
}

// --- The socket. -------------------------------------------------------------------------------
let heard = false;
const decoder = new Decoder((packet, m) => {
  const { msgid, sysid } = packet.header;
  if (sysid !== VEHICLE.sysid) {
    fromOthers.add(msgid, wireBytes(packet));
    return;
  }
  fromVehicle.add(msgid, wireBytes(packet));
  if (!heard && msgid === minimal.Heartbeat.MSG_ID) {
    heard = true;
    process.send({ cmd: 'ready' });
    if (task === 'download') {
      send(make(common.MissionRequestList, { ...target, missionType: 0 }));
      startParams();
      setInterval(downloadTick, 100);
    } else if (task === 'upload') {
      startUpload();
      setInterval(uploadTick, 100);
    }
  }
  if (m === undefined) return;
  if (task === 'download') onDownload(msgid, m);
  if (task === 'upload') onUpload(msgid, m);
});
socket.on('message', (datagram) => decoder.write(datagram));
socket.bind(0, '127.0.0.1', () => {
  const beat = () => send(make(minimal.Heartbeat, { type: 6, autopilot: 8, baseMode: 0,
                                                     customMode: 0, systemStatus: 4,
                                                     mavlinkVersion: 3 }));
  beat();
  setInterval(beat, 1000);
});

process.on('message', (message) => {
  if (message.cmd === 'mark') {
    for (const c of [sent, fromVehicle, fromOthers]) c.mark();
    done = Object.fromEntries(Object.entries(done).map(([k, v]) => [k, Array.isArray(v) ? [] : 0]));
    process.send({ cmd: 'marked' });
  } else if (message.cmd === 'report') {
    process.send({ cmd: 'report', sent: sent.report(), from_vehicle: fromVehicle.report(),
                   from_others: fromOthers.report(), done, crc_failures: decoder.invalid });
  } else if (message.cmd === 'exit') {
    process.exit(0);
  }
});
