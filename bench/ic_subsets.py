#!/usr/bin/env python3
"""`ic` with M path subsets (docs/instant-caching.md §2b): region error, per-pixel error and
time against M = 1, on both backends.

For each scene (`tests/data/two-rooms`, the Cornell box) a `pt` reference (Embree, --ref-spp),
then `ic --spp 16 --ic-subsets M` for each M and backend over seeds 1..--seeds. Per row:
the median time of one render and its ratio to M = 1 on the same backend; the largest
standard deviation over seeds of a 4 x 3 region's mean / the reference's (one render's
region noise); the median over seeds of the worst region's |ratio - 1|; the renders with
every region within 2%; the worst region of the seeds' average (bias plus 1/seeds of the
variance); the median relMSE; and (Embree, seeds 1-6) the mean HDR-FLIP error
(bench/flip_metric.py). Writes Markdown (--out) and JSON beside it.

The time ratio is to the first M given (--subsets), on the same backend.

Usage: ic_subsets.py [--tessera build/tessera] [--seeds 16] [--subsets 1 2 4 8]
                     [--backends embree opencl] [--size 128 96] [--scenes two-rooms cornell-box]
                     [--ref-spp 8192 4096] [--out FILE]
Needs numpy and flip-evaluator (its EXR loader).
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ic_convergence import GRID, ROOT, luminance, write_results  # noqa: E402
import numpy as np  # noqa: E402

SCENES = {"two-rooms": (ROOT / "tests/data/two-rooms/two-rooms.json", 8192),
          "cornell-box": (ROOT / "scenes/cornell-box.json", 4096)}


def render(binary, scene, args, out):
    cmd = [binary, "render", str(scene), *args, "--out", str(out)]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def regions(img, ref):
    h, w = ref.shape
    out = []
    for j in range(GRID[1]):
        for i in range(GRID[0]):
            ys = slice(j * h // GRID[1], (j + 1) * h // GRID[1])
            xs = slice(i * w // GRID[0], (i + 1) * w // GRID[0])
            out.append(float(img[ys, xs].mean() / ref[ys, xs].mean()))
    return np.array(out)


def seed_stats(images, ref):
    """The region figures of renders `images` (luminance, one per seed) against `ref`, as
    the tables report them: per-seed regions (seeds x regions), the largest region sd, the
    median worst region, the renders with every region within 2%, the worst region of
    the seeds' mean image and the median relMSE."""
    reg = np.array([regions(img, ref) for img in images])
    worst = np.abs(reg - 1.0).max(axis=1)
    rel = [float(((img - ref) ** 2 / (ref ** 2 + 1e-2)).mean()) for img in images]
    return reg, {"largest_region_sd": float(reg.std(axis=0, ddof=1).max()),
                 "median_worst_region": float(np.median(worst)),
                 "within_2pct": f"{int((worst <= 0.02).sum())} of {len(images)}",
                 "average_worst_region": float(np.abs(regions(np.mean(images, axis=0), ref) - 1).max()),
                 "median_relmse": float(statistics.median(rel)),
                 "region_sd": reg.std(axis=0, ddof=1).round(4).tolist()}


def flip_mean(ref_path, test_path):
    res = subprocess.run([sys.executable, str(ROOT / "bench/flip_metric.py"), str(ref_path), str(test_path)],
                         check=True, capture_output=True, text=True)
    return json.loads(res.stdout)["mean"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessera", default=str(ROOT / "build/tessera"))
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--subsets", type=int, nargs="+", default=[1, 2, 4, 8])
    ap.add_argument("--backends", nargs="+", default=["embree", "opencl"])
    ap.add_argument("--size", nargs=2, type=int, default=[128, 96])
    ap.add_argument("--scenes", nargs="+", default=list(SCENES), choices=list(SCENES))
    ap.add_argument("--ref-spp", nargs=2, type=int, default=[SCENES[n][1] for n in SCENES],
                    help="pt reference spp of the two rooms and the Cornell box")
    ap.add_argument("--flip-seeds", type=int, default=6)
    ap.add_argument("--out", default=str(ROOT / "bench/results/ic_subsets.md"))
    args = ap.parse_args()
    size = ["--width", str(args.size[0]), "--height", str(args.size[1])]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for name in args.scenes:
            scene, ref_spp = SCENES[name][0], dict(zip(SCENES, args.ref_spp))[name]
            ref_path = tmp / f"{name}-ref.exr"
            render(args.tessera, scene, ["--method", "pt", "--spp", str(ref_spp), "--backend", "embree", *size],
                   ref_path)
            ref = luminance(ref_path)
            for backend in args.backends:
                base_time = None
                for m in args.subsets:
                    times, flips, images = [], [], []
                    for seed in range(1, args.seeds + 1):
                        out = tmp / f"t{seed}.exr"
                        times.append(render(args.tessera, scene, ["--method", "ic", "--spp", "16", "--ic-subsets",
                                                                  str(m), "--seed", str(seed), "--backend", backend,
                                                                  *size], out))
                        images.append(luminance(out))
                        if backend == "embree" and seed <= args.flip_seeds:
                            flips.append(flip_mean(ref_path, out))
                    _, stats = seed_stats(images, ref)
                    t = statistics.median(times)
                    base_time = t if m == args.subsets[0] else base_time
                    row = {"scene": name, "backend": backend, "subsets": m, "time": t,
                           "time_ratio": t / base_time if base_time else float("nan"), **stats,
                           "flip": f"{statistics.fmean(flips):.4f}" if flips else "—"}
                    rows.append(row)
                    print(json.dumps({k: v for k, v in row.items() if k != "region_sd"}), flush=True)
    columns = [("scene", "scene", ""), ("backend", "backend", ""), ("M", "subsets", ""), ("time (s)", "time", ".2f"),
               (f"× M = {args.subsets[0]}", "time_ratio", ".2f"), ("largest region sd", "largest_region_sd", ".3f"),
               ("median worst region", "median_worst_region", ".3f"), ("within 2%", "within_2pct", ""),
               ("average's worst region", "average_worst_region", ".3f"), ("median relMSE", "median_relmse", ".5f"),
               ("mean FLIP", "flip", "")]
    write_results(args.out, {"machine": f"{platform.node()} {os.cpu_count()} cores", "seeds": args.seeds,
                             "size": args.size, "spp": 16}, rows,
                  f"`ic` path subsets: region error and time ({args.size[0]}x{args.size[1]}, 16 spp, seeds 1-"
                  f"{args.seeds})",
                  "Written by `bench/ic_subsets.py`. References: `pt` on Embree, "
                  + ", ".join(f"{n} {dict(zip(SCENES, args.ref_spp))[n]:,} spp" for n in args.scenes) + ". Regions: the 4x3 grid. largest region sd: over seeds, one render's region noise; "
                  "median worst region: |mean / reference - 1| of the worst region, median over seeds; within 2%: "
                  "renders with every region within 2%; average's worst region: of the seeds' mean image; mean FLIP: "
                  "HDR-FLIP, Embree, seeds 1-" f"{args.flip_seeds}; time: median of one render (16 passes) with its "
                  f"ratio to M = {args.subsets[0]} on the same backend.",
                  columns)
    return 0


if __name__ == "__main__":
    sys.exit(main())
