#!/usr/bin/env python3
"""Mean HDR-FLIP error of a test EXR against a reference EXR, from NVIDIA's reference
implementation of FLIP (the PyPI package `flip-evaluator`, module `flip_evaluator`).

FLIP: Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020;
HDR-FLIP: Andersson et al., "Visualizing Errors in Rendered High Dynamic Range Images",
Eurographics 2021 short papers. HDR mode, the package defaults: 67 pixels per degree, ACES
tone mapper, exposure range computed from the reference. Inputs are linear RGB radiance.

Prints one JSON object on stdout:
  {"mean": mean FLIP error in [0, 1],
   "p_gt_0_1": % of pixels with FLIP error > 0.1, "p_gt_0_3": % with error > 0.3,
   "width": W, "height": H, "implementation": "flip-evaluator <version>"}
`--map FILE.png` also writes the FLIP error map (magma colour map, as the FLIP tool does).

Exit status: 0 on success; 3 if `flip_evaluator` (or numpy, OpenEXR) cannot be imported (the
message says so: `tessera compare` then reports FLIP as unavailable); 2 for bad input.
`tessera compare` runs this script (TESSERA_SOURCE_DIR/bench/flip_metric.py).
"""
import argparse
import json
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("reference")
    ap.add_argument("test")
    ap.add_argument("--map", help="write the FLIP error map (magma) to this PNG")
    args = ap.parse_args()
    try:
        import numpy as np
        import flip_evaluator as flip
        # The one EXR reader of the metric scripts; in the try: a copy of this script
        # elsewhere ($TESSERA_FLIP_SCRIPT) without it beside reports FLIP unavailable.
        from cvvdp_metric import BadInput, read_rgb
    except ImportError as e:
        print(f"flip_metric: {e} (install with: python3 -m pip install flip-evaluator)", file=sys.stderr)
        return 3
    try:
        from importlib.metadata import version
        impl = "flip-evaluator " + version("flip-evaluator")
    except Exception:
        impl = "flip-evaluator"

    # Read with OpenEXR, as tessera and the cvvdp script read them: the package's own loader
    # (tinyexr) returns a DECREASING_Y file upside down (FLIP 0.65 for an image against
    # itself) and refuses B44, DWAA and PXR24.
    try:
        import OpenEXR
        ref, test = (read_rgb(path, np, OpenEXR) for path in (args.reference, args.test))
    except ImportError as e:
        print(f"flip_metric: {e} (install with: python3 -m pip install OpenEXR)", file=sys.stderr)
        return 3
    except BadInput as e:
        print(f"flip_metric: {e}", file=sys.stderr)
        return 2
    if ref.shape != test.shape:
        print(f"flip_metric: image sizes differ: {ref.shape[1]}x{ref.shape[0]} vs {test.shape[1]}x{test.shape[0]}",
              file=sys.stderr)
        return 2
    if not np.any(ref > 0.0):
        # HDR-FLIP takes its exposure range from the reference's luminance: none for black.
        if np.any(test > 0.0):
            print("flip_metric: the reference is black everywhere: HDR-FLIP takes its exposure range from the "
                  "reference, so it has none to compare with", file=sys.stderr)
            return 2
        errmap, mean = np.zeros(ref.shape[:2]), 0.0  # black against black: no difference
        if args.map:
            write_png(args.map, np.zeros(ref.shape))
    else:
        errmap, mean = evaluate(flip, np, ref, test, args.map)
    print(json.dumps({
        "mean": float(mean),
        "p_gt_0_1": 100.0 * float(np.mean(errmap > 0.1)),
        "p_gt_0_3": 100.0 * float(np.mean(errmap > 0.3)),
        "width": int(ref.shape[1]), "height": int(ref.shape[0]),
        "implementation": impl,
    }))
    return 0


def evaluate(flip, np, ref, test, map_path):
    """(HxW FLIP error map, mean) of HDR-FLIP; writes the magma map to map_path if given."""
    errmap, mean, _params = flip.evaluate(ref, test, "HDR", applyMagma=False)
    errmap = np.asarray(errmap).reshape(ref.shape[0], ref.shape[1], -1)[:, :, 0]
    if map_path:
        magma, _, _ = flip.evaluate(ref, test, "HDR", applyMagma=True, computeMeanError=False)
        write_png(map_path, np.asarray(magma))
    return errmap, mean


def write_png(path, rgb01):
    """Writes an HxWx3 array in [0, 1] (already display-encoded) as an 8-bit PNG, with
    matplotlib if present, else the minimal zlib encoder below (no extra dependency)."""
    import numpy as np
    import struct
    import zlib
    data = (np.clip(rgb01, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)
    h, w = data.shape[:2]
    raw = b"".join(b"\x00" + data[y].tobytes() for y in range(h))

    def chunk(tag, payload):
        return struct.pack(">I", len(payload)) + tag + payload + struct.pack(">I", zlib.crc32(tag + payload) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) + \
        chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


if __name__ == "__main__":
    sys.exit(main())
