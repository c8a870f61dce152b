#!/usr/bin/env python3
"""bench/web_crowd: how long the operator waits for the dashboard while a crowd holds connections.

Starts `mocaplink run` (sim:// source, one vehicle to a local UDP port, dashboard on a free port),
then times GET /api/status and PATCH /api/vehicles/v1 taking turns 20 ms apart (each on a new
connection from 127.0.0.1; 200 of each by default, after 10 of each not counted), first alone and then with a crowd kept up for the whole phase:
100 idle connections (a half-sent request each, from 127.0.0.2-127.0.0.5, 25 per address, within
the per-address cap; reopened whenever the server closes one), the 8 allowed /api/events streams
and a client sending one byte per second (reconnecting when the request deadline cuts it off).
Prints one markdown row per phase and request: median, p99 and max answer time, the ratio of the
crowd's median and p99 to the same run's alone figures, and requests not answered within 30 s;
then the server's own counters (/api/status "http").

Usage: bench/web_crowd/run_web_crowd.py MOCAPLINK [LABEL] [--samples N]
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


def percentile(sorted_samples, p):
    index = min(len(sorted_samples) - 1, max(0, round(p / 100 * len(sorted_samples) + 0.5) - 1))
    return sorted_samples[index]


def phase(port, samples):
    """{request: [seconds or None]}: `samples` GETs of /api/status and as many PATCHes, taking
    turns 20 ms apart, so that a phase lasts long enough (about 10 s for 200) for the server's
    idle limit and request deadline to act on the crowd while it is measured."""
    results = {"GET /api/status": [], "PATCH": []}
    for i in range(samples):
        results["GET /api/status"].append(timed(port, "GET", "/api/status"))
        time.sleep(0.02)
        results["PATCH"].append(
            timed(port, "PATCH", "/api/vehicles/v1", json.dumps({"rate_hz": 50 + i % 2})))
        time.sleep(0.02)
    return results


def rows(label, results, baseline=None):
    out = []
    for name, samples in results.items():
        ok = sorted(s for s in samples if s is not None)
        if not ok:
            out.append(f"| {label} | {name} | – | – | – | – | {len(samples)} |")
            continue
        med, p99 = statistics.median(ok), percentile(ok, 99)
        ratio = "1 × / 1 ×"
        if baseline is not None:
            base = sorted(s for s in baseline[name] if s is not None)
            ratio = (f"{med / statistics.median(base):.1f} × / "
                     f"{p99 / percentile(base, 99):.1f} ×")
        out.append(f"| {label} | {name} | {1000 * med:.2f} ms | {1000 * p99:.2f} ms | "
                   f"{1000 * ok[-1]:.1f} ms | {ratio} | {len(samples) - len(ok)} |")
    return out


def connect_from(port, address):
    s = socket.socket()
    s.bind((address, 0))
    s.connect(("127.0.0.1", port))
    return s


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--samples")]
    samples = 200
    for a in sys.argv[1:]:
        if a.startswith("--samples="):
            samples = int(a.split("=", 1)[1])
    binary = args[0]
    label = args[1] if len(args) > 1 else os.path.basename(binary)
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
    phase(port, 10)  # warm-up, not counted
    alone = phase(port, samples)

    stop = threading.Event()
    reopened = {"idle": 0, "slow": 0}

    def idle(address):
        # A half-sent request; when the server closes it (idle limit), the next one comes.
        while not stop.is_set():
            try:
                with connect_from(port, address) as s:
                    s.sendall(b"GET /api/status HTTP/1.1\r\nHost: 127.0.0.1\r\n")
                    s.settimeout(1)
                    while not stop.is_set():
                        try:
                            if not s.recv(4096):
                                break
                        except socket.timeout:
                            continue
                if not stop.is_set():
                    reopened["idle"] += 1
            except OSError:
                time.sleep(0.1)

    def stream():
        while not stop.is_set():
            try:
                conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
                conn.request("GET", "/api/events")
                response = conn.getresponse()
                while not stop.is_set() and response.fp.readline():
                    pass
                conn.close()
            except OSError:
                time.sleep(0.1)

    def slow():
        request = b"PATCH /api/vehicles/v1 HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: " + b"a" * 1000
        while not stop.is_set():
            try:
                with connect_from(port, "127.0.0.1") as s:
                    for b in request:
                        if stop.is_set():
                            break
                        s.send(bytes([b]))
                        time.sleep(1)
            except OSError:
                if not stop.is_set():
                    reopened["slow"] += 1

    threads = [threading.Thread(target=idle, args=(f"127.0.0.{2 + i % 4}",), daemon=True)
               for i in range(100)]
    threads += [threading.Thread(target=stream, daemon=True) for _ in range(8)]
    threads.append(threading.Thread(target=slow, daemon=True))
    for t in threads:
        t.start()
    time.sleep(1)
    crowd = phase(port, samples)
    counters = None
    try:
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=30)
        conn.request("GET", "/api/status")
        counters = json.loads(conn.getresponse().read()).get("http")
    except (OSError, ValueError):
        pass
    stop.set()
    bridge.terminate()
    bridge.wait()
    print(f"{samples} requests of each kind per phase, taking turns 20 ms apart\n")
    print("| build, phase | request | median | p99 | max | median / p99 vs alone | not answered in 30 s |")
    print("|---|---|---:|---:|---:|---:|---:|")
    print("\n".join(rows(f"{label}, alone", alone) + rows(f"{label}, crowd", crowd, alone)))
    print(f"\nserver counters after the crowd phase: {counters}; idle connections reopened "
          f"{reopened['idle']} times, slow client cut off {reopened['slow']} times")


if __name__ == "__main__":
    main()
