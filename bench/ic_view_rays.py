#!/usr/bin/env python3
"""`ic`'s paths kept for the view with view rays (docs/instant-caching.md §2): region error
and time of `ic` settings and binaries against a `pt` reference, on both backends.

Each --config is LABEL=BACKENDS=ARGS (BACKENDS: embree, opencl or both; ARGS: `ic` options,
with `bin:PATH` as the first word to run another tessera binary, e.g. an earlier commit's
for the "before" row). For each config and backend, `ic --spp 16` over seeds 1..--seeds at
the scene's own camera size; per row, as bench/ic_subsets.py: the median time of one
render and its ratio to the first row on the same backend, the largest sd over seeds of a
4 x 3 region's mean / the reference's, the median worst region, the renders with every
region within 2%, the worst region of the seeds' mean image, the median relMSE, and the
near room's level: the sd over seeds of the mean of the regions the light reaches only
through the doorway (all but the four around it). The reference is rendered (`pt`,
Embree, --ref-spp) unless --reference gives an EXR of it. Writes Markdown (--out) and JSON.

Usage: ic_view_rays.py [--tessera build/tessera] [--seeds 16] [--reference REF.exr]
                       [--ref-spp 2048] --config LABEL=BACKENDS=ARGS ... [--out FILE]
Needs numpy and flip-evaluator (its EXR loader).
"""
import argparse
import json
import os
import platform
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from ic_convergence import ROOT, luminance, write_results  # noqa: E402
from ic_subsets import render, seed_stats  # noqa: E402

SCENE = ROOT / "tests/data/two-rooms/two-rooms.json"
# The 4 x 3 regions (row-major) that see into the lit room through the doorway; the
# others are lit only by light that came through it.
DOORWAY = (5, 6, 9, 10)


def parse_config(text, default_binary):
    label, backends, args = text.split("=", 2)
    words = args.split()
    binary = default_binary
    if words and words[0].startswith("bin:"):
        binary, words = words[0][4:], words[1:]
    return label, (["embree", "opencl"] if backends == "both" else [backends]), binary, words


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessera", default=str(ROOT / "build/tessera"))
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--reference", help="a pt reference EXR of the scene (else rendered)")
    ap.add_argument("--ref-spp", type=int, default=2048)
    ap.add_argument("--config", action="append", required=True, help="LABEL=BACKENDS=ARGS")
    ap.add_argument("--out", default=str(ROOT / "bench/results/ic_view_rays.md"))
    args = ap.parse_args()
    configs = [parse_config(c, args.tessera) for c in args.config]
    rows, first_time = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        ref_path = Path(args.reference) if args.reference else tmp / "ref.exr"
        if not args.reference:
            render(args.tessera, SCENE, ["--method", "pt", "--spp", str(args.ref_spp), "--backend", "embree"], ref_path)
        ref = luminance(ref_path)
        for label, backends, binary, extra in configs:
            for backend in backends:
                times, images = [], []
                for seed in range(1, args.seeds + 1):
                    out = tmp / f"t{seed}.exr"
                    times.append(render(binary, SCENE, ["--method", "ic", "--spp", "16", "--seed", str(seed),
                                                        "--backend", backend, *extra], out))
                    images.append(luminance(out))
                reg, stats = seed_stats(images, ref)
                near = [k for k in range(reg.shape[1]) if k not in DOORWAY]
                t = statistics.median(times)
                first_time.setdefault(backend, t)
                row = {"config": label, "args": " ".join(extra), "backend": backend, "time": t,
                       "time_ratio": t / first_time[backend], **stats,
                       "near_room_level_sd": float(reg[:, near].mean(axis=1).std(ddof=1))}
                rows.append(row)
                print(json.dumps({k: v for k, v in row.items() if k != "region_sd"}), flush=True)
    columns = [("config", "config", ""), ("options", "args", ""), ("backend", "backend", ""),
               ("time (s)", "time", ".2f"), ("× first", "time_ratio", ".2f"),
               ("largest region sd", "largest_region_sd", ".3f"), ("near room level sd", "near_room_level_sd", ".3f"),
               ("median worst region", "median_worst_region", ".3f"), ("within 2%", "within_2pct", ""),
               ("average's worst region", "average_worst_region", ".3f"), ("median relMSE", "median_relmse", ".5f")]
    write_results(args.out, {"machine": f"{platform.node()} {os.cpu_count()} cores", "seeds": args.seeds, "spp": 16,
                             "reference": str(args.reference or f"pt {args.ref_spp} spp")}, rows,
                  f"`ic` paths kept for the view: region error and time (two-rooms, 16 spp, seeds 1-{args.seeds})",
                  "Written by `bench/ic_view_rays.py`. Reference: `pt` on Embree"
                  + (f", {args.ref_spp:,} spp" if not args.reference else "") + ". Regions: the 4x3 grid. "
                  "largest region sd: over seeds; near room level sd: over seeds, of the mean of the 8 regions "
                  "lit only through the doorway; median worst region: |mean / reference - 1| of the worst region, "
                  "median over seeds; within 2%: renders with every region within 2%; time: median of one render "
                  "with its ratio to the first row on the same backend.", columns)
    return 0


if __name__ == "__main__":
    sys.exit(main())
