// Ground stations on a vehicle's link (issue 38), vehicle on a serial port (a pty pair made by
// pty_relay, `serial://` at 921600 baud, far more than both sides use, so nothing is held back):
// QGroundControl's first seconds through each `gcs` form at once (udpin, tcpin, udp); every frame
// passes unchanged both ways, mocaplink's own answers stay with it; link_share has a capacity.
// See gcs_e2e.js.
'use strict';

const { runMatrix, serialVehicleTransport } = require('./gcs_e2e');

runMatrix(() => serialVehicleTransport(921600), 'serial vehicle');
