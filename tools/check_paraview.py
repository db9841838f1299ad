#!/usr/bin/env python3
"""Opens the results of every shipped `cushion run` case in ParaView and checks what a user sees there.

Requirement: every .pvd a shipped case writes opens with ParaView's own reader (pvpython, PVDReader), holds the
arrays the README lists with a unit in every name, its time values (simulation time [s]; frequency [Hz] for a
sweep) increase and match the case, and every value is finite (except `<contact>_gap_mm`, NaN by design at nodes
outside the contact set, i.e. where `<contact>_status` is -1).

Two halves in one file:
  python3 tools/check_paraview.py --cushion build/tools/cushion [--pvpython pvpython] [--keep DIR]
      runs a short variant of each case (the shapes of tests/cases/test_cases.cpp, coarser or shorter where only
      the files matter; the keys changed are listed in SHORT below) into a scratch folder, writes what each
      output folder must hold (expect.json), then runs the inspector under pvpython. Exit 0 all good, 1 a check
      failed, 77 pvpython not found (ctest SKIP_RETURN_CODE).
  pvpython tools/check_paraview.py --inspect DIR
      the inspector: reads DIR/*/expect.json and opens every listed .pvd (every frame).
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

SKIP = 77

# Units a name may end with, and the arrays that are dimensionless by definition (named as such in the README).
UNITS = ("_mm", "_kPa", "_N", "_deg", "_mm_s", "_mm_s2")
DIMENSIONLESS = {"J", "log_strain", "principal_stretches"}
DIMENSIONLESS_SUFFIXES = ("_status",)  # contact node status: -1 not in the set, 0 open, 1 stick, 2 slip

QUASI_STATIC_POINT = ["displacement_mm", "reaction_force_N"]
QUASI_STATIC_CELL = ["cauchy_stress_kPa", "von_mises_kPa", "pressure_kPa", "log_strain", "principal_stretches", "J",
                     "viscous_stress_norm_kPa"]
CONTACT_POINT = ["{}_pressure_kPa", "{}_gap_mm", "{}_status", "{}_force_N"]
DYNAMIC_POINT = ["velocity_mm_s", "acceleration_mm_s2"]
SWEEP_POINT = ["displacement_mm", "U_real_mm", "U_imag_mm", "U_amplitude_mm", "U_phase_deg"]
SWEEP_CELL = ["cauchy_stress_kPa", "von_mises_kPa", "pressure_kPa", "log_strain", "principal_stretches", "J",
              "sigma_hat_real_kPa", "sigma_hat_imag_kPa", "sigma_hat_amplitude_kPa", "sigma_hat_phase_deg"]


# ----------------------------------------------------------------------------------------------- runner (python3)

def shipped_case(source, relative):
    """A shipped case file with its material (and .inp mesh) path made absolute."""
    path = Path(source) / "cases" / relative
    case = json.loads(path.read_text())

    def absolute(holder, key):
        p = Path(holder[key])
        if not p.is_absolute():
            holder[key] = str((path.parent / p).resolve())

    absolute(case["material"], "file")
    if "inp" in case["mesh"]:
        absolute(case["mesh"], "inp")
    return case


def short_sitbar(case, elements_xy, press_only):
    case["mesh"]["generate"]["elements"] = [elements_xy, elements_xy, 4]
    case["steps"][0]["time_period_s"] = 40
    case["steps"][0]["contact"][0]["motion_mm"] = [0, 0, -20]
    for step in case["steps"]:
        step.setdefault("output", {})["frames_every_s"] = 20
    if press_only:
        del case["steps"][1:]
    else:
        case["steps"][1]["time_period_s"] = 40
    return case


def short_sweep(case):
    case["mesh"]["generate"]["elements"] = [8, 8, 4]
    for step in case["steps"][2:]:
        ss = step["steady_state"]
        ss.pop("frequencies", None)
        ss["frequencies_Hz"] = [1, 20]
        ss["output"] = {"vtk": True}
    return case


def short_dynamic(case):
    case["steps"][1]["time_period_s"] = 20  # hold
    shake = case["steps"][3]
    shake["time_period_s"] = 0.1
    shake["output"] = {"frames_every_s": 0.05}
    case["steps"][2]["steady_state"]["output"] = {"vtk": True}
    return case


def short_calculix(case):
    press = case["steps"][0]
    press["contact"][0]["motion_mm"] = [0, 0, -5]
    press["increment"] = {"initial_s": 0.5, "min_s": 1e-3, "max_s": 0.5, "max_increments": 100}
    press["output"]["frames_every_s"] = 0.5
    return case


def short_iso(case):
    case["mesh"]["generate"]["elements"] = [8, 8, 4]
    case["steps"][1]["time_period_s"] = 4  # hold
    case["steps"][1]["output"] = {"frames_every_s": 4}
    return case


# case file -> how it is shortened (None: run as shipped)
SHORT = {
    "cube_compression/case.json": None,
    "cube_compression/case_petsc.json": None,            # the same with PETSc (needs a build with it)
    "sitbar_quasistatic/cube_same_rate.json": None,
    "dynamic_sine/case.json": short_dynamic,              # hold 20 s, shake 0.1 s, sweep VTK on
    "iso2439_hardness/case.json": short_iso,              # 8x8x4, hold 4 s
    "sitbar_quasistatic/case.json": lambda c: short_sitbar(c, 8, False),    # 8x8x4, 20 mm in 40 s, out in 40 s
    "sitbar_quasistatic/case_full.json": lambda c: short_sitbar(c, 8, True),  # 8x8x4, press only
    "sitbar_sweep/case.json": short_sweep,                # 8x8x4, 1 and 20 Hz, VTK on for both sweeps
    "calculix_check/case.json": short_calculix,           # 5 mm in 2 increments
}


def frequencies(ss):
    if "frequencies_Hz" in ss:
        return list(ss["frequencies_Hz"])
    r = ss["frequencies"]
    count = int(math.floor((r["end_Hz"] - r["start_Hz"]) / r["step_Hz"] * (1 + 1e-12))) + 1
    return [r["start_Hz"] + i * r["step_Hz"] for i in range(count)]


def expectations(case):
    """What the output folder of `case` must hold: {pvd file: {times, exact, point, cell}}; point and cell map
    an array name to the time window [from, to] (from exclusive) of the frames that must carry it: contact
    arrays from the start of the first step naming the contact (the t = 0 frame precedes every contact),
    velocity and acceleration within dynamic steps."""
    everywhere = [-1.0, math.inf]
    point = {name: everywhere for name in QUASI_STATIC_POINT}
    step_ends, t = [0.0], 0.0
    out = {}
    for s in case["steps"]:
        if s["type"] == "steady_state":
            ss = s["steady_state"]
            if ss.get("output", {}).get("vtk", True):
                out[s["name"] + "_sweep.pvd"] = {"times": frequencies(ss), "exact": True,
                                                 "point": {name: everywhere for name in SWEEP_POINT},
                                                 "cell": {name: everywhere for name in SWEEP_CELL}}
            continue
        for c in s.get("contact", []):
            for pattern in CONTACT_POINT:
                point.setdefault(pattern.format(c["name"]), [t, math.inf])
        if s["type"] == "dynamic":
            for name in DYNAMIC_POINT:
                point[name] = [t, t + s["time_period_s"]]
        t += s["time_period_s"]
        step_ends.append(t)
    # Frames at t = 0, at every step end (and in between): these times must all be there, the last one last.
    out["results.pvd"] = {"times": step_ends, "exact": False, "point": point,
                          "cell": {name: everywhere for name in QUASI_STATIC_CELL}}
    return out


def shipped_case_files(source):
    """Every `cushion run` case file in cases/ (a JSON object with "mesh" and "steps"), as "folder/file.json"."""
    found = set()
    for path in (Path(source) / "cases").glob("*/*.json"):
        try:
            data = json.loads(path.read_text())
        except ValueError:
            continue
        if isinstance(data, dict) and "mesh" in data and "steps" in data:
            found.add(f"{path.parent.name}/{path.name}")
    return found


def run_cases(cushion, source, scratch):
    missing = shipped_case_files(source) - set(SHORT)
    if missing:
        print(f"check_paraview: case files without an entry in SHORT: {sorted(missing)}")
        return False
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    for relative, shorten in SHORT.items():
        case = shipped_case(source, relative)
        if shorten:
            case = shorten(case)
        folder = scratch / relative.replace("/", "_").replace(".json", "")
        folder.mkdir(parents=True)
        (folder / "case.json").write_text(json.dumps(case, indent=1))
        t0 = time.time()
        run = subprocess.run([cushion, "run", str(folder / "case.json"), "-o", str(folder / "out"), "--threads", "1",
                              "--quiet"], env=env, capture_output=True, text=True)
        print(f"run  {relative:42s} {time.time() - t0:6.1f} s  exit {run.returncode}", flush=True)
        if run.returncode != 0:
            print(run.stdout + run.stderr)
            return False
        (folder / "out" / "expect.json").write_text(json.dumps({"case": relative, "files": expectations(case)}))
    return True


def runner(args):
    pvpython = args.pvpython or shutil.which("pvpython")
    if not pvpython or not Path(pvpython).exists():
        print("check_paraview: pvpython not found: skipped")
        return SKIP
    scratch = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="cushion_paraview_"))
    scratch.mkdir(parents=True, exist_ok=True)
    try:
        t0 = time.time()
        if not run_cases(args.cushion, args.source, scratch):
            return 1
        t1 = time.time()
        inspect = subprocess.run([pvpython, "--force-offscreen-rendering", os.path.abspath(__file__), "--inspect",
                                  str(scratch)])
        print(f"check_paraview: cases {t1 - t0:.1f} s, pvpython {time.time() - t1:.1f} s")
        return 0 if inspect.returncode == 0 else 1
    finally:
        if not args.keep:
            shutil.rmtree(scratch, ignore_errors=True)


# ------------------------------------------------------------------------------------------- inspector (pvpython)

class Problems:
    def __init__(self):
        self.items = []

    def add(self, where, text):
        self.items.append(f"{where}: {text}")


def has_unit(name):
    return name in DIMENSIONLESS or name.endswith(UNITS) or name.endswith(DIMENSIONLESS_SUFFIXES)


def check_times(where, times, expect, problems):
    if any(b <= a for a, b in zip(times, times[1:])):
        problems.add(where, f"time values do not increase: {times}")
    wanted = expect["times"]
    if expect["exact"]:
        if len(times) != len(wanted) or any(abs(a - b) > 1e-9 * max(1.0, abs(b)) for a, b in zip(times, wanted)):
            problems.add(where, f"frequencies {times} differ from the case's {wanted} Hz")
        return
    for t in wanted:
        if not any(abs(t - x) <= 1e-9 * max(1.0, abs(t)) for x in times):
            problems.add(where, f"no frame at the step end t = {t} s (frames at {times})")
    if times and abs(times[-1] - wanted[-1]) > 1e-9 * max(1.0, wanted[-1]):
        problems.add(where, f"last frame at {times[-1]} s, the case ends at {wanted[-1]} s")


def check_array(where, array, mask, problems):
    """Units in the name; finite values (tuples where mask is False may be NaN: gap outside the contact set)."""
    name = array.GetName()
    if not has_unit(name):
        problems.add(where, f"array '{name}' has no unit in its name")
    nc = array.GetNumberOfComponents()
    for i in range(array.GetNumberOfTuples()):
        if mask is not None and not mask[i]:
            continue
        if not all(math.isfinite(array.GetComponent(i, c)) for c in range(nc)):
            problems.add(where, f"array '{name}' has a non-finite value at tuple {i}")
            return


def check_frame(where, t, data, expect, problems):
    pd, cd = data.GetPointData(), data.GetCellData()
    point = {pd.GetArrayName(i) for i in range(pd.GetNumberOfArrays())}
    cell = {cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())}
    for kind, present in (("point", point), ("cell", cell)):
        for name, (t_from, t_to) in expect[kind].items():
            if t_from < t <= t_to + 1e-9 * max(1.0, abs(t_to)) and name not in present:
                problems.add(where, f"{kind} array '{name}' missing (has {sorted(present)})")
    for i in range(pd.GetNumberOfArrays()):
        array, mask = pd.GetArray(i), None
        if array.GetName().endswith("_gap_mm"):  # NaN by design where the node is not in the contact set
            status = pd.GetArray(array.GetName()[:-len("_gap_mm")] + "_status")
            mask = [status is None or status.GetValue(k) != -1 for k in range(array.GetNumberOfTuples())]
        check_array(where, array, mask, problems)
    for i in range(cd.GetNumberOfArrays()):
        check_array(where, cd.GetArray(i), None, problems)
    for name in ("U_phase_deg", "sigma_hat_phase_deg"):
        array = pd.GetArray(name) if name in point else cd.GetArray(name)
        if array is not None:
            lo, hi = array.GetRange(-1)  # what ParaView colours by (the magnitude for vectors)
            if lo <= -180.0 or hi > 180.0:
                problems.add(where, f"'{name}' spans [{lo}, {hi}] deg, outside (-180, 180]")


def inspect(folder):
    from paraview import servermanager
    from paraview.simple import PVDReader

    problems = Problems()
    count = 0
    for expect_file in sorted(Path(folder).glob("*/out/expect.json")):
        spec = json.loads(expect_file.read_text())
        out = expect_file.parent
        for pvd, expect in spec["files"].items():
            where = f"{spec['case']}: {pvd}"
            if not (out / pvd).exists():
                problems.add(where, "not written")
                continue
            reader = PVDReader(FileName=str(out / pvd))
            times = list(reader.TimestepValues) if reader.TimestepValues else []
            check_times(where, times, expect, problems)
            for t in times:
                reader.UpdatePipeline(t)
                check_frame(f"{where} t = {t}", t, servermanager.Fetch(reader), expect, problems)
                count += 1
            print(f"read {where}: {len(times)} frames, times {times[0] if times else '-'} .. "
                  f"{times[-1] if times else '-'}", flush=True)
    for p in problems.items[:50]:
        print("PROBLEM", p)
    print(f"check_paraview: {count} frames read, {len(problems.items)} problems")
    return 1 if problems.items or count == 0 else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cushion", help="the cushion program")
    parser.add_argument("--source", default=str(Path(__file__).resolve().parent.parent), help="repository root")
    parser.add_argument("--pvpython", default="", help="ParaView's python (default: pvpython on PATH)")
    parser.add_argument("--keep", help="run the cases in this folder and keep it")
    parser.add_argument("--inspect", help="(under pvpython) check the output folders below this folder")
    args = parser.parse_args()
    if args.inspect:
        return inspect(args.inspect)
    if not args.cushion:
        parser.error("--cushion is required")
    return runner(args)


if __name__ == "__main__":
    sys.exit(main())
