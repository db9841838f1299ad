#!/usr/bin/env bash
# Mesh convergence of the SIT-BAR force (loading branch, 0 -> 60 mm in 120 s) and the quarter- vs
# full-model check. Runs the press step of case.json on quarter meshes NX x NX x NZ (default: 10x10x6,
# the shipped 14x14x8, 20x20x12) and, with FULL=N, case_full.json's press step on the mirrored full
# mesh of the N x N x 6 quarter mesh next to that quarter mesh. Prints a markdown table of the
# full-model indenter force |F3| at 20, 40, 60 mm and the difference to the finest mesh.
# Usage: cases/sitbar_quasistatic/mesh_convergence.sh [CUSHION_BINARY] ["NX NZ" ...]
#   e.g. nice cases/sitbar_quasistatic/mesh_convergence.sh build/tools/cushion "10 6" "14 8" "20 12"
#        FULL=8 nice cases/sitbar_quasistatic/mesh_convergence.sh build/tools/cushion "8 6"
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
cushion="${1:-$here/../../build/tools/cushion}"
shift || true
if [ $# -gt 0 ]; then meshes=("$@"); else meshes=("10 6" "14 8" "20 12"); fi
work="${KEEP:-$(mktemp -d /tmp/cushion_sitbar_conv.XXXXXX)}"
mkdir -p "$work"
[ -n "${KEEP:-}" ] || trap 'rm -rf "$work"' EXIT

# press_case SOURCE NX NY NZ OUT: the press step of SOURCE with the mesh replaced (paths absolute).
press_case() {
  python3 - "$here/$1" "$2" "$3" "$4" "$5" <<'PY'
import json, os, sys
src, nx, ny, nz, out = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
c = json.load(open(src))
c["mesh"]["generate"]["elements"] = [nx, ny, nz]
c["material"]["file"] = os.path.normpath(os.path.join(os.path.dirname(src), c["material"]["file"]))
c["steps"] = c["steps"][:1]
c["steps"][0]["output"]["frames_every_s"] = 40
json.dump(c, open(out, "w"))
PY
}
# force_at OUTDIR: |F3| [N] at t = 40, 80, 120 s (20, 40, 60 mm) from contact_sitbar.csv.
force_at() {
  awk -F, '!/^#/ && NR > 1 { for (t = 40; t <= 120; t += 40) if ($1 + 0 == t) f[t] = ($7 < 0 ? -$7 : $7) }
           END { printf "%.2f %.2f %.2f\n", f[40], f[80], f[120] }' "$1/contact_sitbar.csv"
}
run() {  # run NAME CASEFILE -> "F20 F40 F60 dofs increments iterations cutbacks seconds"
  "$cushion" run "$2" -o "$work/out_$1" --overwrite > "$work/$1.log" 2>&1 || { echo "run $1 failed, see $work/$1.log" >&2; exit 1; }
  local s; s="$(grep -E '^summary:' "$work/$1.log")"
  echo "$(force_at "$work/out_$1") $(grep -oE '[0-9]+ free dofs' "$work/$1.log" | cut -d' ' -f1)" \
       "$(echo "$s" | grep -oE '[0-9]+ increments' | cut -d' ' -f1)" \
       "$(echo "$s" | grep -oE '[0-9]+ Newton' | cut -d' ' -f1)" "$(echo "$s" | grep -oE '[0-9]+ cut-backs' | cut -d' ' -f1)" \
       "$(echo "$s" | grep -oE 'wall time [0-9.]+' | cut -d' ' -f3)"
}

echo "| model | mesh | free dofs | increments | Newton iterations | cut-backs | wall s | F(20 mm) N | F(40 mm) N | F(60 mm) N |"
echo "|---|---|---|---|---|---|---|---|---|---|"
declare -a rows
for m in "${meshes[@]}"; do
  read -r nx nz <<< "$m"
  press_case case.json "$nx" "$nx" "$nz" "$work/q_$nx.json"
  read -r f20 f40 f60 dofs inc it cut sec <<< "$(run "q_$nx" "$work/q_$nx.json")"
  echo "| quarter | ${nx}x${nx}x${nz} | $dofs | $inc | $it | $cut | $sec | $f20 | $f40 | $f60 |"
  rows+=("${nx}x${nx}x${nz} $f20 $f40 $f60")
done
if [ -n "${FULL:-}" ]; then
  n="$FULL"
  press_case case_full.json "$((2 * n))" "$((2 * n))" 6 "$work/full_$n.json"
  read -r f20 f40 f60 dofs inc it cut sec <<< "$(run "full_$n" "$work/full_$n.json")"
  echo "| full | $((2 * n))x$((2 * n))x6 | $dofs | $inc | $it | $cut | $sec | $f20 | $f40 | $f60 |"
fi
if [ "${#rows[@]}" -gt 1 ]; then
  echo
  echo "Difference to the finest mesh (last row above):"
  read -r _ g20 g40 g60 <<< "${rows[-1]}"
  for r in "${rows[@]}"; do
    read -r name f20 f40 f60 <<< "$r"
    awk -v n="$name" -v a="$f20" -v b="$f40" -v c="$f60" -v x="$g20" -v y="$g40" -v z="$g60" \
      'BEGIN { printf "- %s: %+.2f %% at 20 mm, %+.2f %% at 40 mm, %+.2f %% at 60 mm\n", n, 100*(a/x-1), 100*(b/y-1), 100*(c/z-1) }'
  done
fi
