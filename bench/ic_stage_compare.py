#!/usr/bin/env python3
"""Times two tessera binaries' instant-cache stages on the same renders, interleaved (old,
new, old, new, ...) so drift on the machine hits both alike: the cache's gather kernel
and gather stage, its place+gather stage (ms, the log's ic line) and the pass time
(--stats-json), medians over the repeats, both backends in one run.

Usage: bench/ic_stage_compare.py OLD_TESSERA NEW_TESSERA [--repeats N] [--size N]
       [--method ic|tic] [--spp N] [--scenes a b ...]   (prints a markdown table)
Scenes are names in scenes/ or paths; TESSERA_DATA names the data directory (Sibenik).
Each render is one pass at the CLI's defaults but for size and spp; the figures are the
last pass's (the log's "last frame")."""
import argparse
import json
import os
import re
import statistics
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GATHER = re.compile(r"gathers ([0-9.]+) \(kernel ([0-9.]+)\)")
PLACE = re.compile(r"place\+gather ([0-9.]+) ms")


def scene_path(name):
    return name if os.path.exists(name) else os.path.join(ROOT, "scenes", name + ".json")


def run(binary, scene, backend, args, tmp):
    out, stats = os.path.join(tmp, "out.exr"), os.path.join(tmp, "stats.json")
    cmd = [binary, "render", scene_path(scene), "--backend", backend, "--method", args.method, "--spp",
           str(args.spp), "--width", str(args.size), "--height", str(args.size), "--out", out,
           "--stats-json", stats]
    log = subprocess.run(cmd, capture_output=True, text=True, check=True).stderr
    g, p = GATHER.search(log), PLACE.search(log)
    with open(stats) as f:
        pass_s = json.load(f)["median_pass_seconds"]
    return float(g.group(1)), float(g.group(2)), float(p.group(1)), pass_s * 1e3


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--spp", type=int, default=1)
    ap.add_argument("--method", default="ic", choices=["ic", "tic"])
    ap.add_argument("--scenes", nargs="+", default=["cornell-box-fog", "sibenik-fog", "office-fog"])
    args = ap.parse_args()
    names = ["gather kernel", "gather stage", "place+gather", "pass"]
    print(f"| scene | backend | {' | '.join(f'{n} old / new ms (new/old)' for n in names)} |")
    print("|---|---|" + "---|" * len(names))
    with tempfile.TemporaryDirectory() as tmp:
        for scene in args.scenes:
            for backend in ("embree", "opencl"):
                run(args.old, scene, backend, args, tmp)  # warm the program cache and the files
                run(args.new, scene, backend, args, tmp)
                old, new = [], []
                for _ in range(args.repeats):
                    old.append(run(args.old, scene, backend, args, tmp))
                    new.append(run(args.new, scene, backend, args, tmp))
                cells = []
                for k in (1, 0, 2, 3):
                    o = statistics.median(r[k] for r in old)
                    n = statistics.median(r[k] for r in new)
                    cells.append(f"{o:.1f} / {n:.1f} ({n / o:.2f})")
                print(f"| {scene} | {backend} | {' | '.join(cells)} |", flush=True)


if __name__ == "__main__":
    main()
