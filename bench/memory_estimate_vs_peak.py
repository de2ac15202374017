#!/usr/bin/python3
"""The memory guard's estimate against the measured peak, over the benchmark set.

Runs `bemshape thickness` on spheres, thin-walled hollow boxes, the labelled parts
(tests/support/labelled_parts.hpp, `make_test_mesh part NAME`), the bundled plate with holes and
the large tray, one after the other, and prints for each run the solver faces, the solver,
the guard's bound on the process's resident size (the report's memory.estimate_mb, checked
before anything is assembled) and the peak resident size (memory.peak_mb, VmHWM at the end
of the run). The bound holds where estimate ≥ peak; the last column is their ratio.

    bench/memory_estimate_vs_peak.py BUILD_DIR [WORK_DIR] [--only NAME,...]

BUILD_DIR holds apps/bemshape and tests/apps/make_test_mesh. The runs take a few minutes on
two cores; run them alone on the machine (they measure memory, and time only as a remark).
"""
import json
import os
import subprocess
import sys
import time

# name, make_test_mesh arguments (the output file appended), thickness options
CASES = [
    ("sphere 0.5, dense", ["sphere", "0.5", "0.05"], ["--h0", "0.3", "--solver", "dense"]),
    ("sphere 0.5, 2e4 faces", ["sphere", "0.5", "0.02"],
     ["--h0", "0.3", "--max-edge", "0.02", "--solver", "hmatrix"]),
    ("hollow box 1, wall 0.1, edge 0.05", ["hollow-box", "1", "0.1", "0.05"],
     ["--h0", "0.1", "--max-edge", "0.05", "--solver", "hmatrix"]),
    ("taper, h0 4", ["part", "taper"], ["--h0", "4"]),
    ("t-junction, h0 4", ["part", "t-junction"], ["--h0", "4"]),
    ("boss-tab, h0 4", ["part", "boss-tab"], ["--h0", "4"]),
    ("plate-holes, h0 4", ["part", "plate-holes"], ["--h0", "4"]),
    ("bent-bracket, h0 3", ["part", "bent-bracket"], ["--h0", "3"]),
    ("l-bracket, h0 3", ["part", "l-bracket"], ["--h0", "3"]),
    ("tube, h0 3", ["part", "tube"], ["--h0", "3"]),
    ("plate_holes.STL, h0 12.7, edge 3.4", None, ["--h0", "12.7", "--max-edge", "3.4"]),
    ("large-tray, h0 3, edge 6", ["part", "large-tray"], ["--h0", "3", "--max-edge", "6"]),
    ("tray, h0 2.5", ["part", "tray"], ["--h0", "2.5"]),
    ("hollow box 1, wall 0.1, edge 0.025", ["hollow-box", "1", "0.1", "0.025"],
     ["--h0", "0.1", "--max-edge", "0.025", "--solver", "hmatrix"]),
    ("sphere 0.5, 1e5 faces", ["sphere", "0.5", "0.0085"],
     ["--h0", "0.3", "--max-edge", "0.0085", "--solver", "hmatrix"]),
    ("sphere 0.5, 1e5 faces, H2", ["sphere", "0.5", "0.0085"],
     ["--h0", "0.03", "--max-edge", "0.0085", "--solver", "hmatrix", "--far-field", "nested"]),
    ("hollow box, edge 0.025, H2", ["hollow-box", "1", "0.1", "0.025"],
     ["--h0", "0.1", "--max-edge", "0.025", "--solver", "hmatrix", "--far-field", "nested"]),
    ("large-tray, h0 3, edge 3", ["part", "large-tray"], ["--h0", "3", "--max-edge", "3"]),
    # Small runs, a minute or less each on two cores.
    ("sphere 0.5, dense, edge 0.09", ["sphere", "0.5", "0.09"], ["--h0", "0.3", "--solver", "dense"]),
    ("sphere 0.5, edge 0.04", ["sphere", "0.5", "0.04"],
     ["--h0", "0.3", "--max-edge", "0.04", "--solver", "hmatrix"]),
    ("hollow box 1, wall 0.1, edge 0.08", ["hollow-box", "1", "0.1", "0.08"],
     ["--h0", "0.1", "--max-edge", "0.08", "--solver", "hmatrix"]),
    ("l-bracket, h0 3, edge 2", ["part", "l-bracket"], ["--h0", "3", "--max-edge", "2"]),
    ("large-tray, h0 3, edge 8", ["part", "large-tray"], ["--h0", "3", "--max-edge", "8"]),
]


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--only")]
    only = None
    for i, a in enumerate(sys.argv):
        if a == "--only":
            only = set(sys.argv[i + 1].split(","))
            args.remove(sys.argv[i + 1])
    if not args:
        sys.exit(__doc__)
    build = os.path.abspath(args[0])
    work = os.path.abspath(args[1] if len(args) > 1 else "memory_bench")
    os.makedirs(work, exist_ok=True)
    bemshape = os.path.join(build, "apps", "bemshape")
    make_mesh = os.path.join(build, "tests", "apps", "make_test_mesh")
    source = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    print(f"{'case':38s} {'faces':>8s} {'solver':18s} {'estimate MB':>12s} {'peak MB':>9s} "
          f"{'est/peak':>8s} {'wall s':>7s}")
    failures = 0
    for k, (name, mesh_args, options) in enumerate(CASES):
        if only and str(k) not in only and name not in only:
            continue
        if mesh_args is None:
            mesh = os.path.join(source, "tests", "data", "meshes", "plate_holes.STL")
        else:
            mesh = os.path.join(work, f"case{k}.stl")
            if not os.path.exists(mesh):
                subprocess.run([make_mesh] + mesh_args + [mesh], check=True,
                               stdout=subprocess.DEVNULL)
        report = os.path.join(work, f"case{k}.json")
        if os.path.exists(report):
            os.remove(report)
        start = time.time()
        run = subprocess.run(["nice", bemshape, "thickness", mesh, "--quiet", "--report", report,
                              "-o", os.path.join(work, f"case{k}.csv")] + options,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        wall = time.time() - start
        if run.returncode != 0:
            print(f"{name:38s} exit {run.returncode}: {run.stderr.strip()}")
            failures += run.returncode < 0 or run.returncode > 2
            continue
        with open(report) as f:
            r = json.load(f)
        solve = r["solver"]
        memory = r["memory"]
        estimate, peak = memory["estimate_mb"], memory["peak_mb"]
        holds = "" if estimate >= peak else "  BELOW THE PEAK"
        failures += estimate < peak
        print(f"{name:38s} {r['mesh']['solver_faces']:8d} {solve['method']:18s} "
              f"{estimate:12.0f} {peak:9.0f} {estimate / peak:8.2f} {wall:7.1f}{holds}",
              flush=True)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
