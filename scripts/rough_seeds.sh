#!/usr/bin/env bash
# Issue 40: run examples/rough_contact_seed001.json with surface.seed = 1..N through a tribod binary;
# print how many converged and the wall times (total, and median of converged / failed runs).
# Usage: scripts/rough_seeds.sh target/release/tribod [N=100] [repository root=.]
set -euo pipefail
bin="${1:?tribod binary}"; n="${2:-100}"; root="${3:-.}"
work="$(mktemp -d)"; trap 'rm -rf "$work"' EXIT
: > "$work/times"
for seed in $(seq 1 "$n"); do
  python3 - "$root/examples/rough_contact_seed001.json" "$seed" > "$work/spec.json" <<'PY'
import json, sys
spec = json.load(open(sys.argv[1])); spec["spec"]["surface"]["seed"] = int(sys.argv[2]); print(json.dumps(spec))
PY
  t0=$(date +%s.%N)
  if "$bin" run "$work/spec.json" --compact > "$work/out.json" 2> "$work/err.json"; then status=ok; else
    status=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1])).get("code"))' "$work/err.json"); fi
  t1=$(date +%s.%N)
  echo "$seed $status $t0 $t1" >> "$work/times"
done
python3 - "$work/times" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
t = lambda r: float(r[3]) - float(r[2])
ok = [t(r) for r in rows if r[1] == "ok"]; bad = [r for r in rows if r[1] != "ok"]
print(f"seeds 1..{len(rows)}: {len(ok)} converged, {len(bad)} failed ({' '.join(r[0] + ':' + r[1] for r in bad) or 'none'})")
print(f"wall {sum(map(t, rows)):.1f} s; median per run: converged {statistics.median(ok) if ok else float('nan'):.2f} s, "
      f"failed {statistics.median(map(t, bad)) if bad else float('nan'):.2f} s")
PY
