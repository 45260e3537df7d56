#!/usr/bin/env python3
"""Fan-out benchmark (issue 44): one 40-case sweep on 1, 2 and 3 instances sharing PostgreSQL,
against the same sweep in-process; and the per-case overhead of the fan-out on tiny cases.

    cargo build --release --features test-kinds --bin tribod
    TRIBOD_TEST_POSTGRES_URL=postgres://root@127.0.0.1:5432/test python3 scripts/fan_out_bench.py
    python3 scripts/fan_out_bench.py --sqlite     # one SQLite instance: fan-out against in-process

Every instance runs 1 worker thread (`serve --workers 1` answers the API and solves; the others are
`tribod worker --workers 1`), so the speed-up is bounded by the machine's cores (2 here). CPU per
case is the user + system time of every tribod process (from /proc) over the sweep, divided by 40.
Each scenario gets a fresh database (created and dropped with psql).
"""
import json, os, subprocess, sys, tempfile, time, urllib.request, uuid

BIN = os.environ.get("TRIBOD_BIN", "target/release/tribod")
ADMIN = os.environ.get("TRIBOD_TEST_POSTGRES_URL", "")
TICK = os.sysconf("SC_CLK_TCK")


def db_url(name):
    base = ADMIN.rsplit("/", 1)[0]
    return f"{base}/{name}"


def psql(sql):
    subprocess.run(["psql", ADMIN, "-q", "-c", sql], check=True, stdout=subprocess.DEVNULL)


def start(kind, url, extra):
    if kind == "serve":
        p = subprocess.Popen([BIN, "serve", "--addr", "127.0.0.1:0", "--database-url", url, *extra],
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, env={**os.environ, "RUST_LOG": "warn"})
        line = p.stdout.readline()
        return p, line.strip().removeprefix("tribod listening on ")
    p = subprocess.Popen([BIN, "worker", "--database-url", url, "--log-format", "json", *extra],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env={**os.environ, "RUST_LOG": "info"})
    for line in p.stderr:
        if "tribod worker running" in line:
            break
    # keep draining
    import threading
    threading.Thread(target=lambda: [None for _ in p.stderr], daemon=True).start()
    return p, None


def cpu(pids):
    total = 0
    for pid in pids:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        total += int(fields[11]) + int(fields[12])
    return total / TICK


def call(method, url, body=None):
    data = json.dumps(body).encode() if body is not None else None
    req = urllib.request.Request(url, data=data, method=method, headers={"content-type": "application/json"})
    with urllib.request.urlopen(req) as r:
        return json.loads(r.read())


def run_sweep(base, job, pids):
    c0, t0 = cpu(pids), time.monotonic()
    jid = call("POST", f"{base}/v1/jobs?fresh=true", job)["id"]
    while True:
        j = call("GET", f"{base}/v1/jobs/{jid}")
        if j["status"] in ("succeeded", "failed", "canceled"):
            break
        time.sleep(0.02)
    wall, used = time.monotonic() - t0, cpu(pids) - c0
    assert j["status"] == "succeeded", j
    r = call("GET", f"{base}/v1/jobs/{jid}/result")
    return wall, used, r


def scenario(name, job, instances, threshold, workers=1):
    """`instances` tribod processes (1 serve + workers) on a fresh database, or SQLite if 0."""
    procs = []
    db = None
    try:
        extra = ["--workers", str(workers), "--fan-out-min-case-seconds", threshold]
        if instances == 0:
            tmp = tempfile.mkdtemp()
            p, base = start("serve", os.path.join(tmp, "bench.db"), extra)
            procs.append(p)
        else:
            db = f"tribod_bench_{uuid.uuid4().hex[:12]}"
            psql(f'CREATE DATABASE "{db}"')
            p, base = start("serve", db_url(db), extra)
            procs.append(p)
            for _ in range(instances - 1):
                procs.append(start("worker", db_url(db), extra)[0])
        wall, used, r = run_sweep(base, job, [p.pid for p in procs])
        n = len(r["cases"])
        who = sorted({c.get("instance") for c in r["cases"] if c.get("instance")})
        print(f"{name:<44} wall {wall:7.2f} s   CPU {used:7.2f} s = {1000 * used / n:7.1f} ms/case   cores used {used / wall:4.2f}   instances that solved: {len(who)}")
        sys.stdout.flush()
        return wall, used
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
        if db:
            psql(f'DROP DATABASE IF EXISTS "{db}" WITH (FORCE)')


def main():
    # The seed 000 finite-line nose point (33 × 65 grid): ≈ 0.5 s of one core in release.
    with open("examples/seed000_finite_nose.json") as f:
        case = json.load(f)
    heavy = {"kind": "sweep", "spec": {"kind": case["kind"], "base": case["spec"],
             "parameters": [{"path": "/lubricant/viscosity", "linspace": {"start": 0.12, "stop": 0.18, "num": 40}}]}}
    tiny = {"kind": "sweep", "spec": {"kind": "hertz",
            "base": {"contact": "line", "load": 5000.0, "length": 0.014,
                     "body_1": {"shape": "cylinder", "radius": 0.0255}, "body_2": {"shape": "cylinder", "radius": 0.02}},
            "parameters": [{"path": "/load", "linspace": {"start": 1000.0, "stop": 10000.0, "num": 40}}]}}
    if "--sqlite" in sys.argv:
        # One instance on one file: the fan-out buys the case cache and per-case restarts, not
        # cores (in-process sweeps use the instance's workers too); its price per case.
        print("# SQLite, one instance; 400 tiny cases (20-ms polling: ±0.05 ms per case)")
        tiny["spec"]["parameters"][0]["linspace"]["num"] = 400
        for w in (1, 2):
            t_in, _ = scenario(f"tiny, in-process (SQLite, {w} worker(s))", tiny, 0, "inf", w)
            t_fan, _ = scenario(f"tiny, fanned out (SQLite, {w} worker(s))", tiny, 0, "0", w)
            print(f"    fan-out overhead per case: {1000 * (t_fan - t_in) / 400:.2f} ms wall")
        for c in (0.02, 0.1):
            job = {"kind": "sweep", "spec": {"kind": "test_sleep", "base": {"seconds": c},
                   "parameters": [{"path": "/nonce", "values": list(range(40))}], "quantities": ["/slept_seconds"]}}
            one, _ = scenario(f"c = {c} s sleeping, in-process (SQLite, 2 workers)", job, 0, "inf", 2)
            two, _ = scenario(f"c = {c} s sleeping, fanned out (SQLite, 2 workers)", job, 0, "0", 2)
            print(f"    fanned out / in-process: {two / one:.2f}")
        base, _ = scenario("heavy, in-process (SQLite, 2 workers)", heavy, 0, "inf", 2)
        fan, _ = scenario("heavy, fanned out (SQLite, 2 workers)", heavy, 0, "0", 2)
        print(f"    fanned out / in-process: {fan / base:.2f}")
        return
    print("# per-case overhead: 40 hertz cases (microseconds each)")
    t_in, _ = scenario("tiny, in-process (SQLite, 1 worker)", tiny, 0, "inf")
    t_pg, _ = scenario("tiny, in-process (PostgreSQL, 1 instance)", tiny, 1, "inf")
    t_fan, _ = scenario("tiny, fanned out (PostgreSQL, 1 instance)", tiny, 1, "0")
    print(f"fan-out overhead per case: {1000 * (t_fan - t_pg) / 40:.1f} ms wall")
    if "--crossover" in sys.argv:
        # Sleeping cases (test builds: `test_sleep`) take no CPU, so the machine's load does not
        # blur the coordination cost: in-process on one instance against fanned out on two.
        print("# crossover: 40 sleeping cases of c seconds, 1 worker per instance")
        for c in (0.005, 0.02, 0.05, 0.1):
            job = {"kind": "sweep", "spec": {"kind": "test_sleep", "base": {"seconds": c},
                   "parameters": [{"path": "/nonce", "values": list(range(40))}], "quantities": ["/slept_seconds"]}}
            one, _ = scenario(f"c = {c} s, in-process (PostgreSQL, 1 instance)", job, 1, "inf")
            two, _ = scenario(f"c = {c} s, fanned out on 2 instances", job, 2, "0")
            print(f"    fanned out / in-process: {two / one:.2f}")
        return
    print("# 40 heavy cases")
    base, _ = scenario("heavy, in-process (SQLite, 1 worker)", heavy, 0, "inf")
    scenario("heavy, in-process (PostgreSQL, 1 instance)", heavy, 1, "inf")
    for n in (1, 2, 3):
        w, _ = scenario(f"heavy, fanned out on {n} instance(s)", heavy, n, "0")
        print(f"    speed-up against in-process: {base / w:.2f} (ceiling: {min(n, os.cpu_count())} cores)")


if __name__ == "__main__":
    main()
