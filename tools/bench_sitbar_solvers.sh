#!/usr/bin/env bash
# Benchmark (not a test): the SIT-BAR press (60 mm in 120 s) and release (120 s) of cases/sitbar_quasistatic
# on a uniform mesh of H mm hex8 elements (quarter block 200 x 200 x 80 mm: 5 mm -> 40 x 40 x 16, about
# 80 k free dofs), run side by side with the direct CHOLMOD path and the PETSc path (CG + GAMG, one process,
# then NP processes under mpirun). Prints a markdown table (wall and CPU time, peak memory, where the time
# goes: element loops, factorizations / preconditioner setups, solves) with each run's time ratio to
# CHOLMOD, and the largest difference of the indenter force from CHOLMOD's at the times all runs share (the
# frame times every 10 s), relative to the peak force.
# Usage: tools/bench_sitbar_solvers.sh [CUSHION_BINARY] [H_mm] [NP]   (defaults: build/tools/cushion 5 2)
# Environment: BENCH_PETSC_OPTIONS (petsc_options of the PETSc runs, default none), BENCH_KEEP=DIR keeps the
# outputs. The runs are sequential; the load average before each is printed (wall times mean little on a
# loaded machine).
set -euo pipefail
main() {
  here="$(cd "$(dirname "$0")/.." && pwd)"
  . "$here/tools/bench_summary.sh"
  cushion="${1:-$here/build/tools/cushion}"
  h="${2:-5}"
  np="${3:-2}"
  [ -x /usr/bin/time ] || { echo "bench_sitbar_solvers.sh: /usr/bin/time is needed (Debian package 'time')" >&2; exit 1; }
  [ -x "$cushion" ] || { echo "bench_sitbar_solvers.sh: cushion binary '$cushion' not found" >&2; exit 2; }
  work="${BENCH_KEEP:-$(mktemp -d /tmp/cushion_bench_sitbar.XXXXXX)}"
  mkdir -p "$work"
  [ -n "${BENCH_KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
  root=()
  [ "$(id -u)" -eq 0 ] && root=(--allow-run-as-root)
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); mesh ${h} mm; PETSc options: ${BENCH_PETSC_OPTIONS:-none}"
  echo
  echo "| run | free dofs | increments | Newton iterations | element loops s | factorizations (PC setups) | factorization s | solves s | wall s | ratio to CHOLMOD | CPU s | peak RSS MiB | force max diff / peak | load before |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  local reference=""
  for run in cholmod petsc "petsc_np$np"; do
    solver=${run%%_*}
    python3 - "$here/cases/sitbar_quasistatic/case.json" "$work/$run.json" "$h" "$solver" "${BENCH_PETSC_OPTIONS:-}" <<'PY'
import json, os, sys
src, dst, h, solver, options = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4], sys.argv[5]
c = json.load(open(src))
g = c["mesh"]["generate"]
g["elements"] = [round(200 / h), round(200 / h), round(80 / h)]
g.pop("grading", None)
c["material"]["file"] = os.path.normpath(os.path.join(os.path.dirname(src), c["material"]["file"]))
c["solver"] = {"linear_solver": solver}
if solver == "petsc" and options:
    c["solver"]["petsc_options"] = options
json.dump(c, open(dst, "w"), indent=1)
PY
    launch=()
    [ "$run" != "${run%_np*}" ] && launch=(mpirun -q --oversubscribe "${root[@]}" -np "$np")
    before=$(cut -d' ' -f1 /proc/loadavg)
    /usr/bin/time -v -o "$work/time_$run.txt" "${launch[@]}" "$cushion" run "$work/$run.json" -o "$work/out_$run" \
      --quiet --overwrite > "$work/summary_$run.txt"
    read_summary "$work/summary_$run.txt" "$work/time_$run.txt"
    setups=$(sed -n 's/.* \([0-9]*\) preconditioner setups.*/\1/p' "$work/out_$run/solver.log" | tail -1)
    [ -n "$reference" ] || reference="$total"
    ratio=$(awk -v a="$total" -v b="$reference" 'BEGIN { printf "%.2f", a / b }')
    diff=$(python3 - "$work/out_cholmod/contact_sitbar.csv" "$work/out_$run/contact_sitbar.csv" <<'PY'
import sys
def forces(path):
    rows = [l.strip().split(",") for l in open(path) if l.strip() and not l.startswith("#")]
    col = rows[0].index("sitbar.F3_N")
    return {round(float(r[0]), 9): float(r[col]) for r in rows[1:]}
a, b = forces(sys.argv[1]), forces(sys.argv[2])
common = sorted(set(a) & set(b))
peak = max(abs(v) for v in a.values())
print("%.2e (%d times)" % (max(abs(a[t] - b[t]) for t in common) / peak, len(common)))
PY
)
    printf '| %s | %s | %s | %s | %s | %s (%s) | %s | %s | %s | %s | %s | %d | %s | %s |\n' "$run" "$dofs" "$increments" \
      "$iters" "$asm_s" "$nfact" "${setups:--}" "$fact" "$solves" "$total" "$ratio" "$cpu" "$rss_mib" "$diff" "$before"
  done
}
main "$@"
exit
