#!/usr/bin/env python3
"""Read a schemathesis run's reports (scripts/openapi_checks.sh --fuzz) and say how deep it went.

1. The job specs: of the schema-valid (positive) `POST /v1/jobs` requests schemathesis generated,
   how many the server accepted (200/202), and the most frequent reasons for the others (the
   field errors of their problems, numbers stripped). A loose schema makes fuzzing shallow: most
   generated specs then die in validation and the solvers are never reached.
2. Requests answered by status, per phase.
3. `use_after_free` as this API defines deletion: a job deleted by `DELETE` answering 204 is never
   read back with a 2xx afterwards (the built-in check also counts a DELETE that cancels an
   unfinished job, 200/202, after which the job stays readable by design; it is excluded).

Usage: fuzz_report.py <report dir>   Exit status 1 when check 3 fails.
"""
import base64
import collections
import glob
import json
import re
import sys

report_dir = sys.argv[1]
ndjson = glob.glob(f"{report_dir}/ndjson-*.ndjson")
har = glob.glob(f"{report_dir}/har-*.json")
if not ndjson or not har:
    sys.exit(f"fuzz report: no ndjson/har report in {report_dir}")


def interactions(recorder):
    """(case, status, response text) of each request a scenario made."""
    cases = {k: v["value"] for k, v in recorder.get("cases", {}).items()}
    for case_id, items in recorder.get("interactions", {}).items():
        for item in items if isinstance(items, list) else [items]:
            response = item.get("response") or {}
            content = response.get("content")
            if isinstance(content, dict) and "$base64" in content:
                content = base64.b64decode(content["$base64"]).decode("utf-8", "replace")
            yield cases.get(case_id, {}), response.get("status_code"), content or ""


accepted, refused, reasons = collections.Counter(), collections.Counter(), collections.Counter()
by_phase = collections.defaultdict(collections.Counter)
for line in open(ndjson[0]):
    event = json.loads(line)
    (kind, body), = event.items()
    if kind != "ScenarioFinished":
        continue
    for case, status, response in interactions(body.get("recorder", {})):
        if status is None:
            continue
        by_phase[body.get("phase", "?")][f"{status // 100}xx"] += 1
        meta = case.get("meta") or {}
        positive = (meta.get("generation") or {}).get("mode") == "positive"
        if case.get("method") != "POST" or case.get("path") != "/v1/jobs" or not positive:
            continue
        phase = body.get("phase", "?")
        if status in (200, 202):
            accepted[phase] += 1
            continue
        refused[phase] += 1
        try:
            problem = json.loads(response or "{}")
        except (ValueError, TypeError):
            problem = {}
        errors = problem.get("errors") or [{"path": "", "message": problem.get("detail", str(status))}]
        for e in errors[:3]:
            path = re.sub(r"/\d+(?=/|$)", "/*", e.get("path", ""))
            message = re.sub(r"[-+]?\d[\d.e+-]*", "#", e.get("message", ""))[:90]
            reasons[f"{status} {problem.get('code', '')} {path}: {message}"] += 1

ok, total = sum(accepted.values()), sum(accepted.values()) + sum(refused.values())
share = ", ".join(f"{p} {accepted[p]} of {accepted[p] + refused[p]}" for p in sorted(set(accepted) | set(refused)))
print(f"fuzz: schema-valid job specs (POST /v1/jobs, positive): {ok} of {total} accepted "
      f"({100 * ok / max(1, total):.1f} %; {share}); the refused ones' most frequent reasons:")
for reason, n in reasons.most_common(8):
    print(f"  {n:5d} × {reason}")
for phase, counts in sorted(by_phase.items()):
    print(f"fuzz: {phase}: {sum(counts.values())} requests by status class {dict(sorted(counts.items()))}")

# 3. Read after a deletion (HAR: every request in order).
entries = json.load(open(har[0]))["log"]["entries"]
deleted, reads_after = {}, []
job = re.compile(r"/v1/jobs/([0-9a-fA-F-]{36})(/|$|\?)")
for i, e in enumerate(entries):
    m = job.search(e["request"]["url"])
    if not m:
        continue
    method, status, jid = e["request"]["method"], e["response"]["status"], m.group(1).lower()
    if method == "DELETE" and status == 204:
        deleted[jid] = i
    elif method == "POST" and jid in deleted:
        del deleted[jid]
    elif method == "GET" and jid in deleted and 200 <= status < 300:
        reads_after.append(f"{method} {e['request']['url']} → {status} after DELETE → 204")
if reads_after:
    print(f"fuzz: FAILED: {len(reads_after)} read(s) of deleted jobs succeeded, e.g. {reads_after[0]}")
    sys.exit(1)
print(f"fuzz: {len(deleted)} jobs deleted (204) and never read back")
