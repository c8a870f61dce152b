#!/bin/sh
# Runs the given test command in a new network namespace with a multicast-capable loopback
# (natnet_netns_test.cpp). Without the privilege to make one, runs it outside with the reason in
# MOCAPLINK_NATNET_NETNS, so that the test reports itself skipped and says why.
if unshare -n true 2>/dev/null; then
  exec unshare -n sh -c 'ip link set lo up && ip link set lo multicast on &&
    ip route add 224.0.0.0/4 dev lo && MOCAPLINK_NATNET_NETNS=1 exec "$@"' sh "$@"
fi
MOCAPLINK_NATNET_NETNS="cannot make a network namespace (unshare -n needs root)" exec "$@"
