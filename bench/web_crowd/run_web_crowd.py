#!/usr/bin/env python3
"""bench/web_crowd: how long the operator waits for the dashboard while a crowd holds connections.

Starts `mocaplink run` (sim:// source, one vehicle to a local UDP port, dashboard on a free port),
then times 20 GET /api/status and 20 PATCH /api/vehicles/v1 one after the other, first alone and
then with a crowd: 100 idle connections (a half-sent request each), the 8 allowed /api/events
streams and a client sending one byte per second. Prints one markdown row per phase: median and
max answer time, and requests not answered within 30 s.

Usage: bench/web_crowd/run_web_crowd.py MOCAPLINK [LABEL]
"""
import http.client
import json
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def timed(port, method, path, body=None):
    start = time.monotonic()
    try:
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
        headers = {"Content-Type": "application/json"} if body else {}
        conn.request(method, path, body=body, headers=headers)
        conn.getresponse().read()
        conn.close()
        return time.monotonic() - start
    except OSError:
        return None


def phase(port, label, rows):
    status = [timed(port, "GET", "/api/status") for _ in range(20)]
    patch = [timed(port, "PATCH", "/api/vehicles/v1", json.dumps({"rate_hz": 50 + i % 2}))
             for i in range(20)]
    for name, samples in (("GET /api/status", status), ("PATCH", patch)):
        ok = [s for s in samples if s is not None]
        med = f"{1000 * statistics.median(ok):.1f}" if ok else "–"
        mx = f"{1000 * max(ok):.1f}" if ok else "–"
        rows.append(f"| {label} | {name} | {med} ms | {mx} ms | {len(samples) - len(ok)} |")


def main():
    binary = sys.argv[1]
    label = sys.argv[2] if len(sys.argv) > 2 else os.path.basename(binary)
    work = tempfile.mkdtemp(prefix="web-crowd-")
    port = free_port()
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    udp.bind(("127.0.0.1", 0))
    config = os.path.join(work, "c.toml")
    with open(config, "w") as f:
        f.write(f'[mocap]\nsource = "sim://?bodies=1&rate_hz=240"\n[http]\nlisten = "127.0.0.1:{port}"\n'
                f'[[vehicle]]\nname = "v1"\nbody = "Body1"\n'
                f'link = "udp://127.0.0.1:{udp.getsockname()[1]}"\nsystem_id = 1\nprofile = "px4"\n'
                f'rate_hz = 50\n')
    bridge = subprocess.Popen([binary, "run", "--config", config], stderr=subprocess.DEVNULL,
                              env=dict(os.environ, MOCAPLINK_STATE_DIR=os.path.join(work, "s")))
    while timed(port, "GET", "/api/status") is None:
        if bridge.poll() is not None:
            sys.exit(f"mocaplink run exited with {bridge.returncode}")
        time.sleep(0.1)
    rows = []
    phase(port, f"{label}, alone", rows)

    stop = threading.Event()
    idle = []
    for _ in range(100):
        s = socket.create_connection(("127.0.0.1", port))
        s.sendall(b"GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\n")
        idle.append(s)

    def stream():
        try:
            conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
            conn.request("GET", "/api/events")
            response = conn.getresponse()
            while not stop.is_set() and response.fp.readline():
                pass
        except OSError:
            pass

    def slow():
        s = socket.create_connection(("127.0.0.1", port))
        for b in b"PATCH /api/vehicles/v1 HTTP/1.1\r\nHost: 127.0.0.1\r\n":
            if stop.is_set():
                break
            try:
                s.send(bytes([b]))
            except OSError:
                break
            time.sleep(1)
        s.close()

    threads = [threading.Thread(target=stream, daemon=True) for _ in range(8)]
    threads.append(threading.Thread(target=slow, daemon=True))
    for t in threads:
        t.start()
    time.sleep(1)
    phase(port, f"{label}, crowd", rows)
    stop.set()
    for s in idle:
        s.close()
    bridge.terminate()
    bridge.wait()
    print("\n".join(rows))


if __name__ == "__main__":
    main()
