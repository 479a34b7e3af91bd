#!/usr/bin/env python3
"""Load, abuse and fuzz test of `aecurve editor` (loopback only, bounded in count and time).

Run by .ci/run after the end-to-end test:  AECURVE=target/release/aecurve python3 e2e/abuse_test.py

1. 200 concurrent normal requests: all answered, p50/p99 latency reported.
2. 300 connections holding half a header: a normal request still answers within 1 s.
3. Cross-site requests (text/plain, a form, another Origin, another Host) are refused.
4. A request over its time budget gets a `timeout` error in time, and the server's memory
   grows by less than 100 MB over a batch of such requests.
5. Fuzz: arbitrary bytes, arbitrary JSON and random well-formed requests to /api: one JSON
   response each, no non-finite number, none slower than the time limit plus a margin.

Exits non-zero on the first failed check.
"""

import json
import os
import random
import socket
import statistics
import subprocess
import sys
import threading
import time

TIMEOUT_S = 2.0  # the editor's --timeout for this run
FAILURES = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


def start_editor():
    exe = os.environ.get("AECURVE", "target/release/aecurve")
    p = subprocess.Popen(
        [exe, "editor", "--port", "0", "--no-open", "--timeout", str(TIMEOUT_S)],
        stdout=subprocess.PIPE,
        text=True,
    )
    line = p.stdout.readline().strip()
    url = line.removeprefix("editor: ").removeprefix("http://").rstrip("/")
    host, port = url.rsplit(":", 1)
    return p, (host, int(port))


def request(addr, path, body, headers=None, timeout=30.0):
    """One HTTP/1.1 request on a fresh connection: (status, body text, seconds)."""
    if isinstance(body, str):
        body = body.encode()
    h = {"Host": f"{addr[0]}:{addr[1]}", "Content-Type": "application/json"}
    h.update(headers or {})
    head = f"POST {path} HTTP/1.1\r\n" + "".join(f"{k}: {v}\r\n" for k, v in h.items() if v is not None)
    head += f"Content-Length: {len(body)}\r\nConnection: close\r\n\r\n"
    t = time.perf_counter()
    with socket.create_connection(addr, timeout=timeout) as s:
        s.sendall(head.encode() + body)
        chunks = []
        while True:
            try:
                c = s.recv(65536)
            except (ConnectionResetError, socket.timeout):
                break
            if not c:
                break
            chunks.append(c)
    secs = time.perf_counter() - t
    text = b"".join(chunks).decode("utf-8", "replace")
    try:
        status = int(text.split(" ", 2)[1])
    except (IndexError, ValueError):
        status = 0
    body_text = text.split("\r\n\r\n", 1)[1] if "\r\n\r\n" in text else ""
    return status, body_text, secs


def rss_kb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


NORMAL = json.dumps({"id": 1, "op": "lac.segment", "alpha": 0.5, "control": [[0, 0], [4, 0], [6, 3]]})


def load(addr):
    lat, ok = [], [0]
    lock = threading.Lock()

    def one():
        st, body, secs = request(addr, "/api", NORMAL)
        with lock:
            lat.append(secs)
            if st == 200 and '"ok":true' in body:
                ok[0] += 1

    threads = [threading.Thread(target=one) for _ in range(200)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    lat.sort()
    p50, p99 = statistics.median(lat), lat[int(0.99 * (len(lat) - 1))]
    print(f"     200 concurrent requests: {ok[0]} answered, p50 {p50 * 1e3:.1f} ms, p99 {p99 * 1e3:.1f} ms")
    check(ok[0] == 200, "200 concurrent normal requests all answered")


def hostile(addr):
    held = []
    for _ in range(300):
        try:
            s = socket.create_connection(addr, timeout=5)
            s.sendall(b"GET / HTTP/1.1\r\nHo")
            held.append(s)
        except OSError:
            break
    st, body, secs = request(addr, "/api", NORMAL)
    print(f"     {len(held)} connections holding half a header; a normal request: {st} in {secs * 1e3:.1f} ms")
    check(st == 200 and secs < 1.0, "a normal request answers within 1 s among held connections")
    for s in held:
        s.close()


def cross_site(addr):
    cases = [
        ("text/plain body", {"Content-Type": "text/plain"}, 415),
        ("form body", {"Content-Type": "application/x-www-form-urlencoded"}, 415),
        ("another Origin", {"Origin": "http://evil.example"}, 403),
        ("another Host (DNS rebinding)", {"Host": f"evil.example:{addr[1]}"}, 421),
    ]
    for name, headers, want in cases:
        for path in ["/api", "/api/region", "/api/export"]:
            st, _, _ = request(addr, path, NORMAL, headers)
            if st != want:
                check(False, f"cross-site {name} on {path}: {st}, want {want}")
                return
    check(True, "cross-site requests refused (415 text/plain and forms, 403 other origins, 421 other hosts)")


def over_budget(p, addr):
    # 16 points: the most exact mode takes (seconds each), far over the editor's 5 s.
    pts = [[i, (i * 37 % 11) / 3.0] for i in range(16)]
    slow = json.dumps({"id": 9, "op": "spline.pseudo_elastic", "mode": "exact", "points": pts})
    before = rss_kb(p.pid)
    worst = 0.0
    kinds = set()
    for _ in range(6):
        st, body, secs = request(addr, "/api", slow)
        worst = max(worst, secs)
        try:
            kinds.add(json.loads(body).get("error", {}).get("kind"))
        except ValueError:
            kinds.add("unparsable")
    # Cancellation: the timed-out work stopped at its deadline, so the slots are free.
    st, body, secs = request(addr, "/api", NORMAL)
    print(f"     right after them, a normal request: {st} in {secs * 1e3:.1f} ms")
    check(st == 200 and '"ok":true' in body and secs < 0.5,
          "timed-out work is cancelled: a normal request right after answers within 0.5 s")
    # A big request within the size limits, several times.
    big = json.dumps({"id": 10, "op": "lac.fit", "points": [[i, (i % 97) * 0.01] for i in range(20000)]})
    for _ in range(3):
        request(addr, "/api", big)
    after = rss_kb(p.pid)
    grew = (after - before) / 1024
    print(f"     over-budget requests: kinds {sorted(k for k in kinds if k)}, slowest {worst:.2f} s; memory {before // 1024} -> {after // 1024} MB")
    check(kinds == {"timeout"} and worst < TIMEOUT_S + 1.0, "requests over the time budget get a timeout error in time")
    check(grew < 100, f"memory grows by less than 100 MB ({grew:.0f} MB)")


def fuzz(addr, n=1500):
    rnd = random.Random(2026)
    ops = ["bezier.curvature_monotone", "lac.point", "lac.segment", "lac.inflection_segment",
           "lcg.estimate", "lac.rational_approx", "spline.pseudo_elastic", "lac.fit", "sketch.fit",
           "sketch.contour", "outline.fix"]

    def num():
        return rnd.choice([0, 1, -1, 0.5, 1e-300, 1e300, -1e308, 3.7, rnd.uniform(-10, 10), rnd.uniform(-1e6, 1e6)])

    def pts(k):
        return [[num(), num()] for _ in range(k)]

    def value(depth=0):
        c = rnd.randrange(7 if depth < 3 else 4)
        if c == 0:
            return num()
        if c == 1:
            return rnd.choice(["", "x", "exact", "table", "distance", "paper", "\u00e9\u6f22"])
        if c == 2:
            return rnd.choice([True, False, None])
        if c == 3:
            return rnd.randrange(-3, 30)
        if c == 4:
            return [value(depth + 1) for _ in range(rnd.randrange(5))]
        if c == 5:
            return pts(rnd.randrange(0, 12))
        return {rnd.choice(["alpha", "control", "points", "theta", "lambda", "weights", "mode"]): value(depth + 1)
                for _ in range(rnd.randrange(4))}

    def well_formed():
        op = rnd.choice(ops)
        r = {"id": rnd.randrange(1000), "op": op}
        if op in ("lac.segment", "lac.rational_approx"):
            r.update(alpha=rnd.uniform(-4, 4), control=pts(3))
        elif op == "lac.point":
            r.update(alpha=rnd.uniform(-4, 4), **{"lambda": rnd.uniform(0, 2)}, theta=[rnd.uniform(-2, 2)])
        elif op == "lac.inflection_segment":
            r.update(control=pts(3))
        elif op == "bezier.curvature_monotone":
            r.update(control_points=pts(rnd.randrange(2, 8)))
        elif op == "spline.pseudo_elastic":
            r.update(points=pts(rnd.randrange(2, 20)))
        elif op == "outline.fix":
            p = pts(3 * rnd.randrange(1, 6) + 1)
            r.update(segments=[{"control_points": p[k:k + 4]} for k in range(0, len(p) - 3, 3)],
                     closed=rnd.random() < 0.5, tolerance=num(), grid=rnd.choice([0, 1, num()]))
        else:
            r.update(points=[[i + rnd.uniform(0, 0.5), rnd.uniform(-3, 3)] for i in range(rnd.randrange(4, 60))])
            if op == "sketch.contour":
                r.update(closed=rnd.choice([True, False, None]))
        return json.dumps(r)

    answered, bad, slowest, timeouts = 0, [], (0.0, b""), []
    for i in range(n):
        kind = i % 3
        if kind == 0:
            body = bytes(rnd.randrange(256) for _ in range(rnd.randrange(1, 200)))
        elif kind == 1:
            v = value()
            if isinstance(v, dict) and rnd.random() < 0.7:
                v["op"] = rnd.choice(ops + ["x"])
            body = json.dumps(v).encode()
        else:
            body = well_formed().encode()
        st, text, secs = request(addr, "/api", body)
        if secs > slowest[0]:
            slowest = (secs, body[:300])
        if '"timeout"' in text:
            timeouts.append(body[:300])
        ok = st == 200
        try:
            v = json.loads(text, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
            ok = ok and isinstance(v, dict) and ("ok" in v)
        except ValueError:
            ok = False
        if ok:
            answered += 1
        elif len(bad) < 5:
            bad.append((st, body[:80], text[:200]))
    print(f"     fuzz: {n} requests, {answered} answered with one JSON response, {len(timeouts)} timed out, slowest {slowest[0]:.2f} s: {slowest[1][:160]!r}")
    for b in bad:
        print(f"     unanswered: {b}")
    check(answered == n, "fuzz: every request gets one finite JSON response")
    check(slowest[0] < TIMEOUT_S + 1.0, "fuzz: no request over its time budget")


def main():
    p, addr = start_editor()
    try:
        load(addr)
        hostile(addr)
        cross_site(addr)
        over_budget(p, addr)
        fuzz(addr)
    finally:
        p.kill()
        p.wait()
    if FAILURES:
        print(f"{len(FAILURES)} abuse checks failed")
        sys.exit(1)
    print("all abuse checks passed")


if __name__ == "__main__":
    main()
