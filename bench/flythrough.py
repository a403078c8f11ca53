#!/usr/bin/env python3
"""Writes the committed fly-throughs of the standard scenes, bench/flythroughs/<scene>.json
(with the scene's name as "scene"), for `tessera view --headless --camera-path` (bench/interactive). Each path starts at the
scene's camera and moves forward by 2% of the look distance per frame while turning left
by 1 degree per frame: every frame is a moving frame (one fresh interleaved frame of the
method), as under a user's continuous motion. Deterministic; run it again only to change
the paths.

Usage: bench/flythrough.py [--frames N]   (default 6)
"""
import argparse
import json
import math
from pathlib import Path

from standard_scenes import STANDARD_SCENES

ROOT = Path(__file__).resolve().parent.parent


def path_for(camera, frames):
    p = camera["position"]
    look = camera["look_at"]
    d = [look[i] - p[i] for i in range(3)]
    dist = math.sqrt(sum(x * x for x in d))
    f = [x / dist for x in d]
    cams = []
    for k in range(frames):
        a = math.radians(1.0 * k)  # yaw about +y (every standard scene's up)
        fx = f[0] * math.cos(a) + f[2] * math.sin(a)
        fz = -f[0] * math.sin(a) + f[2] * math.cos(a)
        fk = [fx, f[1], fz]
        pos = [p[i] + 0.02 * dist * k * f[i] for i in range(3)]
        cams.append({"position": [round(x, 6) for x in pos],
                     "look_at": [round(pos[i] + dist * fk[i], 6) for i in range(3)],
                     "up": camera["up"], "vfov": camera["vfov"], "frame": 0})
    return {"cameras": cams}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--frames", type=int, default=6)
    args = ap.parse_args()
    out = ROOT / "bench" / "flythroughs"
    out.mkdir(exist_ok=True)
    for name in STANDARD_SCENES:
        scene = json.loads((ROOT / "scenes" / f"{name}.json").read_text())
        cams = path_for(scene["camera"], args.frames)["cameras"]
        # "scene": the scene's name, so that the viewer can say when a path is replayed on
        # another scene.
        text = ("{\"scene\": " + json.dumps(scene.get("name", name)) + ",\n \"cameras\": [\n" +
                ",\n".join("  " + json.dumps(c) for c in cams) + "\n]}\n")
        (out / f"{name}.json").write_text(text)
        print(out / f"{name}.json")


if __name__ == "__main__":
    main()
