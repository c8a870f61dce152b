// Ground stations on a vehicle's link (issue 38), vehicle over UDP (`udp://` to a PX4-like
// autopilot): QGroundControl's first seconds through each `gcs` form at once (udpin, tcpin, udp);
// every frame passes unchanged both ways, mocaplink's own answers stay with it. See gcs_e2e.js.
'use strict';

const h = require('./harness');
const { forwardingMatrix, udpVehicleTransport } = require('./gcs_e2e');

async function main() {
  const r = await forwardingMatrix(udpVehicleTransport, 'udp vehicle');
  console.log(`ok: udp vehicle, ${r.gcs.map((g) => `${g.url} ${g.sent.length} sent/${g.received.length} received`).join('; ')}; ` +
    `${r.odometry} ODOMETRY in ${r.seconds.toFixed(1)} s`);
  console.log(JSON.stringify({ gcs: r.after.gcs, link_share: r.after.link_share }));
}

main().catch(h.fail);
