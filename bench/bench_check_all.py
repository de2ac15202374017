#!/usr/bin/python3
"""`bemshape check-all --jobs 2` against the same parts checked one after another, in the
same run.

The set: the labelled parts (tests/support/labelled_parts.hpp, `make_test_mesh part NAME`)
with their round walls at 64 segments, four with round walls again at 32 and 48 segments and
three at 24, the bundled plate tests/data/meshes/plate_holes.STL, and one unreadable file (a
binary STL cut in half): 20 parts. The tube is left out: at the coarse meshes that keep the
set short its solve does not converge (GMRES stops at 600 iterations after 6 minutes at
--max-edge 12), and at its default mesh it alone takes minutes. Both ways run each part as
`bemshape thickness PART ...` with the same options:

    serial    one part after the other, --threads 2 each (what a shell loop does);
    check-all --jobs 2 (one thread each on two cores): one report per part, the summary.

It prints the two wall times and their ratio, the CPU time of each (user + system of the
processes), the verdicts, and checks that the unreadable part is reported and every other
part has a verdict.

    bench/bench_check_all.py BUILD_DIR [--jobs 2] [--threads 2] [--work DIR] [-- OPTIONS...]

BUILD_DIR holds apps/bemshape and tests/apps/make_test_mesh. OPTIONS go to every part of
both runs (default: --min-thickness 1 --measure sphere --h0 8 --max-edge 8: a coarse mesh
and no mid-surface search, which keep the set to a few minutes on two cores). docs/benchmarks.md,
"Many parts: check-all against a shell loop", quotes the figures.
"""
import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

LABELLED_PARTS = ["plate-holes", "l-bracket", "boss-tab", "tray", "bent-bracket", "t-junction",
                  "taper"]
# Variants: the parts with round walls at other numbers of segments.
VARIANTS = [(32, ["plate-holes", "boss-tab", "bent-bracket", "t-junction"]),
            (48, ["plate-holes", "boss-tab", "bent-bracket", "t-junction"]),
            (24, ["plate-holes", "boss-tab", "t-junction"])]
DEFAULT_OPTIONS = ["--min-thickness", "1", "--measure", "sphere", "--h0", "8", "--max-edge", "8"]


def make_parts(build, folder):
    """Writes the 20 parts into `folder`; returns their paths, the unreadable one last but
    one (in path order it sits among the others)."""
    source = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    make = os.path.join(build, "tests", "apps", "make_test_mesh")
    os.makedirs(folder, exist_ok=True)
    paths = []

    def part(name, segments):
        out = os.path.join(folder, f"{name}-{segments}.stl")
        subprocess.run([make, "part", name, out, str(segments)], check=True,
                       stdout=subprocess.DEVNULL)
        paths.append(out)

    for name in LABELLED_PARTS:
        part(name, 64)
    for segments, names in VARIANTS:
        for name in names:
            part(name, segments)
    plate = os.path.join(folder, "plate_holes.stl")
    shutil.copy(os.path.join(source, "tests", "data", "meshes", "plate_holes.STL"), plate)
    paths.append(plate)
    unreadable = os.path.join(folder, "broken-export.stl")
    with open(os.path.join(folder, "t-junction-32.stl"), "rb") as f:
        data = f.read()
    with open(unreadable, "wb") as f:
        f.write(data[: len(data) // 2])  # a binary STL cut in half: a broken export
    paths.append(unreadable)
    return sorted(paths)


def children_cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--threads", type=int, default=2, help="threads of each serial run")
    parser.add_argument("--work", help="folder for the parts and reports (default: a "
                        "temporary folder, removed at the end)")
    # argparse cannot take a positional list after BUILD_DIR once "--" is given: split here.
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    args = parser.parse_args(argv[:split])
    options = argv[split + 1:] or DEFAULT_OPTIONS
    bemshape = os.path.join(args.build, "apps", "bemshape")
    work = args.work or tempfile.mkdtemp(prefix="bench_check_all_")
    os.makedirs(work, exist_ok=True)
    try:
        parts = make_parts(args.build, os.path.join(work, "parts"))
        print(f"{len(parts)} parts, options {' '.join(options)}, {os.cpu_count()} cores",
              flush=True)

        serial_reports = os.path.join(work, "serial")
        os.makedirs(serial_reports, exist_ok=True)
        cpu = children_cpu_seconds()
        start = time.monotonic()
        serial_codes = {}
        for path in parts:
            report = os.path.join(serial_reports, os.path.basename(path) + ".json")
            run = subprocess.run([bemshape, "thickness", path, "--threads", str(args.threads),
                                  "--quiet", "--report", report, *options],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            serial_codes[path] = run.returncode
        serial_seconds = time.monotonic() - start
        serial_cpu = children_cpu_seconds() - cpu
        print(f"serial    (--threads {args.threads}): {serial_seconds:8.1f} s wall, "
              f"{serial_cpu:8.1f} s CPU", flush=True)

        reports = os.path.join(work, "check-all")
        cpu = children_cpu_seconds()
        start = time.monotonic()
        run = subprocess.run([bemshape, "check-all", *parts, "--reports", reports, "--jobs",
                              str(args.jobs), "--quiet", *options],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        set_seconds = time.monotonic() - start
        set_cpu = children_cpu_seconds() - cpu
        print(f"check-all (--jobs {args.jobs}):    {set_seconds:8.1f} s wall, "
              f"{set_cpu:8.1f} s CPU, exit {run.returncode}", flush=True)
        print(f"ratio check-all / serial: {set_seconds / serial_seconds:.3f} (wall), "
              f"{set_cpu / serial_cpu:.3f} (CPU)")

        with open(os.path.join(reports, "summary.jsonl")) as f:
            records = [json.loads(line) for line in f]
        counts = {}
        for r in records:
            counts[r["verdict"]] = counts.get(r["verdict"], 0) + 1
        print("verdicts: " + ", ".join(f"{n} {v}" for v, n in sorted(counts.items())))
        problems = []
        if [r["part"] for r in records] != parts:
            problems.append("the summary does not list every part in order")
        for r in records:
            expected_code = serial_codes[r["part"]]
            if r["exit_code"] != expected_code:
                problems.append(f"{r['part']}: check-all {r['exit_code']}, serial {expected_code}")
            if r["part"].endswith("broken-export.stl"):
                if r["verdict"] != "error":
                    problems.append("the unreadable part was not reported as an error")
                else:
                    print(f"unreadable part: {r['error']}")
            elif r["verdict"] not in ("pass", "thin"):
                problems.append(f"{r['part']}: {r['verdict']}: {r['error']}")
        for p in problems:
            print("problem: " + p)
        return 1 if problems else 0
    finally:
        if not args.work:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
