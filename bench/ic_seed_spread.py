#!/usr/bin/env python3
"""The spread of a method's image over seeds: how much of its error is VPL noise.

Each seed draws its own light paths (docs/igi.md §3), so the spread over seeds of the
image mean (luminance / the `pt` reference's) measures the VPL noise a single render
carries, and the mean over seeds its bias. For each scene and binary (--before BIN for a
before/after table): `pt` reference (Embree), then the method at --spp over seeds
1..--seeds. Reports mean, standard deviation and worst seed of the image mean, the median
worst 4 x 3 region, the median relMSE and the worst region of the seeds' average (bias). Writes Markdown (--out) and JSON beside it.

Usage: ic_seed_spread.py [--tessera build/tessera] [--before BIN] [--method ic] [--spp 16]
                         [--seeds 30] [--size W H] [--reference-spp N] [--out FILE]
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
from ic_convergence import ROOT, compare, render, write_results  # noqa: E402
import numpy as np  # noqa: E402

SCENES = {"two-rooms": ROOT / "tests/data/two-rooms/two-rooms.json",
          "cornell-box": ROOT / "scenes/cornell-box.json"}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessera", default=str(ROOT / "build/tessera"))
    ap.add_argument("--before", help="another tessera binary for the 'before' rows")
    ap.add_argument("--method", default="ic")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--seeds", type=int, default=30)
    ap.add_argument("--size", nargs=2, type=int, default=[128, 96])
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--out", default=str(ROOT / "bench/results/ic_seed_spread.md"))
    args = ap.parse_args()
    binaries = {"before": args.before} if args.before else {}
    binaries["after"] = args.tessera
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for name, scene in SCENES.items():
            ref = render(args.tessera, scene, "pt", args.reference_spp, 1, "embree", args.size, tmp / "ref.exr")
            for label, binary in binaries.items():
                images = [render(binary, scene, args.method, args.spp, seed, "embree", args.size, tmp / "t.exr")
                          for seed in range(1, args.seeds + 1)]
                runs = [compare(img, ref) for img in images]
                means = [r["mean"] for r in runs]
                # The seeds' average keeps the bias and 1/seeds of the variance.
                average = compare(np.mean(images, axis=0), ref)
                row = {"scene": name, "binary": label, "mean": statistics.fmean(means),
                       "sd": statistics.stdev(means), "worst_seed": max(means, key=lambda m: abs(m - 1.0)),
                       "median_worst_region": statistics.median(r["worst_region"] for r in runs),
                       "median_relmse": statistics.median(r["relmse"] for r in runs),
                       "average_worst_region": average["worst_region"], "seeds": means}
                rows.append(row)
                print(json.dumps({k: v for k, v in row.items() if k != "seeds"}), flush=True)
    columns = [("scene", "scene", ""), ("binary", "binary", ""), ("mean", "mean", ".4f"), ("sd", "sd", ".4f"),
               ("worst seed", "worst_seed", ".3f"), ("median worst region", "median_worst_region", ".3f"),
               ("median relMSE", "median_relmse", ".4f"), ("average's worst region", "average_worst_region", ".3f")]
    write_results(args.out, {"machine": f"{platform.node()} {os.cpu_count()} cores", "method": args.method,
                             "spp": args.spp, "seeds": args.seeds, "size": args.size,
                             "reference_spp": args.reference_spp}, rows,
                  f"`{args.method}` over seeds: VPL noise ({args.size[0]}x{args.size[1]}, {args.spp} spp, seeds 1-"
                  f"{args.seeds}, Embree, reference `pt` {args.reference_spp} spp)",
                  "Written by `bench/ic_seed_spread.py`. mean = image mean luminance / the reference's, over the "
                  "seeds; sd its standard deviation over the seeds (the VPL noise of one render); worst region = "
                  "the 4x3 region furthest from 1, median over the seeds; average's worst region: the same for the "
                  "seeds' average image, which keeps the bias (the clamp's) and 1/seeds of the variance.",
                  columns)
    return 0


if __name__ == "__main__":
    sys.exit(main())
