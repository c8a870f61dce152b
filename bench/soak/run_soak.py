#!/usr/bin/env python3
"""bench/soak: hours, not minutes (issue 15).

`mocaplink run` bridges a Vicon DataStream emulator (`mocaplink serve --protocol vicon --from sim`,
50 bodies at 240 Hz) to 50 UDP vehicles (bench/e2e/e2e_receivers, rate_hz 240) for an hour,
inside a network namespace this script makes (`unshare -n`, root), with faults injected:

* the mocap server is killed and restarted every 5 minutes (at 5:00, 10:00, ...);
* vehicle 1's link (bound to 127.0.0.2) is black-holed for 30 s every 10 minutes (at 2:00, 12:00,
  ...): with `tc netem loss 100%` on loopback when the kernel has sch_netem and sch_prio, else
  with an `ip rule ... blackhole` for 127.0.0.2 (sends then fail at once instead of vanishing);
* dashboard clients come and go: every few seconds a client reads /api/status or holds the
  /api/events stream for 2-20 s.

Every minute it samples mocaplink's RSS and CPU (/proc), the frames the bridge received
(/api/status station.frames), the ODOMETRY the vehicles received (all, and vehicle 1) and their
latency (receive − time_usec, as bench/e2e), writes one CSV row and finally plots the CSV with
gnuplot (Debian gnuplot-nox; `scripts/setup --bench`).

Usage (root): bench/soak/run_soak.py MOCAPLINK E2E_RECEIVERS [--minutes 60] [--vehicles 50]
              [--rate-hz 240] [--out DIR] [--plot docs/img/soak.png]
"""
import argparse
import http.client
import json
import os
import random
import signal
import subprocess
import sys
import threading
import time

SERVER_PORT = 8801
HTTP_PORT = 8080
BLACKHOLED = "127.0.0.2"


def run(*cmd, check=True):
    return subprocess.run(cmd, check=check, capture_output=True, text=True)


class Blackhole:
    """Black-holes datagrams to 127.0.0.2 (vehicle 1) on demand."""

    def __init__(self):
        self.method = "netem"
        try:
            run("tc", "qdisc", "add", "dev", "lo", "root", "handle", "1:", "prio", "bands", "4",
                "priomap", *(["0"] * 16))
            run("tc", "qdisc", "add", "dev", "lo", "parent", "1:4", "handle", "40:", "netem",
                "loss", "100%")
        except subprocess.CalledProcessError:
            run("tc", "qdisc", "del", "dev", "lo", "root", check=False)
            self.method = "ip rule blackhole"
            # The local table is consulted first (rule 0): move it behind the black-hole rule.
            run("ip", "rule", "add", "pref", "100", "lookup", "local")
            run("ip", "rule", "del", "pref", "0")

    def set(self, on):
        if self.method == "netem":
            if on:
                run("tc", "filter", "add", "dev", "lo", "parent", "1:", "protocol", "ip", "prio",
                    "1", "u32", "match", "ip", "dst", BLACKHOLED + "/32", "flowid", "1:4")
            else:
                run("tc", "filter", "del", "dev", "lo", "parent", "1:", "prio", "1")
        elif on:
            run("ip", "rule", "add", "pref", "10", "to", BLACKHOLED + "/32", "blackhole")
        else:
            run("ip", "rule", "del", "pref", "10")


def get_json(path, timeout=5.0):
    conn = http.client.HTTPConnection("127.0.0.1", HTTP_PORT, timeout=timeout)
    try:
        conn.request("GET", path)
        response = conn.getresponse()
        return json.loads(response.read())
    finally:
        conn.close()


def dashboard_clients(stop, stats):
    """Clients that come and go: a status read, or an event stream held for a while."""
    rng = random.Random(15)
    while not stop.is_set():
        try:
            if rng.random() < 0.5:
                get_json("/api/status")
            else:
                conn = http.client.HTTPConnection("127.0.0.1", HTTP_PORT, timeout=5)
                conn.request("GET", "/api/events")
                response = conn.getresponse()
                until = time.monotonic() + rng.uniform(2, 20)
                while time.monotonic() < until and not stop.is_set():
                    if not response.fp.readline():
                        break
                conn.close()
            stats["dashboard_ok"] += 1
        except (OSError, http.client.HTTPException, ValueError) as e:
            stats["dashboard_failed"] += 1
            # When and why, in summary.json: a failure near the end may be the bridge stopping.
            stats.setdefault("dashboard_errors", []).append(f"{time.strftime('%H:%M:%S')} {e!r}")
        stop.wait(rng.uniform(1, 8))


def proc_sample(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    ticks = int(fields[11]) + int(fields[12])  # utime + stime
    rss_kb = 0
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                rss_kb = int(line.split()[1])
    return ticks / os.sysconf("SC_CLK_TCK"), rss_kb / 1024.0


def start_server(binary, bodies, rate_hz, log):
    server = subprocess.Popen(
        [binary, "serve", "--protocol", "vicon", "--from", f"sim://?bodies={bodies}",
         "--rate", str(rate_hz), "--listen", f"127.0.0.1:{SERVER_PORT}"],
        stdout=log, stderr=log)
    return server


def plot(csv_path, png_path, title):
    script = f"""
set terminal png size 1200,900 font ",10"
set output "{png_path}"
set datafile separator ","
set key autotitle columnhead
set multiplot layout 4,1 title "{title}"
set xlabel "minute"
set grid
set ylabel "RSS (MiB)"
set yrange [0:*]
plot "{csv_path}" using 1:2 with linespoints title "RSS"
set ylabel "CPU (% of one core)"
plot "{csv_path}" using 1:3 with linespoints title "CPU"
set ylabel "loss (%)"
set yrange [0:*]
plot "{csv_path}" using 1:7 with linespoints title "vehicles 2-50", \\
     "{csv_path}" using 1:9 with linespoints title "vehicle 1 (black-holed 30 s every 10 min)"
set ylabel "latency (ms)"
set logscale y
set yrange [*:*]
plot "{csv_path}" using 1:10 with linespoints title "p50", \\
     "{csv_path}" using 1:11 with linespoints title "p99"
unset multiplot
"""
    subprocess.run(["gnuplot"], input=script, text=True, check=True)


def soak(args):
    run("ip", "link", "set", "lo", "up")
    blackhole = Blackhole()
    os.makedirs(args.out, exist_ok=True)
    log = open(os.path.join(args.out, "processes.log"), "w")
    server = start_server(args.mocaplink, args.vehicles, args.rate_hz, log)
    config = os.path.join(args.out, "soak.toml")
    receivers = subprocess.Popen(
        [args.receivers, "--vehicles", str(args.vehicles), "--bodies", str(args.vehicles),
         "--rate-hz", str(args.rate_hz), "--config", config, "--report-s", "60",
         "--idle-s", "120", "--first-address", BLACKHOLED,
         "--source", f"vicon://127.0.0.1:{SERVER_PORT}", "--http", f"127.0.0.1:{HTTP_PORT}"],
        stdout=subprocess.PIPE, stderr=log, text=True)
    assert receivers.stdout.readline().strip() == "ready"
    env = dict(os.environ, MOCAPLINK_STATE_DIR=os.path.join(args.out, "state"),
               MOCAPLINK_SUMMARY_S="3600")
    bridge = subprocess.Popen([args.mocaplink, "run", "--config", config], stdout=log,
                              stderr=log, env=env)
    start = time.monotonic()
    stop = threading.Event()
    stats = {"dashboard_ok": 0, "dashboard_failed": 0}
    clients = threading.Thread(target=dashboard_clients, args=(stop, stats), daemon=True)
    clients.start()

    csv_path = os.path.join(args.out, "soak.csv")
    csv = open(csv_path, "w")
    csv.write("minute,rss_mib,cpu_pct,frames,odometry,expected,loss_pct,vehicle1,vehicle1_loss_pct,"
              "p50_ms,p99_ms,max_ms,faults\n")
    last_cpu, _ = proc_sample(bridge.pid)
    last_frames = 0
    faults = []
    for minute in range(1, args.minutes + 1):
        # Faults inside this minute, by its start offset in seconds.
        m0 = (minute - 1) * 60
        if minute > 1 and (minute - 1) % 5 == 0:
            server.terminate()
            server.wait()
            server = start_server(args.mocaplink, args.vehicles, args.rate_hz, log)
            faults.append("server restart")
        if (minute - 1) % 10 == 2:
            while time.monotonic() - start < m0:
                time.sleep(0.2)
            blackhole.set(True)
            faults.append("vehicle 1 black-holed 30 s")
            while time.monotonic() - start < m0 + 30:
                time.sleep(0.2)
            blackhole.set(False)
        line = receivers.stdout.readline()
        if not line:
            break
        interval = json.loads(line)
        cpu, rss = proc_sample(bridge.pid)
        try:
            frames_total = get_json("/api/status", timeout=20)["station"]["frames"]
        except (OSError, http.client.HTTPException, ValueError, KeyError) as e:
            print(f"minute {minute}: /api/status failed: {e!r}", file=sys.stderr)
            stats["status_failed"] = stats.get("status_failed", 0) + 1
            frames_total = last_frames
        frames = frames_total - last_frames
        last_frames = frames_total
        others = interval["odometry"] - interval["vehicle1"]
        expected = frames * (args.vehicles - 1)
        loss = 100.0 * (1 - others / expected) if expected else 0.0
        v1_loss = 100.0 * (1 - interval["vehicle1"] / frames) if frames else 0.0
        lat = interval["latency_us"]
        csv.write(f"{minute},{rss:.1f},{100 * (cpu - last_cpu) / 60:.1f},{frames},"
                  f"{interval['odometry']},{expected},{loss:.3f},{interval['vehicle1']},"
                  f"{v1_loss:.3f},{lat['p50'] / 1000:.3f},{lat['p99'] / 1000:.3f},"
                  f"{lat['max'] / 1000:.3f},{'; '.join(faults)}\n")
        csv.flush()
        last_cpu = cpu
        faults = []
    stop.set()
    bridge.send_signal(signal.SIGTERM)
    bridge.wait()
    server.terminate()
    server.wait()
    receivers.terminate()
    receivers.wait()
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(dict(stats, blackhole=blackhole.method, minutes=args.minutes,
                       vehicles=args.vehicles, rate_hz=args.rate_hz), f)
    title = (f"soak: {args.vehicles} vehicles x {args.rate_hz:g} Hz, mocap server restarted every "
             f"5 min, vehicle 1 black-holed 30 s every 10 min ({blackhole.method})")
    if args.plot:
        plot(csv_path, args.plot, title)
    print(open(csv_path).read())
    print(json.dumps(stats))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mocaplink")
    parser.add_argument("receivers")
    parser.add_argument("--minutes", type=int, default=60)
    parser.add_argument("--vehicles", type=int, default=50)
    parser.add_argument("--rate-hz", type=float, default=240.0)
    parser.add_argument("--out", default="/tmp/mocaplink-soak")
    parser.add_argument("--plot", default="")
    args = parser.parse_args()
    args.mocaplink = os.path.abspath(args.mocaplink)
    args.receivers = os.path.abspath(args.receivers)
    if args.plot:
        args.plot = os.path.abspath(args.plot)
    if os.environ.get("MOCAPLINK_SOAK_NETNS") != "1":
        if os.geteuid() != 0:
            sys.exit("bench/soak: needs root (it makes a network namespace with unshare -n)")
        env = dict(os.environ, MOCAPLINK_SOAK_NETNS="1")
        sys.exit(subprocess.run(["unshare", "-n", sys.executable, *sys.argv], env=env).returncode)
    soak(args)


if __name__ == "__main__":
    main()
