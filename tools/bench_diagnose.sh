#!/usr/bin/env bash
# Confusion-matrix benchmark of `cushion diagnose` on FOREIGN campaigns (issue 15, part 5); not a ctest.
#
#   tools/bench_diagnose.sh [N] [OUT]        N campaigns (default 60), results in OUT (default results/bench_diagnose, git-ignored)
#   env: SEED (2025), PAIRS and CONTROLS (default round(N/6) each), JOBS (campaigns at a time, 2),
#        THREADS (diagnose --threads per campaign, 1), DYNAMIC_NOISE (amplitude|reading, amplitude),
#        PROTOCOL (recorded|unrecorded, default recorded; unrecorded: each campaign runs its own dynamic protocol and
#        leaves its keys out of the manifest), DIAGNOSE_ARGS (more options of every diagnose call, e.g. --assume-protocol),
#        GENERATOR_ARGS (more options of the generator, e.g. "--extra-rate 3000": a test diagnose proposed to separate
#        two explanations, added to every campaign with the truth unchanged; "--sweep-substeps 8": sweeps integrated
#        8 steps a sample, closer to a continuous specimen than cushion's 64-step model, docs/physics.md 9.39),
#        BASE_REFIT (none|report|scale, default none: the generator's --base-refit; report: truth.json also says what
#        a refitted base of the generator's OWN family leaves of the effects (and, of each member of a pair, what that
#        base refitted with the other member leaves: docs/physics.md 9.43), and the summary splits the effect
#        campaigns by it; scale: every effect sized so that what that refit leaves of it is 14-36x noise, i.e.
#        visible in these tests by a measure independent of cushion), REUSE (1: keep OUT/campaigns when it holds an
#        index.csv made with the same generator options,
#        instead of generating them again; the generator is deterministic, so this only saves its time, about 8 min
#        with BASE_REFIT=scale), BUILD (the CMake build folder whose cushion and generator run, default build; another
#        lets a benchmark of one code run while the default folder is rebuilt), ONLY (with REUSE=1: a space-separated
#        list of campaigns, e.g. "c001 c014", diagnosed (again) alone; the others keep the diagnosis of the earlier run
#        in OUT, if any, so use it only when the code of cushion did not change since then: to finish an interrupted
#        run, or to run the pairs first; the summary leaves out and lists the campaigns not diagnosed yet), RESCORE (1:
#        neither generate nor diagnose: score the campaigns and diagnoses already in OUT again, e.g. after a change of
#        this summary)
#
# The campaigns come from $BUILD/tests/foreign_campaigns (tests/foreign: a 1D test machine with its own
# foam and effect forms, independent of cushion's material/ and calibration/). Each is run through the
# BLIND user path of cushion from raw data: `cushion diagnose CAMP/campaign.json -o CAMP/diag` (fit included, every
# candidate fitted jointly with the base); truth.json is
# read only here, to score. Verdict from CAMP/diag/report.json (calibration/diagnose_output.cpp): "winner"
# names the effect(s) ("kind" or "kind + kind"); without a winner the verdict is "none" when it says
# "No effect is missing", else "base" (recalibrate the base: "No effect can be told from a base
# calibration ..." or "The model fails beyond noise ...").
# The truth of each campaign is also written in cushion's catalogue where it has the truth's forms
# (tools/foreign_truth.py -> CAMP/truth_material.json) and compared with the campaign (CAMP/truth_compare): where it
# reproduces every test within 1.5x noise, the family's form matches, and the error after the named effect is held to
# 1.5x noise there (issue 15); elsewhere the verdict must list the tests its effect leaves beyond noise.
# Writes OUT/confusion.csv, OUT/campaigns.csv (one line per campaign) and OUT/summary.txt (printed too). The summary
# also splits the effect campaigns by what the fitted base leaves: beyond 1.5x noise on some test (the effect is visible
# in these tests) or not (absorbed: no method can tell it from a base on these data).
set -euo pipefail
cd "$(dirname "$0")/.."
N=${1:-60}
OUT=${2:-results/bench_diagnose}
SEED=${SEED:-2025}
PAIRS=${PAIRS:-$(( (N + 3) / 6 ))}
CONTROLS=${CONTROLS:-$(( (N + 3) / 6 ))}
JOBS=${JOBS:-2}
THREADS=${THREADS:-1}
DYNAMIC_NOISE=${DYNAMIC_NOISE:-amplitude}
PROTOCOL=${PROTOCOL:-recorded}
DIAGNOSE_ARGS=${DIAGNOSE_ARGS:-}
GENERATOR_ARGS=${GENERATOR_ARGS:-}
BASE_REFIT=${BASE_REFIT:-none}
(( JOBS >= 1 && JOBS <= 2 )) || { echo "JOBS must be 1 or 2 (2 cores)" >&2; exit 2; }

BUILD=${BUILD:-build}
[[ -f $BUILD/CMakeCache.txt ]] || { echo "BUILD=$BUILD: not a configured CMake build folder (no CMakeCache.txt)" >&2; exit 2; }
BUILD=$(cd "$BUILD" && pwd)
nice -n 5 cmake --build "$BUILD" --target cushion foreign_campaigns -j2 >/dev/null
CUSHION=$BUILD/tools/cushion
GENERATOR=$BUILD/tests/foreign_campaigns
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
if [[ ${RESCORE:-0} == 1 ]]; then
  [[ -f $OUT/campaigns/index.csv ]] || { echo "RESCORE: no campaigns in $OUT/campaigns to score" >&2; exit 2; }
  echo "bench_diagnose: scoring the campaigns and diagnoses in $OUT again (RESCORE=1: nothing generated or diagnosed)"
else
generator_options="--count $N --seed $SEED --pairs $PAIRS --controls $CONTROLS --dynamic-noise $DYNAMIC_NOISE --protocol $PROTOCOL --base-refit $BASE_REFIT $GENERATOR_ARGS"
rerun=()  # the campaigns to diagnose: ONLY's, else all of them
for c in ${ONLY:-}; do rerun+=("$OUT/campaigns/$c"); done
if [[ ${REUSE:-0} == 1 && -f $OUT/campaigns/index.csv && "$(cat "$OUT/generator_options.txt" 2>/dev/null)" == "$generator_options" ]]; then
  echo "bench_diagnose: reusing the $N campaigns in $OUT/campaigns (same generator options)"
  for c in "${rerun[@]}"; do [[ -f $c/campaign.json ]] ||
    { echo "ONLY: $(basename "$c") is not a campaign of $OUT/campaigns" >&2; exit 2; }; done
  (( ${#rerun[@]} )) || rerun=("$OUT"/campaigns/c[0-9]*)
  for c in "${rerun[@]}"; do rm -rf "$c/diag" "$c/diag.log" "$c/bench_status.txt"; done
elif [[ -n ${ONLY:-} ]]; then
  echo "ONLY needs REUSE=1 and the campaigns of an earlier run with the same generator options in $OUT" >&2; exit 2
else
  rm -rf "$OUT/campaigns" "$OUT/generator_options.txt"
  echo "bench_diagnose: generating $N campaigns (seed $SEED, $PAIRS pairs, $CONTROLS controls) in $OUT/campaigns"
  # shellcheck disable=SC2086  # generator_options: words
  "$GENERATOR" --out "$OUT/campaigns" $generator_options > "$OUT/generator.log"
  echo "$generator_options" > "$OUT/generator_options.txt"
  rerun=("$OUT"/campaigns/c[0-9]*)
fi

# One campaign: `cushion diagnose CAMP/campaign.json` (no material: the base is fitted first into CAMP/diag/fit,
# then every candidate jointly with it); CAMP/bench_status.txt holds "status fit_s diagnose_s" (fit_s is 0: the
# fit runs inside the diagnose call, whose whole time is diagnose_s).
run_one() {
  local camp=$1 cushion=$2 threads=$3 t0 t1 status=ok
  t0=$(date +%s.%N)
  # shellcheck disable=SC2086  # DIAGNOSE_ARGS: words
  if ! nice -n 5 "$cushion" diagnose "$camp/campaign.json" -o "$camp/diag" --threads "$threads" $DIAGNOSE_ARGS \
       > "$camp/diag.log" 2>&1; then
    if [[ ! -f $camp/diag/fit/material.json ]]; then status=fit_failed; else status=diagnose_failed; fi
  fi
  t1=$(date +%s.%N)
  echo "$status 0 $(echo "$t1 - $t0" | bc)" > "$camp/bench_status.txt"
  echo "bench_diagnose: $(basename "$camp") $(cat "$camp/bench_status.txt")"
}
export -f run_one
export DIAGNOSE_ARGS
start=$(date +%s)
printf '%s\n' "${rerun[@]}" | xargs -P "$JOBS" -I{} bash -c 'run_one "$@"' _ {} "$CUSHION" "$THREADS"
echo "bench_diagnose: wall time $(( $(date +%s) - start )) s for ${ONLY:+the campaigns }${ONLY:-$N campaigns}, $JOBS at a time"
fi

# The truth in cushion's catalogue against its own campaign (not timed; about 1 s a campaign).
for camp in "$OUT"/campaigns/c[0-9]*; do
  rm -rf "$camp/truth_material.json" "$camp/truth_compare" "$camp/truth_status.txt" "$camp/truth_map.txt"
  if python3 tools/foreign_truth.py "$camp" "$camp/truth_material.json" > "$camp/truth_map.txt" 2> "$camp/truth_status.txt"; then
    "$CUSHION" compare "$camp/truth_material.json" "$camp/campaign.json" -o "$camp/truth_compare" > /dev/null 2>> "$camp/truth_status.txt" ||
      echo "compare failed" >> "$camp/truth_status.txt"
  fi
done

python3 - "$OUT" "$SEED" "$JOBS" "$THREADS" "${RESCORE:-0}" <<'PY'
import csv, json, os, re, statistics, sys
out, seed, jobs, threads, rescore = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5] == "1"
families = ["pneumatic", "friction", "mullins", "stiffness_damping", "strain_dependent_prony"]
columns = families + ["none", "base", "fit-failed", "diagnose-failed"]

def worst_ratio(compare):
    """The largest error/noise over the tests of a comparison (report.json "tests"), None when no test has one."""
    return max((t["error_over_noise"] for t in compare["tests"] if t.get("error_over_noise") is not None), default=None)

def named_step_error(camp):
    """The largest time-step error estimate of the named model's sweeps (diagnose's step check, report.json
    step_error_over_noise of the winner's comparison), None without a winner or a check."""
    path = os.path.join(camp, "diag", "report.json")
    r = json.load(open(path)) if os.path.exists(path) else {}
    if not r.get("winner") or not r.get("candidates") or "compare" not in r["candidates"][0]:
        return None
    return max((t["step_error_over_noise"] for t in r["candidates"][0]["compare"]["tests"]
                if "step_error_over_noise" in t), default=None)

def verdict_of(camp):
    status, fit_s, diag_s = open(os.path.join(camp, "bench_status.txt")).read().split()
    seconds = float(fit_s) + float(diag_s)
    if status == "fit_failed":
        return ["fit-failed"], None, None, seconds, []
    report = os.path.join(camp, "diag", "report.json")
    if status != "ok" or not os.path.exists(report):
        return ["diagnose-failed"], None, None, seconds, []
    r = json.load(open(report))
    baseline = worst_ratio(r["baseline"])
    if r.get("winner"):
        named = [k.strip() for k in r["winner"].split("+")]
        after = worst_ratio(r["candidates"][0]["compare"]) if r["candidates"] and "compare" in r["candidates"][0] else None
        rival = [k.strip() for k in r["rival"]["name"].split("+")] if r.get("rival") else []
        return named, baseline, after, seconds, rival
    if r.get("at_noise_level") or r["verdict"].startswith("No effect is missing"):
        return ["none"], baseline, None, seconds, []
    if r["verdict"].startswith("Cannot diagnose"):
        return ["diagnose-failed"], baseline, None, seconds, []
    return ["base"], baseline, None, seconds, []

def truth_in_catalogue(camp):
    """Worst error/noise of the truth written in cushion's catalogue (tools/foreign_truth.py) against its campaign, and
    how it maps: "same" (every form the same equation), "strain measure" (some form on another strain measure), or
    why there is no such material (a form without counterpart)."""
    status = open(os.path.join(camp, "truth_status.txt")).read().strip()
    report = os.path.join(camp, "truth_compare", "report.json")
    if not os.path.exists(report):
        return None, re.sub(r"^.*: ", "", status.splitlines()[-1]) if status else "no truth material"
    kind = open(os.path.join(camp, "truth_map.txt")).read().strip()  # tools/foreign_truth.py: base, same or strain
    return worst_ratio(json.load(open(report))), "strain measure" if kind == "strain" else "same"

def lists_tests_beyond_noise(camp):
    """A verdict whose effect leaves a test beyond noise says so (diagnose: "Tests still beyond noise ...")."""
    report = os.path.join(camp, "diag", "report.json")
    if not os.path.exists(report):
        return None
    r = json.load(open(report))
    if not r.get("winner") or r.get("winner_at_noise_level"):
        return None
    return "Tests still beyond noise after adding it" in r["verdict"]

rows, undiagnosed = [], []
def weakest_member(truth, key):
    """Of a pair: the smallest over its members of the largest ratio over the tests in parameters.FAMILY.key (x noise);
    None for a single or a control, or when a member has no such record."""
    largest = [max(p[key].values()) for p in truth.get("parameters", {}).values() if isinstance(p, dict) and p.get(key)]
    return min(largest) if len(truth["families"]) > 1 and len(largest) == len(truth["families"]) else None

for line in csv.DictReader(open(os.path.join(out, "campaigns", "index.csv"))):
    camp = os.path.join(out, "campaigns", line["campaign"])
    if not os.path.exists(os.path.join(camp, "bench_status.txt")):  # ONLY: not run yet
        undiagnosed.append(line["campaign"])
        continue
    truth = json.load(open(os.path.join(camp, "truth.json")))
    true = truth["families"]
    label = "control" if not true else "+".join(true)
    named, baseline, after, seconds, rival = verdict_of(camp)
    if not true:
        right = named == ["none"]
    elif len(true) == 1:
        right = named[0] == true[0]                      # the true family ranked first
    else:
        right = sorted(named) == sorted(true)            # both families of a pair
    left = truth.get("after_base_refit", {}).get("largest")  # what the generator's own base refit leaves (report|scale)
    # of a pair, for the member hardest to show: what that refit leaves of it alone, and what a base refit PLUS the
    # other member (its magnitude refitted) leaves of the pair's records
    weaker = weakest_member(truth, "after_base_refit")
    weaker_beyond = weakest_member(truth, "beyond_partner_refit")
    truth_worst, truth_map = truth_in_catalogue(camp)
    rows.append(dict(campaign=line["campaign"], truth=label, forms=line["forms"], base=truth["base"]["family"],
                     verdict="+".join(named), rival="+".join(rival) or "-", right=right, baseline_error_over_noise=baseline,
                     after_error_over_noise=after, seconds=seconds, left_by_foreign_refit=left,
                     weaker_member_left=weaker, weaker_member_beyond_partner=weaker_beyond, truth_in_cushion_error_over_noise=truth_worst, truth_map=truth_map,
                     verdict_lists_tests_beyond_noise=lists_tests_beyond_noise(camp),
                     named_step_error_over_noise=named_step_error(camp)))

def kind(label):
    return "control" if label == "control" else ("pair" if "+" in label else "single")

labels = [f for f in families if any(r["truth"] == f for r in rows)]
labels += sorted({r["truth"] for r in rows if kind(r["truth"]) == "pair"})
labels += ["control"] if any(r["truth"] == "control" for r in rows) else []
matrix = {l: {c: 0 for c in columns} for l in labels}
count = {l: 0 for l in labels}
for r in rows:
    count[r["truth"]] += 1
    for v in r["verdict"].split("+"):
        matrix[r["truth"]][v] += 1

with open(os.path.join(out, "confusion.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["truth", "campaigns"] + columns)
    for l in labels:
        w.writerow([l, count[l]] + [matrix[l][c] for c in columns])
with open(os.path.join(out, "campaigns.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
    w.writeheader()
    w.writerows(rows)

fmt = lambda x: "-" if x is None else f"{x:.3g}"
lines = []
p = lines.append
p(f"cushion diagnose benchmark on foreign campaigns: N = {len(rows)} (seed {seed}; diagnose from raw data: fit + joint candidates, "
  + ("the diagnoses and times of an earlier run in this folder, scored again)" if rescore else
     f"{jobs} campaigns at a time, --threads {threads})"))
if undiagnosed:
    p(f"NOT diagnosed yet, left out of every figure below: {len(undiagnosed)} campaigns ({' '.join(undiagnosed)})")
p("")
p("Confusion matrix (rows: truth; columns: verdict; a pair verdict counts in both of its families' columns):")
short = {"pneumatic": "pneum", "friction": "frict", "mullins": "mull", "stiffness_damping": "stiffd",
         "strain_dependent_prony": "sdprony", "none": "none", "base": "base", "fit-failed": "fitfail",
         "diagnose-failed": "diagfail"}
width = max(len(l) for l in labels) + 2
p("truth".ljust(width) + "n".rjust(4) + "".join(short[c].rjust(9) for c in columns))
for l in labels:
    p(l.ljust(width) + str(count[l]).rjust(4) + "".join(str(matrix[l][c]).rjust(9) for c in columns))
p("")
for k, what in (("single", "true family ranked first"), ("pair", "both families named"), ("control", "'no effect missing'")):
    sel = [r for r in rows if kind(r["truth"]) == k]
    if sel:
        p(f"{k:8s}: {sum(r['right'] for r in sel)}/{len(sel)} right ({what})")
effect_rows = [r for r in rows if kind(r["truth"]) != "control"]
p(f"effects : {sum(r['right'] for r in effect_rows)}/{len(effect_rows)} right (singles and pairs)")
# An effect the base fitted on these tests already absorbs to the noise level cannot be told from a pure base by any
# method on these data; the generator scales each effect against the TRUE base, not against the best base fit.
seen = [r for r in effect_rows if r["baseline_error_over_noise"] is not None and r["baseline_error_over_noise"] > 1.5]
if effect_rows:
    p(f"effects the fitted base leaves beyond 1.5x noise (visible in these tests): {len(seen)}/{len(effect_rows)}, "
      f"right among them {sum(r['right'] for r in seen)}/{len(seen)}; absorbed by the fitted base (<= 1.5x): "
      f"{len(effect_rows) - len(seen)}, of them 'none' {sum(r['verdict'] == 'none' for r in effect_rows if r not in seen)}")
# The same split by a measure independent of cushion (BASE_REFIT report or scale): what a base of the generator's own
# family, refitted to the noise-free records, leaves of the effects (truth.json after_base_refit): beyond 3x noise the
# effects are visible in these tests whatever base one fits.
refit_rows = [r for r in effect_rows if r["left_by_foreign_refit"] is not None]
if refit_rows:
    vis = [r for r in refit_rows if r["left_by_foreign_refit"] > 3.0]
    p(f"effects a refitted base of the generator's own family leaves beyond 3x noise: {len(vis)}/{len(refit_rows)}, right among "
      f"them {sum(r['right'] for r in vis)}/{len(vis)} (singles {sum(r['right'] for r in vis if kind(r['truth']) == 'single')}/"
      f"{sum(kind(r['truth']) == 'single' for r in vis)}); at most 3x: {len(refit_rows) - len(vis)}, right among them "
      f"{sum(r['right'] for r in refit_rows if r not in vis)}")
# A pair is only as visible as its weaker member: what the generator's own base refit leaves of that member alone
# (weaker_member_left), and beyond its partner: what a base refitted with the other member in the model (its magnitude
# refitted too) leaves (weaker_member_beyond_partner, docs/physics.md 9.43).
def pair_split(key, what, others):
    pair_rows = [r for r in effect_rows if kind(r["truth"]) == "pair" and r[key] is not None]
    if pair_rows:
        vis = [r for r in pair_rows if r[key] > 3.0]
        p(f"pairs whose {what} beyond 3x noise: {len(vis)}/{len(pair_rows)}, right among them "
          f"{sum(r['right'] for r in vis)}/{len(vis)}; the others{others}: right "
          f"{sum(r['right'] for r in pair_rows if r not in vis)}/{len(pair_rows) - len(vis)}")
pair_split("weaker_member_left", "weaker member alone a refitted base of the generator's own family leaves",
           " (weaker member at most 3x)")
pair_split("weaker_member_beyond_partner", "each member a refitted base plus the other member leaves", "")
# A verdict that names a winner may add that another candidate explains the data as well (diagnose's rival, with
# the test that would separate them): the true family is then at least put before the user.
singles = [r for r in rows if kind(r["truth"]) == "single"]
if singles:
    tied = [r for r in singles if r["rival"] != "-"]
    p(f"singles whose verdict names an equal rival: {len(tied)}/{len(singles)}; true family first or the rival: "
      f"{sum(r['right'] or r['truth'] in r['rival'].split('+') for r in singles)}/{len(singles)}")
controls = [r for r in rows if r["truth"] == "control"]
if controls:
    fp = sum(1 for r in controls if r["verdict"] not in ("none", "base", "fit-failed", "diagnose-failed"))
    p(f"control false-positive rate (an effect named): {fp}/{len(controls)} = {fp / len(controls):.2f}")
after = [r for r in rows if r["after_error_over_noise"] is not None]
if after:
    worst = max(after, key=lambda r: r["after_error_over_noise"])
    p(f"worst error/noise after adding the named effect: {worst['after_error_over_noise']:.3g} ({worst['campaign']}, "
      f"truth {worst['truth']}, named {worst['verdict']}); median over {len(after)} campaigns with a verdict effect "
      f"{statistics.median(r['after_error_over_noise'] for r in after):.3g}")
stepped = [r for r in rows if r["named_step_error_over_noise"] is not None]
if stepped:
    worst = max(stepped, key=lambda r: r["named_step_error_over_noise"])
    beyond = sum(1 for r in stepped if r["named_step_error_over_noise"] > 1.0)
    p(f"time step of the named model's sweeps (diagnose's step check, docs/physics.md 9.39): beyond 1 noise unit on "
      f"{beyond}/{len(stepped)}, largest {worst['named_step_error_over_noise']:.3g} ({worst['campaign']}, named "
      f"{worst['verdict']})")
# Where the family's form matches: the truth written in cushion's catalogue reproduces its campaign within 1.5x noise
# on every test (tools/foreign_truth.py; the effect's own equation, or on another strain measure). There the error
# after the named effect must be at the noise level; elsewhere the verdict must list the tests left beyond it.
mapped = [r for r in rows if r["truth_in_cushion_error_over_noise"] is not None]
if mapped:
    reproduced = [r for r in mapped if r["truth_in_cushion_error_over_noise"] <= 1.5]
    by_map = lambda sel, m: f"{sum(r['truth_map'] == m for r in sel)}"
    p(f"truth written in cushion's catalogue (tools/foreign_truth.py) reproduces its campaign within 1.5x noise: "
      f"{len(reproduced)}/{len(mapped)} (controls {sum(r['truth'] == 'control' for r in reproduced)}/"
      f"{sum(r['truth'] == 'control' for r in mapped)}; effects of the same equation "
      f"{sum(r['truth'] != 'control' for r in reproduced if r['truth_map'] == 'same')}/"
      f"{sum(r['truth'] != 'control' for r in mapped if r['truth_map'] == 'same')}, on another strain measure "
      f"{by_map(reproduced, 'strain measure')}/{by_map(mapped, 'strain measure')}); no counterpart in the catalogue: "
      f"{sum(1 for r in rows if r['truth_in_cushion_error_over_noise'] is None)}")
    matched = [r for r in reproduced if r["truth"] != "control"]
    named = [r for r in matched if r["after_error_over_noise"] is not None]
    within = [r for r in named if r["after_error_over_noise"] <= 1.5]
    quiet = [r for r in matched if r["verdict"] == "none" and (r["baseline_error_over_noise"] or 0) <= 1.5]
    p(f"form matches (the truth reproduces): {len(matched)} effect campaigns; an effect named on {len(named)}, every "
      f"test within 1.5x noise after it on {len(within)}/{len(named)}"
      + (f" (beyond: {', '.join(r['campaign'] + ' ' + fmt(r['after_error_over_noise']) for r in named if r not in within)})"
         if len(within) < len(named) else "")
      + f"; 'none' with the fitted base already within 1.5x: {len(quiet)}")
said = [r for r in rows if r["verdict_lists_tests_beyond_noise"] is not None]
if said:
    p(f"verdicts whose named effect leaves a test beyond 1.5x noise: {len(said)}; the verdict lists those tests: "
      f"{sum(r['verdict_lists_tests_beyond_noise'] for r in said)}/{len(said)}")
base = [r["baseline_error_over_noise"] for r in rows if r["baseline_error_over_noise"] is not None]
if base:
    p(f"worst error/noise of the fitted baseline: median {statistics.median(base):.3g}, max {max(base):.3g}")
secs = [r["seconds"] for r in rows]
p(f"time per campaign (fit + diagnose): mean {statistics.mean(secs):.1f} s, max {max(secs):.1f} s")
p("")
p("Per campaign:")
p(f"{'campaign':9s} {'truth':40s} {'forms':34s} {'base':16s} {'verdict':36s} ok   err/noise before -> after   s      "
  f"rival{'  left by the foreign refit' if refit_rows else ''}  truth in cushion")
for r in rows:
    p(f"{r['campaign']:9s} {r['truth']:40s} {r['forms']:34s} {r['base']:16s} {r['verdict']:36s} "
      f"{'yes' if r['right'] else 'no ':3s}  {fmt(r['baseline_error_over_noise']):>8s} -> {fmt(r['after_error_over_noise']):8s} "
      f"{r['seconds']:6.1f}  {r['rival']}" + (f"  {fmt(r['left_by_foreign_refit'])}" if refit_rows else "")
      + f"  {fmt(r['truth_in_cushion_error_over_noise'])}"
      + (f" ({r['truth_map']})" if r['truth_map'] == 'strain measure' else ""))
text = "\n".join(lines) + "\n"
open(os.path.join(out, "summary.txt"), "w").write(text)
print(text, end="")
PY
