// Ground stations on a vehicle's link (issue 38), vehicle on a serial port (a pty pair made by
// pty_relay, `serial://` at 921600 baud, far more than both sides use, so nothing is held back):
// QGroundControl's first seconds through each `gcs` form at once (udpin, tcpin, udp); every frame
// passes unchanged both ways, mocaplink's own answers stay with it; link_share has a capacity.
// See gcs_e2e.js.
'use strict';

const h = require('./harness');
const { forwardingMatrix, serialVehicleTransport } = require('./gcs_e2e');

async function main() {
  const r = await forwardingMatrix(() => serialVehicleTransport(921600), 'serial vehicle');
  console.log(`ok: serial vehicle, ${r.gcs.map((g) => `${g.url} ${g.sent.length} sent/${g.received.length} received`).join('; ')}; ` +
    `${r.odometry} ODOMETRY in ${r.seconds.toFixed(1)} s`);
  console.log(JSON.stringify({ gcs: r.after.gcs, link_share: r.after.link_share }));
}

main().catch(h.fail);
