#!/usr/bin/env bash
# aoreplay record / trend / export against a real store: an SQLite file, or (mode postgresql) a
# real PostgreSQL server started from Debian's packages on loopback in a temporary data folder,
# as an unprivileged user (nobody when the test runs as root, as CI does), and stopped at the end.
# Nothing is mocked: the reports are one real `aoreplay run` on lavapipe and copies of it with
# their samples scaled (each copy a distinct report).
#   bash results_store_test.sh AOREPLAY CAPTURE WORK_DIR sqlite|postgresql
set -euo pipefail
aoreplay=${1:?aoreplay binary}
capture=${2:?capture folder}
work=${3:?work folder}
mode=${4:?sqlite or postgresql}
rm -rf "$work"
mkdir -p "$work"
work=$(cd "$work" && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }

# --- the store -------------------------------------------------------------------------------
pg_bin=
server_user=
if [ "$mode" = postgresql ]; then
  pg_bin=$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -1)
  [ -x "$pg_bin/initdb" ] || fail "no PostgreSQL server binaries under /usr/lib/postgresql (Debian: postgresql)"
  as_server() { "$@"; }
  if [ "$(id -u)" -eq 0 ]; then  # initdb and postgres refuse to run as root
    server_user=nobody
    as_server() { runuser -u "$server_user" -- "$@"; }
  fi
  # In /tmp: the server's user must reach its data folder, which the build tree may not let it.
  pg_dir=$(mktemp -d /tmp/aoreplay-pg.XXXXXX)
  [ -z "$server_user" ] || chown "$server_user" "$pg_dir"
  as_server "$pg_bin/initdb" -D "$pg_dir/data" -U aoreplay --auth=trust -E UTF8 >"$work/initdb.log" 2>&1 ||
    { cat "$work/initdb.log"; fail "initdb failed"; }
  port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  as_server "$pg_bin/pg_ctl" -D "$pg_dir/data" -l "$pg_dir/server.log" -w -t 60 \
    -o "-c listen_addresses=127.0.0.1 -p $port -k $pg_dir -c fsync=off" start >/dev/null ||
    { cat "$pg_dir/server.log"; fail "the PostgreSQL server did not start"; }
  trap 'as_server "$pg_bin/pg_ctl" -D "$pg_dir/data" -m fast -w stop >/dev/null 2>&1 || true; rm -rf "$pg_dir"' EXIT
  db="postgresql://aoreplay@127.0.0.1:$port/postgres"
  new_store() {  # a fresh database on the server, its URL in $db
    local name=$1
    psql "postgresql://aoreplay@127.0.0.1:$port/postgres" -qAt -c "CREATE DATABASE $name" >/dev/null
    db="postgresql://aoreplay@127.0.0.1:$port/$name"
  }
  sql() { psql "$db" -qAt -c "$1"; }
  echo "PostgreSQL $("$pg_bin/postgres" --version | awk '{print $3}') on 127.0.0.1:$port as ${server_user:-$(id -un)}"
else
  new_store() { db="$work/$1.sqlite"; }
  sql() { sqlite3 "$db" "$1"; }
fi

# --- reports ---------------------------------------------------------------------------------
"$aoreplay" run "$capture" --frames 0:2 --repeat 3 --warmup 1 --no-images --out "$work/base" >/dev/null
variant() {  # variant NAME FACTOR: a copy of the real report with every sample scaled
  python3 - "$work/base/report.json" "$work/reports/$1.json" "$2" <<'PY'
import json, sys
report = json.load(open(sys.argv[1]))
factor = float(sys.argv[3])
for p in report["passes"]:
    p["gpu_ms"]["samples"] = [s * factor for s in p["gpu_ms"]["samples"]]
report["gpu_ms_total_median"] *= factor
json.dump(report, open(sys.argv[2], "w"), indent=1)
PY
}
mkdir -p "$work/reports"
samples_of() {  # the samples record stores for these reports: every pass's and the total's
  python3 - "$@" <<'PY'
import json, sys
n = 0
for path in sys.argv[1:]:
    r = json.load(open(path))
    counts = [len(p["gpu_ms"]["samples"]) for p in r["passes"]]
    compute = [p for p in r["passes"] if p["name"] not in ("upload", "readback")]
    n += sum(counts) + (r["run"]["repeat"] * len(r["frames"]) if len(compute) >= 2 else 0)
print(n)
PY
}

# --- four processes at once ------------------------------------------------------------------
new_store concurrent
for k in 1 2 3 4; do
  for j in 1 2 3 4 5; do variant "p${k}r$j" "1.$k$j"; done
done
cp "$work/base/report.json" "$work/reports/shared.json"
pids=()
for k in 1 2 3 4; do
  (
    for j in 1 2 3 4 5; do
      "$aoreplay" record "$work/reports/p${k}r$j.json" --db "$db" --commit "commit$k" --ordinal "$k" --tag "writer=$k" >/dev/null
    done
    "$aoreplay" record "$work/reports/shared.json" --db "$db" --commit commit0 --ordinal 0 >/dev/null
  ) &
  pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid" || fail "a concurrent record failed"; done
expected_samples=$(samples_of "$work"/reports/p*.json "$work/reports/shared.json")
[ "$(sql 'SELECT COUNT(*) FROM runs')" -eq 21 ] || fail "runs: $(sql 'SELECT COUNT(*) FROM runs'), expected 21"
[ "$(sql 'SELECT COUNT(*) FROM commits')" -eq 5 ] || fail "commits: expected 5"
[ "$(sql 'SELECT COUNT(*) FROM series')" -eq 1 ] || fail "series: expected 1"
[ "$(sql 'SELECT COUNT(*) FROM samples')" -eq "$expected_samples" ] ||
  fail "samples: $(sql 'SELECT COUNT(*) FROM samples'), expected $expected_samples"
echo "4 processes recording at once: 21 runs, $expected_samples samples, nothing lost or doubled"

# --- a killed record leaves no partial run ---------------------------------------------------
variant kill1 2.01
variant kill2 2.02
set +e
AOREPLAY_TEST_KILL_AFTER=record-inserted "$aoreplay" record "$work/reports/kill1.json" "$work/reports/kill2.json" \
  --db "$db" --commit killed --ordinal 9 >/dev/null 2>&1
rc=$?
set -e
[ "$rc" -eq 137 ] || fail "the record to be killed exited $rc, not 137 (SIGKILL)"
[ "$(sql 'SELECT COUNT(*) FROM runs')" -eq 21 ] || fail "a killed record left runs behind"
[ "$(sql "SELECT COUNT(*) FROM commits WHERE sha = 'killed'")" -eq 0 ] || fail "a killed record left its commit"
[ "$(sql 'SELECT COUNT(*) FROM samples')" -eq "$expected_samples" ] || fail "a killed record left samples behind"
"$aoreplay" record "$work/reports/kill1.json" "$work/reports/kill2.json" --db "$db" --commit killed --ordinal 9 >/dev/null
[ "$(sql 'SELECT COUNT(*) FROM runs')" -eq 23 ] || fail "the record after the kill did not store both runs"
# Killed at random moments of a record of 30 reports (its length measured first): all or none.
batch() { files=(); for j in $(seq 1 30); do variant "$1_$j" "$2.$(printf %03d "$j")"; files+=("$work/reports/$1_$j.json"); done; }
batch timed 4
start=$(date +%s%N)
"$aoreplay" record "${files[@]}" --db "$db" --commit timed --ordinal 10 >/dev/null
length_ms=$(( ($(date +%s%N) - start) / 1000000 ))
RANDOM=26
killed_midway=0
for i in 1 2 3 4 5 6 7 8; do
  batch "rk$i" "5$i"
  before=$(sql 'SELECT COUNT(*) FROM runs')
  "$aoreplay" record "${files[@]}" --db "$db" --commit "random$i" --ordinal "$((10 + i))" >/dev/null 2>&1 &
  pid=$!
  delay_ms=$(( RANDOM % (length_ms + 1) ))
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  after=$(sql 'SELECT COUNT(*) FROM runs')
  [ "$after" -eq "$before" ] || [ "$after" -eq $((before + 30)) ] || fail "kill $i left $((after - before)) of 30 runs"
  [ "$after" -eq "$before" ] && killed_midway=$((killed_midway + 1))
  echo "killed after ${delay_ms} ms of a ${length_ms} ms record: $((after - before)) of 30 runs stored (all or none)"
done
echo "$killed_midway of 8 random kills landed before the commit"

# --- idempotence at the command line ---------------------------------------------------------
out=$("$aoreplay" record "$work/reports/p1r1.json" --db "$db" --commit commit1 --ordinal 1)
[[ "$out" == *"recorded 0 runs"*"1 already there"* ]] || fail "recording a report again: $out"
set +e
"$aoreplay" record "$work/reports/p1r1.json" --db "$db" --commit other --ordinal 77 >/dev/null 2>"$work/err.txt"
rc=$?
set -e
[ "$rc" -eq 2 ] && grep -q "already recorded for commit commit1" "$work/err.txt" || fail "a report for two commits: exit $rc"

# --- trend: a slowdown at commit s13, exit 1, JUnit; exports ---------------------------------
new_store history
for c in $(seq -w 1 24); do
  factor=$(python3 -c "import sys; c=int(sys.argv[1]); print((1.3 if c >= 13 else 1.0) * (1 + ((c * 37) % 11 - 5) / 1000 + c / 100000))" "$c")
  variant "h$c" "$factor"
  "$aoreplay" record "$work/reports/h$c.json" --db "$db" --commit "s$c" --ordinal "$((10#$c))" >/dev/null
done
set +e
"$aoreplay" trend --db "$db" --junit "$work/junit.xml" --json "$work/trend.json" --plot "$work/plots" >"$work/trend.txt"
rc=$?
set -e
cat "$work/trend.txt"
[ "$rc" -eq 1 ] || fail "trend on a slowdown exited $rc, not 1"
grep -q "first commit after the change: s13" "$work/trend.txt" || fail "trend did not name s13"
python3 - "$work/junit.xml" "$work/trend.json" "$work/plots" <<'PY' || fail "JUnit, JSON or plot"
import json, os, sys, xml.etree.ElementTree as ET
suite = ET.parse(sys.argv[1]).getroot().find("testsuite")
assert int(suite.get("failures")) >= 1, "no failing test case"
failed = [c.get("name") for c in suite.iter("testcase") if c.find("failure") is not None]
assert "total" in failed, failed
t = json.load(open(sys.argv[2]))
(s,) = t["series"]
assert s["new_slowdown"] and len(s["changes"]) == 1 and s["changes"][0]["first_commit"] == "s13", s["changes"]
plots = os.listdir(sys.argv[3])
assert plots == [s["fingerprint"][:12] + ".svg"], plots
root = ET.parse(os.path.join(sys.argv[3], plots[0])).getroot()
assert root.tag.endswith("svg")
PY
"$aoreplay" trend --db "$db" --since s13 >/dev/null || fail "trend since the change: no change in it, exit 0 expected"
"$aoreplay" export --db "$db" --format google-benchmark --commit s05 --out "$work/before.json" >/dev/null
"$aoreplay" export --db "$db" --format google-benchmark --commit s20 --out "$work/after.json" >/dev/null
"$aoreplay" export --db "$db" --format bencher --commit s20 --out "$work/bmf.json" >/dev/null
"$aoreplay" export --db "$db" --format otava --out "$work/otava.csv" >/dev/null
compare_py=/usr/share/benchmark/compare.py
if [ -f "$compare_py" ]; then
  # Debian's interpreter: compare.py needs python3-scipy, which is installed for it
  /usr/bin/python3 "$compare_py" benchmarks "$work/before.json" "$work/after.json" >"$work/compare_py.txt" ||
    fail "compare.py did not read the Google Benchmark export"
  grep -q "/gtao " "$work/compare_py.txt" || { cat "$work/compare_py.txt"; fail "compare.py shows no gtao"; }
  echo "compare.py read the exports: $(grep -c / "$work/compare_py.txt") lines"
fi
python3 - "$work/bmf.json" "$work/otava.csv" <<'PY' || fail "Bencher or Otava export"
import csv, json, sys
# Bencher Metric Format: { benchmark: { measure: { value, lower_value?, upper_value? } } }, numbers.
bmf = json.load(open(sys.argv[1]))
assert isinstance(bmf, dict) and bmf
for name, measures in bmf.items():
    assert isinstance(name, str) and isinstance(measures, dict) and measures, name
    for slug, m in measures.items():
        assert set(m) <= {"value", "lower_value", "upper_value"} and "value" in m, m
        assert all(isinstance(v, (int, float)) for v in m.values()), m
        assert m["lower_value"] <= m["value"] <= m["upper_value"], m
# Otava: a time column, then one numeric column per metric, a row per commit in time order.
rows = list(csv.DictReader(open(sys.argv[2])))
assert len(rows) == 24 and [r["commit"] for r in rows] == ["s%02d" % c for c in range(1, 25)], rows
metric = next(k for k in rows[0] if k.endswith("/total"))
assert float(rows[-1][metric]) > 1.25 * float(rows[0][metric])
PY
echo "trend named s13 (exit 1), JUnit, JSON, plot, Google Benchmark, Bencher and Otava exports checked"

# --- trend on a flat history: exit 0 ---------------------------------------------------------
new_store flat
for c in $(seq -w 1 24); do
  variant "f$c" "$(python3 -c "import sys; c=int(sys.argv[1]); print(1 + ((c * 37) % 11 - 5) / 1000 + c / 100000)" "$c")"
  "$aoreplay" record "$work/reports/f$c.json" --db "$db" --commit "f$c" --date "2026-01-$c" >/dev/null
done
"$aoreplay" trend --db "$db" >"$work/flat.txt" || { cat "$work/flat.txt"; fail "trend on a flat history exited 1"; }
grep -q "no change" "$work/flat.txt" || fail "flat history: no 'no change'"
echo "PASS ($mode)"
