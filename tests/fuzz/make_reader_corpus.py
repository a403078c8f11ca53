#!/usr/bin/env python3
"""Writes the seed corpora of the input-reader fuzzers (input_readers_fuzzer.cpp) into
tests/fuzz/readers/<reader>/: camera paths and input scripts (small valid and invalid
files, and the shipped fly-through of the Cornell box), checkpoints in the format of
host/render/checkpoint.h with the identity the fuzzer expects (4x3, "direct", seed 1,
...), and small EXR images. The EXR seeds are written by `tessera render`; pass the
executable as the first argument (default build/tessera). Replaces the seed-* files."""
import math
import pathlib
import shutil
import struct
import subprocess
import sys
import tempfile

root = pathlib.Path(__file__).resolve().parents[2]
out = root / "tests" / "fuzz" / "readers"
CAM = '{"position": [0.278, 0.273, -0.8], "look_at": [0.278, 0.273, 0], "up": [0, 1, 0], "vfov": 39.3077'


def seeds(reader, items):
    d = out / reader
    d.mkdir(parents=True, exist_ok=True)
    for old in d.glob("seed-*"):
        old.unlink()
    for name, data in items.items():
        (d / f"seed-{name}").write_bytes(data if isinstance(data, bytes) else data.encode())


def fnv1a64(data, h=0xCBF29CE484222325):
    for b in data:
        h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def checkpoint(passes=2, nan_at=None):
    """A 4x3 checkpoint of the fuzzer's identity (input_readers_fuzzer.cpp identity())."""
    def string(s):
        return struct.pack("<I", len(s)) + s.encode()
    ident = (string("/scenes/box.json") + struct.pack("<QQ", 42, 43) + string("direct") +
             struct.pack("<IIIIii", 1, 8, 0, 0, 4, 3) + string("embree") + string(""))  # no method settings
    n, floats = 12, 10  # pixels, TS_PASS_FLOATS
    head = (b"TSCKPT01" + struct.pack("<IIiiIIQ", 3, floats, 4, 3, passes, 4, fnv1a64(ident)) + ident +
            struct.pack("<I", 0))  # version 3; no method sums (direct keeps none)
    sums = [0.25 * (i % 7) * passes for i in range(n * floats)]
    if nan_at is not None:
        sums[nan_at] = math.nan
    body = (struct.pack(f"<{n * floats}d", *sums) + struct.pack(f"<{n * 3}d", *[0.1] * (n * 3)) +
            struct.pack(f"<{n}I", *[passes] * n))
    data = head + body
    return data + struct.pack("<Q", fnv1a64(data))


def exr_seeds(exe):
    items = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, (method, w, h) in {"direct-4x3": ("direct", 4, 3), "pt-2x2": ("pt", 2, 2)}.items():
            img = pathlib.Path(tmp) / f"{name}.exr"
            cmd = [str(exe), "render", "--backend", "embree", "--spp", "1", "--method", method, "--width", str(w),
                   "--height", str(h), "--out", str(img)]
            subprocess.run(cmd, check=True, capture_output=True)
            items[name] = img.read_bytes()
    return items


def main():
    exe = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else root / "build" / "tessera")
    seeds("camera_path", {
        "one": '{"cameras": [' + CAM + "}]}",
        "frames": '{"cameras": [' + CAM + ', "frame": 0}, ' + CAM + ', "frame": 3}]}',
        "degenerate": '{"cameras": [' + CAM + '}, {"position": [0,0,0], "look_at": [0,1,0], "up": [0,1,0], "vfov": 40}]}',
        "cornell-flythrough": (root / "bench" / "flythroughs" / "cornell-box.json").read_text(),
    })
    seeds("input_script", {
        "all-actions": '{"events": [{"frame": 0, "press": "w"}, {"frame": 2, "release": "w"}, '
                       '{"frame": 3, "tap": "space"}, {"frame": 4, "drag": [10, -2.5]}, '
                       '{"frame": 5, "scroll": -1}, {"frame": 9, "quit": true}]}',
        "two-actions": '{"events": [{"frame": 1, "tap": "p", "quit": true}]}',
        "comment": '{"comment": "x", "events": [{"frame": 0, "tap": "escape", "_note": 1}]}',
    })
    seeds("checkpoint", {"valid": checkpoint(), "nan-sum": checkpoint(nan_at=5), "zero-passes": checkpoint(0)})
    seeds("exr", exr_seeds(exe))


if __name__ == "__main__":
    main()
