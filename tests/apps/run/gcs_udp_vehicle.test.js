// Ground stations on a vehicle's link (issue 38), vehicle over UDP (`udp://` to a PX4-like
// autopilot): QGroundControl's first seconds through each `gcs` form at once (udpin, tcpin, udp);
// every frame passes unchanged both ways, mocaplink's own answers stay with it. See gcs_e2e.js.
'use strict';

const { runMatrix, udpVehicleTransport } = require('./gcs_e2e');

runMatrix(udpVehicleTransport, 'udp vehicle');
