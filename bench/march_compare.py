#!/usr/bin/env python3
"""One AIS frame in fog with the media ray march's two distance samplers, both backends.

For each fog scene: one frame of `ais` at the `ais_bench` settings with equiangular distances
(the default, docs/igi.md §6) and with `--uniform-march` (the stratified march alone), on
Embree and OpenCL, seeds 1-3; time, relMSE, HDR-FLIP and HDR-VDP-3 as bench/mode_compare.py
describes, with the ratio equiangular / uniform and the reference's own noise.

Usage: march_compare.py [--tessera build/tessera] [--size 256 256] [--reference DIR]
                        [--reference-spp N|SCENE=N ...] [--floor-spp 256] [--time-passes 4] [--out bench/results/march_compare.md]
Writes Markdown (--out) and JSON beside it.
"""
import sys

from mode_compare import ROOT, Comparison

SCENES = {"cornell-box-fog": ROOT / "scenes/cornell-box-fog.json",
          "sibenik-fog": ROOT / "scenes/sibenik-fog.json"}
MODES = {"equiangular": [], "uniform": ["--uniform-march"]}

COMPARISON = Comparison("march_compare", SCENES, MODES,
                        "Media ray march: equiangular distances against the stratified march (one AIS frame)",
                        "Equiangular: the default (docs/igi.md §6); uniform: `--uniform-march`.", 4096)

if __name__ == "__main__":
    sys.exit(COMPARISON.main(__doc__, "bench/results/march_compare.md"))
