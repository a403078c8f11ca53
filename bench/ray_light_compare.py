#!/usr/bin/env python3
"""One AIS frame in fog with the ray march's multiple scattering from medium VPLs or from
virtual ray lights, both backends.

For the five fog scenes (foggy Cornell box, office, Sibenik, subdivided and Shirley 6 in
fog): one frame of `ais` at the `ais_bench` settings with the ray lights (the default: a
virtual ray light per light-path segment in the medium, unclamped; docs/igi.md §6) and with
`--point-medium-vpls` (the medium VPLs, clamped), on Embree and OpenCL, seeds 1-3; time,
relMSE, HDR-FLIP and HDR-VDP-3 as bench/mode_compare.py describes, with the ratio ray
lights / point VPLs.

Usage: ray_light_compare.py [--tessera build/tessera] [--size 256 256] [--reference DIR]
                            [--reference-spp N|SCENE=N ...] [--floor-spp 256] [--time-passes 4]
                            [--scenes ...] [--out bench/results/ray_lights.md]
Writes Markdown (--out) and JSON beside it.
"""
import sys

from mode_compare import ROOT, Comparison

FOG = ("cornell-box-fog", "office-fog", "sibenik-fog", "subdivided-fog", "shirley6-fog")
SCENES = {name: ROOT / f"scenes/{name}.json" for name in FOG}
MODES = {"ray lights": [], "point VPLs": ["--point-medium-vpls"]}

COMPARISON = Comparison("ray_light_compare", SCENES, MODES,
                        "Multiple scattering in the ray march: medium VPLs against virtual ray lights (one AIS frame)",
                        "Ray lights: the default, one virtual ray light per light-path segment in the medium, "
                        "unclamped (docs/igi.md §6); point VPLs: `--point-medium-vpls`, the march gathers the light "
                        "paths' medium VPLs (clamped to b/4). Surfaces gather the medium VPLs in both.", 10000)

if __name__ == "__main__":
    sys.exit(COMPARISON.main(__doc__, "bench/results/ray_lights.md"))
