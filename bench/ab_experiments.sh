#!/usr/bin/env bash
# The many-run acceptance experiments of `aoreplay ab` (issue 19, "What it must show"), each kind
# repeated EXPERIMENTS times, every experiment one `ab` of ROUNDS rounds (2 x ROUNDS runs a side):
#   same    one build against itself: exit 0 in at least 19 of 20, every judged name `same` in at least 18
#   hog     the same while a CPU hog (one busy core) runs for part of the experiment: the same figures
#   slice   --b "--set slices=4" against the default (one GTAO slice more): exit 1 in at least 19 of 20
#   preset  --a "--preset ultra" --b "--preset high": gtao `faster`
#   loop    bench/loop_technique (a user technique of known work), --set iterations=101 against 100:
#           about 1 % more of its one pass; for counted cost (AB_ARGS="--cost instructions"): `slower`
#   bash bench/ab_experiments.sh BUILD_DIR OUT_DIR [EXPERIMENTS=20] [ROUNDS=5]
# Environment: RUN_ARGS (words added to both sides' `run` arguments, e.g. "--frames 0:2"), AB_ARGS
# (words added to `ab` itself, e.g. "--cost instructions"),
# KINDS (default "same hog slice preset"), CAPTURE (default captures/boxes-orbit).
# The hog starts a quarter of the way into each hog experiment and stops after half of it (the
# duration is estimated from the previous `same` or `hog` experiment, or from an uncounted probe
# experiment, OUT_DIR/probe, when none ran), so it is started and stopped inside the experiment,
# and it is stopped at the experiment's end in any case.
# Writes OUT_DIR/KIND/NN/ (ab's outputs), OUT_DIR/KIND/NN.txt (its terminal output), and
# OUT_DIR/summary.txt and summary.json.
set -euo pipefail
build=${1:?build dir}
out=${2:?output dir}
experiments=${3:-20}
rounds=${4:-5}
aoreplay="$build/replay/aoreplay"
capture=${CAPTURE:-"$(dirname "$0")/../captures/boxes-orbit"}
kinds=${KINDS:-same hog slice preset}
run_args=${RUN_ARGS:-}
ab_args=${AB_ARGS:-}
loop_technique="$(cd "$(dirname "$0")" && pwd)/loop_technique/technique.json"
mkdir -p "$out"

side_args() {  # kind side -> that side's extra `run` arguments
  case "$1:$2" in
    slice:b) echo "--set slices=4";;
    preset:a) echo "--preset ultra";;
    preset:b) echo "--preset high";;
    loop:a) echo "--technique $loop_technique --set iterations=100";;
    loop:b) echo "--technique $loop_technique --set iterations=101";;
    *) echo "";;
  esac
}

hog_pid=
stop_hog() {
  if [ -n "$hog_pid" ]; then
    kill "$hog_pid" 2>/dev/null || true
    wait "$hog_pid" 2>/dev/null || true
    hog_pid=
  fi
}
trap stop_hog EXIT

# One busy loop for `seconds`, after `delay`: started in the background, its pid kept to stop it.
# Its command line carries HOG_TAG (default ab-experiments-hog) so a test can find its own.
start_hog() {  # delay seconds
  ( sleep "$1"; exec timeout "$2" bash -c 'while :; do :; done' "${HOG_TAG:-ab-experiments-hog}" ) &
  hog_pid=$!
}

estimate_s=
for kind in $kinds; do
  mkdir -p "$out/$kind"
  for i in $(seq -w 1 "$experiments"); do
    dir="$out/$kind/$i"
    hog_note=
    if [ "$kind" = hog ] && [ -z "$estimate_s" ]; then  # no `same` experiment ran first: time one, not counted
      start=$(date +%s.%N)
      "$aoreplay" ab "$capture" --rounds "$rounds" $ab_args --a "$run_args" --b "$run_args" --out "$out/probe" >"$out/probe.txt" 2>&1 || true
      estimate_s=$(awk "BEGIN{print $(date +%s.%N) - $start}")
    fi
    if [ "$kind" = hog ]; then
      est=$estimate_s
      delay=$(awk "BEGIN{printf \"%.1f\", $est / 4}") span=$(awk "BEGIN{printf \"%.1f\", $est / 2}")
      start_hog "$delay" "$span"
      hog_note=" (one busy core from +$delay s for $span s)"
    fi
    start=$(date +%s.%N)
    set +e
    "$aoreplay" ab "$capture" --rounds "$rounds" $ab_args --a "$run_args $(side_args "$kind" a)" \
      --b "$run_args $(side_args "$kind" b)" --out "$dir" >"$dir.txt" 2>&1
    rc=$?
    set -e
    stop_hog
    seconds=$(awk "BEGIN{print $(date +%s.%N) - $start}")
    if [ "$kind" = same ] || [ "$kind" = hog ]; then estimate_s=$seconds; fi
    echo "$rc $seconds" > "$dir.status"
    echo "$kind $i: exit $rc in ${seconds%.*} s$hog_note"
  done
done

python3 - "$out" "$experiments" "$rounds" "$run_args $ab_args" $kinds <<'PY'
import json, os, sys
out, experiments, rounds, run_args, kinds = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5:]
targets = {
    "same": "exit 0 in >= 19 of 20; every judged name `same` in >= 18 of 20",
    "hog": "exit 0 in >= 19 of 20; every judged name `same` in >= 18 of 20",
    "slice": "exit 1 in >= 19 of 20",
    "preset": "gtao `faster` (ultra against high)",
    "loop": "loop `slower` (iterations 101 against 100, counted cost)",
}
summary, lines = {}, []
lines.append(f"ab experiments: {experiments} per kind, {rounds} rounds each ({2 * rounds} runs a side, ABBA), "
             f"run args both sides: '{run_args}'")
for kind in kinds:
    exits, all_same, gtao, total, more = {}, 0, {}, {}, []
    for i in range(1, experiments + 1):
        name = f"{i:0{len(str(experiments))}d}"
        rc = int(open(os.path.join(out, kind, name + ".status")).read().split()[0])
        exits[rc] = exits.get(rc, 0) + 1
        path = os.path.join(out, kind, name, "compare.json")
        if not os.path.exists(path):
            continue
        c = json.load(open(path))
        judged = [p for p in c["passes"] if p["judged"]]
        all_same += all(p["verdict"] == "same" for p in judged)
        for p in c["passes"]:
            if p["name"] in ("gtao", "loop"): gtao[p["verdict"]] = gtao.get(p["verdict"], 0) + 1
            if p["name"] == "total": total[p["verdict"]] = total.get(p["verdict"], 0) + 1
        more += [f"{p['name']} {p['verdict']} x{p['ratio']:.5f}" for p in judged if p["verdict"] != "same"]
        if kind in ("loop", "slice"):
            same_names = sorted(p["name"] for p in c["passes"] if p["verdict"] == "same")
            more.append(f"[{name}] same: {', '.join(same_names) or '-'}")
    summary[kind] = {"experiments": experiments, "exit_codes": {str(k): v for k, v in sorted(exits.items())},
                     "every_judged_name_same": all_same, "gtao_verdicts": gtao, "total_verdicts": total,
                     "not_same": more, "target": targets.get(kind, "")}
    lines.append(f"{kind}: exit codes {dict(sorted(exits.items()))}; every judged name same in {all_same}/{experiments}; "
                 f"{'loop' if kind == 'loop' else 'gtao'} {gtao}; total {total}  (target for 20: {targets.get(kind, '-')})")
    if more:
        lines.append(f"  not same: {'; '.join(more)}")
text = "\n".join(lines) + "\n"
open(os.path.join(out, "summary.txt"), "w").write(text)
json.dump({"experiments": experiments, "rounds": rounds, "run_args": run_args, "kinds": summary},
          open(os.path.join(out, "summary.json"), "w"), indent=2)
print(text, end="")
PY
