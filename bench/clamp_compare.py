#!/usr/bin/env python3
"""One AIS frame with and without the clamp's screen-space compensation, both backends.

For the four clear scenes of the edge table (Cornell box, Sibenik, office, conference) and
the five fog scenes (foggy Cornell box, office, Sibenik, subdivided and Shirley 6 in fog):
one frame of `ais` at the `ais_bench` settings with the compensation (the default,
docs/igi.md §4) and without it (`--no-clamp-compensation`), on Embree and OpenCL, seeds
1-3; time, relMSE, HDR-FLIP and HDR-VDP-3 as bench/mode_compare.py describes, with the
ratio compensated / clamped.

Usage: clamp_compare.py [--tessera build/tessera] [--size 256 256] [--reference DIR]
                        [--reference-spp N|SCENE=N ...] [--floor-spp 256] [--time-passes 4]
                        [--scenes ...] [--out bench/results/clamp_screen.md]
Writes Markdown (--out) and JSON beside it.
"""
import sys

from mode_compare import ROOT, Comparison

CLEAR = ("cornell-box", "sibenik", "office", "conference")
FOG = ("cornell-box-fog", "office-fog", "sibenik-fog", "subdivided-fog", "shirley6-fog")
SCENES = {name: ROOT / f"scenes/{name}.json" for name in CLEAR + FOG}
MODES = {"compensated": [], "clamped": ["--no-clamp-compensation"]}

COMPARISON = Comparison("clamp_compare", SCENES, MODES,
                        "The clamp's loss returned from the screen: one AIS frame with and without it",
                        "Compensated: the default, the light the VPL clamp removed estimated from the frame's "
                        "G-buffer and irradiance (docs/igi.md §4); clamped: `--no-clamp-compensation`.", 2500)

if __name__ == "__main__":
    sys.exit(COMPARISON.main(__doc__, "bench/results/clamp_screen.md"))
