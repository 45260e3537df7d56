#!/usr/bin/env python3
"""Slow-client probe (issue 40): many trickling clients against a running tribod, and the latency
of normal clients meanwhile. Standard library only.

    tribod serve --addr 127.0.0.1:8080 --database-url /tmp/probe.db &
    scripts/trickle_probe.py --url http://127.0.0.1:8080 --tricklers 1000 --interval 5 --duration 60

Half the tricklers send a request's headers, half a request's body (after complete headers), one
byte every --interval seconds; a trickler the server closes reconnects after --pause seconds.
Meanwhile a normal client sends GET /healthz and POST /v1/jobs (a tiny `hertz` job) every
--every seconds, each on a fresh connection. Prints the normal clients' latency (p50, p90, max)
and failures, and how long the server took to close the trickling bodies and headers (with the
status it answered them).
"""

import argparse
import asyncio
import json
import statistics
import time
from urllib.parse import urlparse


def parse_args():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--url", default="http://127.0.0.1:8080")
    p.add_argument("--tricklers", type=int, default=1000)
    p.add_argument("--interval", type=float, default=5.0, help="seconds between a trickler's bytes")
    p.add_argument("--pause", type=float, default=0.5, help="seconds before a closed trickler reconnects")
    p.add_argument("--duration", type=float, default=60.0, help="seconds of normal traffic")
    p.add_argument("--every", type=float, default=0.2, help="seconds between normal requests")
    return p.parse_args()


class Tally:
    def __init__(self):
        self.latencies = []  # seconds, normal requests that succeeded
        self.failures = []  # (what, detail)
        self.closed = {"headers": [], "body": []}  # (seconds open, first status line)
        self.connections = 0


async def trickler(host, port, body, interval, pause, stop, tally):
    if body:
        head = (b"POST /v1/jobs HTTP/1.1\r\nhost: probe\r\ncontent-type: application/json\r\n"
                b"content-length: 100000\r\n\r\n{")
        drip = b" "
    else:
        head = b"GET /healthz HTTP/1.1\r\nhost: probe\r\n"
        drip = b"x"
    while not stop.is_set():
        try:
            reader, writer = await asyncio.open_connection(host, port)
        except OSError:
            await asyncio.sleep(pause)
            continue
        tally.connections += 1
        opened = time.monotonic()
        first = b""
        try:
            writer.write(head)
            await writer.drain()
            while not stop.is_set():
                try:
                    data = await asyncio.wait_for(reader.read(4096), timeout=interval)
                except asyncio.TimeoutError:
                    writer.write(drip)
                    await writer.drain()
                    continue
                first = first or data
                if not data:
                    break
                # An answer: read on until the server closes.
        except (OSError, ConnectionError):
            pass
        if not stop.is_set():
            status = first.split(b"\r\n", 1)[0].decode(errors="replace") if first else "(closed, no answer)"
            tally.closed["body" if body else "headers"].append((time.monotonic() - opened, status))
        writer.close()
        await asyncio.sleep(pause)


async def request(host, port, raw):
    """One request on a fresh connection; (status, seconds)."""
    started = time.monotonic()
    reader, writer = await asyncio.open_connection(host, port)
    writer.write(raw)
    await writer.drain()
    answer = await reader.read()  # Connection: close
    writer.close()
    status = int(answer.split(b" ", 2)[1]) if answer.startswith(b"HTTP/1.1 ") else 0
    return status, time.monotonic() - started


async def normal_client(host, port, every, duration, tally):
    n = 0
    until = time.monotonic() + duration
    while time.monotonic() < until:
        n += 1
        body = json.dumps({"kind": "hertz", "spec": {"contact": "line", "load": 1000.0 + n, "length": 0.01,
                                                      "body_1": {"shape": "cylinder", "radius": 0.02},
                                                      "body_2": {"shape": "flat"}}}).encode()
        for what, raw, ok in [
            ("GET /healthz", b"GET /healthz HTTP/1.1\r\nhost: probe\r\nconnection: close\r\n\r\n", (200,)),
            ("POST /v1/jobs", b"POST /v1/jobs HTTP/1.1\r\nhost: probe\r\ncontent-type: application/json\r\n"
             b"connection: close\r\ncontent-length: " + str(len(body)).encode() + b"\r\n\r\n" + body, (200, 202)),
        ]:
            try:
                status, took = await asyncio.wait_for(request(host, port, raw), timeout=10)
                if status in ok:
                    tally.latencies.append(took)
                else:
                    tally.failures.append((what, f"status {status} after {took:.3f} s"))
            except (OSError, asyncio.TimeoutError) as e:
                tally.failures.append((what, repr(e)))
        await asyncio.sleep(every)


def summary(values):
    if not values:
        return "none"
    v = sorted(values)
    return (f"n {len(v)}, p50 {statistics.median(v) * 1e3:.1f} ms, p90 {v[int(0.9 * (len(v) - 1))] * 1e3:.1f} ms, "
            f"max {v[-1] * 1e3:.1f} ms")


async def main():
    args = parse_args()
    url = urlparse(args.url)
    host, port = url.hostname, url.port or 80
    tally = Tally()
    stop = asyncio.Event()
    tasks = [asyncio.create_task(trickler(host, port, i % 2 == 1, args.interval, args.pause, stop, tally))
             for i in range(args.tricklers)]
    await asyncio.sleep(2.0)
    print(f"{args.tricklers} tricklers (one byte every {args.interval} s) connected: {tally.connections} connections")
    await normal_client(host, port, args.every, args.duration, tally)
    stop.set()
    for t in tasks:
        t.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    print(f"normal clients during the trickle: {summary(tally.latencies)}; failures {len(tally.failures)}")
    for what, detail in tally.failures[:10]:
        print(f"  failed: {what}: {detail}")
    print(f"trickling connections opened: {tally.connections}")
    for kind, closed in tally.closed.items():
        statuses = {}
        for _, status in closed:
            statuses[status] = statuses.get(status, 0) + 1
        print(f"trickling {kind} closed by the server after: {summary([t for t, _ in closed])}; answers {statuses}")


if __name__ == "__main__":
    asyncio.run(main())
