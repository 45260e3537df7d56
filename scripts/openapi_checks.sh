#!/usr/bin/env bash
# Check openapi/openapi.json with standard outside tools (issue 10, defect 8; issue 40):
#  1. generate a Python client with openapi-python-client and submit one job of every kind
#     through its typed request models (scripts/openapi_client_check.py);
#  2. with --fuzz, run schemathesis against a live server: every phase (examples, coverage,
#     fuzzing, stateful), every check, a fixed seed and a bounded number of cases per operation,
#     then report how many schema-valid job specs the server accepted (scripts/fuzz_report.py).
#     Any failure schemathesis reports fails this script.
# Needs python3 with venv and access to PyPI; without them it says SKIPPED and exits 0.
# The Python tools live in a virtualenv under ~/.cache/tribod (TRIBOD_TOOLS_CACHE), one per set
# of pinned versions, so a second run on the same machine installs nothing.
# The server is TRIBOD_BIN when set (.ci/run passes the binary `cargo test` has just built, so
# this stage compiles nothing), else this builds tribod.
# Usage (from anywhere):
#   scripts/openapi_checks.sh [--fuzz] [--max-examples N] [--seed S] [--max-time SECONDS]
#   --max-examples: cases per operation and phase (default 50); --seed: default 20261122;
#   --max-time: a time budget instead (fuzzing and stateful repeat until it is spent).
set -euo pipefail
fuzz=0 examples=50 seed=20261122 max_time=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --fuzz) fuzz=1; if [[ "${2:-}" =~ ^[0-9]+$ ]]; then max_time="$2"; shift; fi ;;
    --max-examples) examples="$2"; shift ;;
    --seed) seed="$2"; shift ;;
    --max-time) max_time="$2"; shift ;;
    *) echo "usage: $0 [--fuzz] [--max-examples N] [--seed S] [--max-time SECONDS]" >&2; exit 2 ;;
  esac
  shift
done
root="$(cd "$(dirname "$0")/.." && pwd)"
work="$root/target/openapi-checks"
mkdir -p "$work"
packages=(openapi-python-client==0.29.1)
if [[ "$fuzz" != 0 ]]; then packages+=(schemathesis==4.32.5); fi
venv="${TRIBOD_TOOLS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/tribod}/venv-$(echo "${packages[*]}" | tr ' =' '_-')"
mkdir -p "$(dirname "$venv")"
if ! { [[ -x "$venv/bin/python" ]] || python3 -m venv "$venv"; } \
   || ! "$venv/bin/pip" install -q --timeout 20 --retries 1 "${packages[@]}" >"$work/pip.log" 2>&1; then
  echo "SKIPPED openapi checks: cannot install ${packages[*]} from PyPI (see $work/pip.log)"
  exit 0
fi
rm -rf "$work/client"
mkdir -p "$work/client"
(cd "$work/client" && "$venv/bin/openapi-python-client" generate --path "$root/openapi/openapi.json" \
  --meta none --output-path tribod_client >"$work/generate.log" 2>&1) || { cat "$work/generate.log"; exit 1; }
bin="${TRIBOD_BIN:-}"
if [[ -z "$bin" ]]; then
  cargo build --quiet --manifest-path "$root/Cargo.toml" --bin tribod
  bin="$root/target/debug/tribod"
fi
servers=()
# At exit: stop the servers and wait for them (a next run reuses the file names).
trap 'for p in "${servers[@]}"; do kill "$p" 2>/dev/null || true; done; wait' EXIT
# serve NAME ARGS...: a server on a free port with a fresh SQLite file; sets $base.
serve() {
  local name="$1"; shift
  local db="$work/$name.db"
  rm -f "$db" "$db-wal" "$db-shm"
  "$bin" serve --addr 127.0.0.1:0 --database-url "$db" --shutdown-grace 1 "$@" \
    >"$work/server-$name.out" 2>"$work/server-$name.log" &
  servers+=($!)
  for _ in $(seq 300); do grep -q "listening on" "$work/server-$name.out" && break; sleep 0.1; done
  base="$(sed -n 's/.*listening on \(http:[^ ]*\).*/\1/p' "$work/server-$name.out")"
  [[ -n "$base" ]] || { echo "tribod did not start within 30 s; $work/server-$name.log ends:"; tail -5 "$work/server-$name.log"; exit 1; }
}
serve checks
"$venv/bin/python" "$root/scripts/openapi_client_check.py" "$work/client" "$base"
[[ "$fuzz" != 0 ]] || exit 0

# The fuzzed server: one worker; accepted jobs stopped after 5 s and `Prefer: wait` after 1 s, so
# the run's length does not depend on which specs the generator happens to find solvable.
serve fuzz --workers 1 --job-timeout 5 --max-wait 1
rm -rf "$work/fuzz"
budget=(--max-examples "$examples")
if [[ -n "$max_time" ]]; then budget+=(--max-time "$max_time"); fi
started=$SECONDS
status=0
# `use_after_free` is replaced by fuzz_report.py's own reading: it takes any 2xx DELETE for a
# deletion, and DELETE of a queued or running job cancels it (200/202) and keeps it readable.
# One worker (-w 1): reproducible with the seed.
"$venv/bin/schemathesis" --config-file "$root/scripts/schemathesis.toml" run "$root/openapi/openapi.json" \
  --url "$base" --checks all --exclude-checks use_after_free \
  --phases examples,coverage,fuzzing,stateful --seed "$seed" "${budget[@]}" -w 1 \
  --generation-database none --suppress-health-check all --no-color \
  --report har,ndjson --report-dir "$work/fuzz" >"$work/fuzz.log" 2>&1 || status=$?
grep -E "^ *(✅|❌|🚫|⏭).*(Examples|Coverage|Fuzzing|Stateful)|passed|generated|ST[0-9]+ |Seed:" "$work/fuzz.log" | sed 's/^ */schemathesis: /' | tail -14
"$venv/bin/python" "$root/scripts/fuzz_report.py" "$work/fuzz" || status=1
echo "schemathesis: $((SECONDS - started)) s, seed $seed, ${examples} examples per operation and phase (log: $work/fuzz.log)"
if [[ "$status" != 0 ]]; then
  sed -n '/= \(ERRORS\|FAILURES\) =/,/= SUMMARY =/p' "$work/fuzz.log" | head -120
  echo "FAILED openapi fuzzing (see $work/fuzz.log)"
  exit 1
fi
