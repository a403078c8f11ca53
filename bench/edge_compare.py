#!/usr/bin/env python3
"""One AIS frame with and without edge samples (AIS's fourth component), both backends.

For each scene of the issue's table (the Cornell box, Sibenik, office, conference): one
frame of `ais` at the `ais_bench` settings with edge samples (the default, docs/ais.md §9)
and without them (`--components ss,id,pm`), on Embree and OpenCL, seeds 1-3; time, relMSE,
HDR-FLIP and HDR-VDP-3 as bench/mode_compare.py describes, with the ratio edges / no edges
and the reference's own noise.

Usage: edge_compare.py [--tessera build/tessera] [--size 256 256] [--reference DIR]
                       [--reference-spp N|SCENE=N ...] [--floor-spp 256] [--time-passes 4] [--out bench/results/edge_compare.md]
Writes Markdown (--out) and JSON beside it.
"""
import sys

from mode_compare import ROOT, Comparison

SCENES = {name: ROOT / f"scenes/{name}.json" for name in ("cornell-box", "sibenik", "office", "conference")}
MODES = {"edges": [], "no edges": ["--components", "ss,id,pm"]}

COMPARISON = Comparison("edge_compare", SCENES, MODES,
                        "Edge samples: one AIS frame with and without them",
                        "Edges: the default, extra camera samples on flagged edge pixels (docs/ais.md §9); no edges: "
                        "`--components ss,id,pm`.", 2500)

if __name__ == "__main__":
    sys.exit(COMPARISON.main(__doc__, "bench/results/edge_compare.md"))
