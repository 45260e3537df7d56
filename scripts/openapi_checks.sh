#!/usr/bin/env bash
# Check openapi/openapi.json with standard outside tools (issue 10, defect 8):
#  1. generate a Python client with openapi-python-client and submit one job of every kind
#     through its typed request models (scripts/openapi_client_check.py);
#  2. with --fuzz SECONDS, run schemathesis against a live server and print the share of
#     generated job requests the server accepted and any server errors.
# Needs python3 with venv and access to PyPI; without them it says SKIPPED and exits 0.
# Usage: scripts/openapi_checks.sh [--fuzz SECONDS]   (from the repository root; builds tribod)
set -euo pipefail
fuzz=0
if [[ "${1:-}" == "--fuzz" ]]; then fuzz="${2:-60}"; fi
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$root/target/openapi-checks"
mkdir -p "$work"
venv="$work/venv"
packages=(openapi-python-client==0.29.1)
if [[ "$fuzz" != 0 ]]; then packages+=(schemathesis==4.32.5); fi
if ! { [[ -x "$venv/bin/python" ]] || python3 -m venv "$venv"; } \
   || ! "$venv/bin/pip" install -q "${packages[@]}" >"$work/pip.log" 2>&1; then
  echo "SKIPPED openapi checks: cannot install ${packages[*]} from PyPI (see $work/pip.log)"
  exit 0
fi
rm -rf "$work/client"
mkdir -p "$work/client"
(cd "$work/client" && "$venv/bin/openapi-python-client" generate --path "$root/openapi/openapi.json" \
  --meta none --output-path tribod_client >"$work/generate.log" 2>&1) || { cat "$work/generate.log"; exit 1; }
cargo build --quiet --manifest-path "$root/Cargo.toml"
db="$work/checks.db"
rm -f "$db" "$db-wal" "$db-shm"
"$root/target/debug/tribod" serve --addr 127.0.0.1:0 --database-url "$db" >"$work/server.out" 2>"$work/server.log" &
server=$!
trap 'kill $server 2>/dev/null || true' EXIT
for _ in $(seq 100); do grep -q "listening on" "$work/server.out" && break; sleep 0.1; done
base="$(sed -n 's/.*listening on \(http:[^ ]*\).*/\1/p' "$work/server.out")"
"$venv/bin/python" "$root/scripts/openapi_client_check.py" "$work/client" "$base"
if [[ "$fuzz" != 0 ]]; then
  rm -rf "$work/fuzz"
  "$venv/bin/schemathesis" run "$root/openapi/openapi.json" --url "$base" --checks all \
    --max-time "$fuzz" -w 2 --suppress-health-check all --report har --report-dir "$work/fuzz" \
    >"$work/fuzz.log" 2>&1 || true
  grep -E "generated|failures|passed|ST[0-9]+ " "$work/fuzz.log" | tail -8
  "$venv/bin/python" - "$work/fuzz" <<'PY'
import collections, glob, json, sys
har = json.load(open(glob.glob(sys.argv[1] + "/har-*.json")[0]))
codes = collections.Counter()
for e in har["log"]["entries"]:
    codes[(e["request"]["method"], e["request"]["url"].split("?")[0].endswith("/v1/jobs"), e["response"]["status"])] += 1
posts = {s: n for (m, jobs, s), n in codes.items() if m == "POST" and jobs}
accepted = posts.get(200, 0) + posts.get(202, 0)
errors = sum(n for (_, _, s), n in codes.items() if s >= 500)
print(f"schemathesis: {sum(codes.values())} requests, {errors} answered 5xx; POST /v1/jobs: "
      f"{accepted} of {sum(posts.values())} accepted ({100 * accepted / max(1, sum(posts.values())):.1f} %), by status {dict(sorted(posts.items()))}")
PY
fi
