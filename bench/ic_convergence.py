#!/usr/bin/env python3
"""Instant caching's convergence against the path tracer, per region, on both backends.

For each scene, renders a `pt` reference (Embree) and then ic, tic and igi at 1, 4 and 16
spp (16 spp with seeds 1-3, each seed its own VPL sets) on Embree and OpenCL, and reports
mean radiance / the reference's (luminance, whole image) and the worst of a 4 x 3 grid of
regions, plus relMSE. With --before BIN also the same columns from another tessera binary
(an earlier commit), for before/after tables. Writes Markdown (--out) and JSON beside it.

Usage: ic_convergence.py [--tessera build/tessera] [--before BIN] [--size W H]
                         [--reference-spp N] [--out bench/results/ic_convergence.md]
Needs numpy and flip-evaluator (its EXR loader).
"""
import argparse
import json
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import flip_evaluator as flip

ROOT = Path(__file__).resolve().parent.parent
SCENES = {"cornell-box": ROOT / "scenes/cornell-box.json",
          "cornell-box-fog": ROOT / "scenes/cornell-box-fog.json",
          "two-rooms": ROOT / "tests/data/two-rooms/two-rooms.json"}
GRID = (4, 3)  # regions across, down


def luminance(path):
    rgb = np.asarray(flip.load(str(path)), dtype=np.float64)[:, :, :3]
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def render(binary, scene, method, spp, seed, backend, size, out):
    cmd = [binary, "render", str(scene), "--method", method, "--spp", str(spp), "--seed", str(seed),
           "--backend", backend, "--width", str(size[0]), "--height", str(size[1]), "--out", str(out)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return luminance(out)


def compare(test, ref):
    h, w = ref.shape
    regions = []
    for j in range(GRID[1]):
        for i in range(GRID[0]):
            ys, xs = slice(j * h // GRID[1], (j + 1) * h // GRID[1]), slice(i * w // GRID[0], (i + 1) * w // GRID[0])
            regions.append(float(test[ys, xs].mean() / ref[ys, xs].mean()))
    worst = max(regions, key=lambda r: abs(r - 1.0))
    rel = float(((test - ref) ** 2 / (ref ** 2 + 1e-2)).mean())
    return {"mean": float(test.mean() / ref.mean()), "worst_region": worst, "relmse": rel}


def write_results(out, meta, rows, title, note, columns):
    """Writes `rows` (dicts) to OUT's .json beside it (`meta` plus the rows) and to OUT as
    Markdown: `title`, `note`, then one table row per row with `columns`, (header, key,
    format spec) triples."""
    out = Path(out)
    out.with_suffix(".json").write_text(json.dumps({**meta, "rows": rows}, indent=1) + "\n")
    lines = [f"# {title}", "", note, "", "| " + " | ".join(c[0] for c in columns) + " |",
             "|" + "---|" * len(columns)]
    for r in rows:
        lines.append("| " + " | ".join(format(r[key], spec) for _, key, spec in columns) + " |")
    out.write_text("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tessera", default=str(ROOT / "build/tessera"))
    ap.add_argument("--before", help="another tessera binary for the 'before' columns")
    ap.add_argument("--size", nargs=2, type=int, default=[128, 96])
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--out", default=str(ROOT / "bench/results/ic_convergence.md"))
    args = ap.parse_args()
    binaries = {"after": args.tessera}
    if args.before:
        binaries["before"] = args.before
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for name, scene in SCENES.items():
            ref = render(args.tessera, scene, "pt", args.reference_spp, 1, "embree", args.size, tmp / "ref.exr")
            ref2 = render(args.tessera, scene, "pt", args.reference_spp, 2, "embree", args.size, tmp / "ref2.exr")
            rows.append({"scene": name, "method": "pt (2nd seed)", "binary": "after", "backend": "embree",
                         "spp": args.reference_spp, "seed": 2, **compare(ref2, ref)})
            for label, binary in binaries.items():
                for backend in ("embree", "opencl"):
                    for method in ("ic", "tic", "igi"):
                        for spp, seeds in ((1, (1,)), (4, (1,)), (16, (1, 2, 3))):
                            for seed in seeds:
                                img = render(binary, scene, method, spp, seed, backend, args.size, tmp / "t.exr")
                                r = {"scene": name, "method": method, "binary": label, "backend": backend,
                                     "spp": spp, "seed": seed, **compare(img, ref)}
                                rows.append(r)
                                print(json.dumps(r), flush=True)
    columns = [("scene", "scene", ""), ("method", "method", ""), ("binary", "binary", ""), ("backend", "backend", ""),
               ("spp", "spp", ""), ("seed", "seed", ""), ("mean", "mean", ".3f"), ("worst region", "worst_region", ".3f"),
               ("relMSE", "relmse", ".4f")]
    write_results(args.out, {"machine": f"{platform.node()} {os.cpu_count()} cores", "size": args.size,
                             "reference_spp": args.reference_spp}, rows,
                  f"Instant caching against `pt`: mean and worst region ({args.size[0]}x{args.size[1]}, "
                  f"reference {args.reference_spp} spp Embree)",
                  "Written by `bench/ic_convergence.py`. mean = mean luminance / the reference's; worst = the "
                  f"{GRID[0]}x{GRID[1]} region furthest from 1; 16 spp: seeds 1, 2, 3 (each its own VPL sets).",
                  columns)
    return 0


if __name__ == "__main__":
    sys.exit(main())
