#!/usr/bin/env bash
# Benchmark (not a test): the same-mesh indentation problem of tools/calculix_indentation.sh (rigid sphere
# R = 100 mm pressed 60 mm into the quarter 400 x 400 x 80 mm block in 30 increments, hyperfoam, frictionless
# augmented-Lagrangian contact; mesh by tools/calculix/make_indentation.py, graded towards the sphere) refined to
# N x N x NZ hex8 (40 x 40 x 16: about 80 k free dofs, element size 5 mm on average), run side by side with the
# direct CHOLMOD path and the PETSc path (CG + GAMG, one process, then NP processes under mpirun). Prints a
# markdown table (wall and CPU time, peak memory, where the time goes: element loops, factorizations /
# preconditioner setups, solves) with each run's time ratio to CHOLMOD, and the largest difference of the
# indenter force from CHOLMOD's at the times all runs share (the 30 increments), relative to the peak force.
# Usage: tools/bench_indentation_solvers.sh [CUSHION_BINARY] [N] [NZ] [NP]   (defaults: build/tools/cushion 40 16 2)
# Environment: BENCH_PETSC_OPTIONS (petsc_options of the PETSc runs, default none), BENCH_KEEP=DIR keeps the
# outputs. The runs are sequential; the load average before each is printed (wall times mean little on a
# loaded machine).
set -euo pipefail
main() {
  here="$(cd "$(dirname "$0")/.." && pwd)"
  . "$here/tools/bench_summary.sh"
  cushion="${1:-$here/build/tools/cushion}"
  n="${2:-40}"
  nz="${3:-16}"
  np="${4:-2}"
  [ -x /usr/bin/time ] || { echo "bench_indentation_solvers.sh: /usr/bin/time is needed (Debian package 'time')" >&2; exit 1; }
  [ -x "$cushion" ] || { echo "bench_indentation_solvers.sh: cushion binary '$cushion' not found" >&2; exit 2; }
  work="${BENCH_KEEP:-$(mktemp -d /tmp/cushion_bench_indentation.XXXXXX)}"
  mkdir -p "$work"
  [ -n "${BENCH_KEEP:-}" ] || trap 'rm -rf "$work"' EXIT
  root=()
  [ "$(id -u)" -eq 0 ] && root=(--allow-run-as-root)
  python3 "$here/tools/calculix/make_indentation.py" "$work/problem" --n "$n" --nz "$nz"
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); mesh $n x $n x $nz; PETSc options: ${BENCH_PETSC_OPTIONS:-none}"
  echo
  echo "| run | free dofs | increments | Newton iterations | element loops s | factorizations (PC setups) | factorization s | solves s | wall s | ratio to CHOLMOD | CPU s | peak RSS MiB | force max diff / peak | load before |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  local reference=""
  for run in cholmod petsc "petsc_np$np"; do
    solver=${run%%_*}
    python3 - "$work/problem/case.json" "$work/problem/$run.json" "$solver" "${BENCH_PETSC_OPTIONS:-}" <<'PY'
import json, sys
src, dst, solver, options = sys.argv[1:5]
c = json.load(open(src))
c["solver"] = {"linear_solver": solver}
if solver == "petsc" and options:
    c["solver"]["petsc_options"] = options
json.dump(c, open(dst, "w"), indent=1)
PY
    launch=()
    [ "$run" != "${run%_np*}" ] && launch=(mpirun -q --oversubscribe "${root[@]}" -np "$np")
    before=$(cut -d' ' -f1 /proc/loadavg)
    /usr/bin/time -v -o "$work/time_$run.txt" "${launch[@]}" "$cushion" run "$work/problem/$run.json" -o "$work/out_$run" \
      --quiet --overwrite > "$work/summary_$run.txt"
    read_summary "$work/summary_$run.txt" "$work/time_$run.txt"
    setups=$(sed -n 's/.* \([0-9]*\) preconditioner setups.*/\1/p' "$work/out_$run/solver.log" | tail -1)
    [ -n "$reference" ] || reference="$total"
    ratio=$(awk -v a="$total" -v b="$reference" 'BEGIN { printf "%.2f", a / b }')
    diff=$(python3 - "$work/out_cholmod/contact_sphere.csv" "$work/out_$run/contact_sphere.csv" <<'PY'
import sys
def forces(path):
    rows = [l.strip().split(",") for l in open(path) if l.strip() and not l.startswith("#")]
    col = rows[0].index("sphere.F3_N")
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
