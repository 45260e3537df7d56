#!/usr/bin/env python3
"""Submit one job file, wait for it, print its key results with units, save a CSV and a plot.

    python3 clients/python/example.py examples/hertz_roller_on_cam.json [out_dir]

The server is TRIBOD_URL (default http://127.0.0.1:8080), with TRIBOD_API_TOKEN if it needs
one. Writes <out_dir>/<stem>-<table>.csv (the result's first table) and <out_dir>/<stem>-<plot>.svg
(its first plot); out_dir defaults to the current directory.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tribod_client import JobFailed, TribodError, format_quantity, from_env  # noqa: E402


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    path, out_dir = argv[1], (argv[2] if len(argv) > 2 else ".")
    stem = os.path.splitext(os.path.basename(path))[0]
    client = from_env()
    try:
        job = client.submit_file(path, wait=30)
        reused = " (reused: an identical spec ran before)" if job.get("reused") else ""
        print(f"job {job['id']}  {job['kind']}  {job.get('label', '')}{reused}")
        job = client.wait(job["id"], timeout=600)
        for w in job.get("warnings") or []:  # legal but implausible values (GET shows them)
            print(f"  warning {w['path']}: {w['message']}")
        print(f"status {job['status']}  (started {job.get('started_at')}, finished {job.get('finished_at')})")

        result = client.result(job["id"])
        print("key results:")
        for pointer, value, unit in client.key_results(job["kind"], result):
            print(f"  {pointer:<45} {format_quantity(value, unit)}")

        tables = client.kind(job["kind"]).get("tables") or []
        table = next((t for t in tables if result.get(t) is not None), None)
        if table:
            text = client.csv(job["id"], table)
            csv_path = os.path.join(out_dir, f"{stem}-{table}.csv")
            with open(csv_path, "w", encoding="utf-8") as f:
                f.write(text)
            lines = text.splitlines()
            print(f"wrote {csv_path}: {len(lines) - 1} rows; header: {lines[0][:100]}{'…' if len(lines[0]) > 100 else ''}")

        plots = client.plots(job["id"])
        if plots:
            svg = client.plot(job["id"], plots[0]["name"])
            svg_path = os.path.join(out_dir, f"{stem}-{plots[0]['name']}.svg")
            with open(svg_path, "wb") as f:
                f.write(svg)
            print(f"wrote {svg_path}: {plots[0]['title']} ({len(svg)} bytes; {len(plots)} plot{'' if len(plots) == 1 else 's'} in all)")
    except JobFailed as e:
        print(f"job failed: {e}", file=sys.stderr)
        return 1
    except TribodError as e:
        print(f"tribod: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
