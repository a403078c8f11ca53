#!/usr/bin/env python3
"""HDR-VDP-3 (Mantiuk et al., "HDR-VDP-3: a multi-metric for predicting image differences,
quality and contrast distortions in high dynamic range and regular content", 2023; the
maintained successor of the HDR-VDP the seed thesis validates with, its Table 5.3) of test
EXRs against reference EXRs, run in GNU Octave. Optional: it needs `octave-cli` with the
`statistics` and `image` packages (Debian: apt-get install octave octave-statistics
octave-image) and the HDR-VDP-3 sources (../shared/tools/hdrvdp-3.0.7 beside the
repository, or $TESSERA_HDRVDP / --hdrvdp).

The protocol (../shared/tools/README.md; kept so figures stay comparable with the issue's
and the seed's):
  * images: linear RGB radiance (EXR R, G, B), test and reference of the same size;
  * both scaled by one factor k = 100 / mean(Y_ref), Y = 0.2126 R + 0.7152 G + 0.0722 B, so
    the reference's mean luminance is 100 cd/m^2;
  * hdrvdp3('side-by-side', k*test, k*ref, 'rgb-native', ppd, {'use_gpu', false, 'quiet', true})
    with ppd = hdrvdp_pix_per_deg(24, [1920 1080], 0.5) = 32.45 pixels per degree (a 24-inch
    full-HD display seen from 0.5 m).

Usage: hdrvdp_metric.py REF TEST [REF TEST ...]: one Octave session for all pairs (it
starts in ~3 s; a 256x256 pair then takes 1-3 s). Prints one JSON object per pair, one per
line: "p_ge_75", "p_ge_95" (% of pixels whose probability of a visible difference is >= 75%
/ >= 95%: the seed's Table 5.3 columns), "q_jod" (HDR-VDP-3's quality in JOD, 10 = no
visible difference), "width", "height", "luminance_scale", "reference", "test",
"implementation", "pixels_per_degree".

Exit status: 0 on success; 3 if Octave, its packages or the HDR-VDP-3 sources are missing
(the message says what and how to install); 2 for bad input (unreadable file, no R/G/B
channel, NaN or infinite values, different sizes, a reference with zero mean luminance, an
odd number of paths). `--check` only checks that all of it is there (exit 0 or 3).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from cvvdp_metric import REC709_Y, BadInput, read_rgb

MEAN_LUMINANCE = 100.0  # cd/m^2 of the reference's mean luminance (the protocol)
VERSION = "hdrvdp-3.0.7"
DEFAULT_ROOT = Path(__file__).resolve().parent.parent.parent / "shared" / "tools" / VERSION

# Octave script: read_raw reads a raw float32 HxWx3 file (row-major, as numpy writes it);
# the main part runs the protocol on `pairs` and prints "RESULT i P75 P95 QJOD" per pair.
# The script starts "1;" so that Octave takes it as a script file that may define functions.
OCTAVE_FUNCTIONS = r"""1;
function img = read_raw(path, h, w)
  fid = fopen(path, 'r'); v = fread(fid, Inf, 'single=>double'); fclose(fid);
  img = permute(reshape(v, [3, w, h]), [3 2 1]);
end
"""
OCTAVE_MAIN = r"""
pkg load statistics; pkg load image;
addpath(hdrvdp_root);
ppd = hdrvdp_pix_per_deg(24, [1920 1080], 0.5);
printf('PPD %.6f\n', ppd);
for i = 1:size(pairs, 1)
  h = pairs{i, 3}; w = pairs{i, 4};
  ref = read_raw(pairs{i, 1}, h, w); test = read_raw(pairs{i, 2}, h, w);
  res = hdrvdp3('side-by-side', test, ref, 'rgb-native', ppd, {'use_gpu', false, 'quiet', true});
  printf('RESULT %d %.6f %.6f %.6f\n', i, 100 * mean(res.P_map(:) >= 0.75), 100 * mean(res.P_map(:) >= 0.95), res.Q_JOD);
end
"""


class Missing(Exception):
    pass


def find_root(arg):
    root = Path(arg or os.environ.get("TESSERA_HDRVDP") or DEFAULT_ROOT)
    if not (root / "hdrvdp3.m").is_file():
        raise Missing(f"HDR-VDP-3 sources not found: {root}/hdrvdp3.m (set --hdrvdp or $TESSERA_HDRVDP; "
                      "they ship in ../shared/tools beside the repository)")
    return root


def find_octave():
    octave = shutil.which("octave-cli") or shutil.which("octave")
    if not octave:
        raise Missing("octave-cli not found (Debian: apt-get install octave octave-statistics octave-image)")
    return octave


def check(root, octave):
    """Raises Missing unless Octave loads both packages."""
    r = subprocess.run([octave, "--no-gui", "--quiet", "--eval", "pkg load statistics; pkg load image;"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise Missing("Octave cannot load its statistics and image packages (Debian: apt-get install "
                      f"octave-statistics octave-image): {r.stderr.strip()[-300:]}")
    return f"{VERSION} in {subprocess.run([octave, '--version'], capture_output=True, text=True).stdout.splitlines()[0]}"


def scaled_pairs(paths, tmp):
    """Reads and checks every pair before any Octave work; writes the scaled raw files."""
    import numpy as np
    import OpenEXR
    pairs = []
    for i in range(0, len(paths), 2):
        ref = read_rgb(paths[i], np, OpenEXR)
        test = read_rgb(paths[i + 1], np, OpenEXR)
        if ref.shape != test.shape:
            raise BadInput(f"{paths[i + 1]}: {test.shape[1]}x{test.shape[0]}, but the reference {paths[i]} is "
                           f"{ref.shape[1]}x{ref.shape[0]}")
        y = float((ref * np.asarray(REC709_Y, dtype=np.float32)).sum(axis=-1).mean())
        if not y > 0.0:
            raise BadInput(f"{paths[i]}: zero mean luminance, cannot scale it to {MEAN_LUMINANCE:g} cd/m^2")
        k = MEAN_LUMINANCE / y
        files = []
        for name, img in (("ref", ref), ("test", test)):
            f = Path(tmp) / f"{name}{i // 2}.f32"
            np.ascontiguousarray(img * k, dtype=np.float32).tofile(f)
            files.append(str(f))
        pairs.append({"files": files, "h": ref.shape[0], "w": ref.shape[1], "k": k,
                      "reference": str(paths[i]), "test": str(paths[i + 1])})
    return pairs


def run(pairs, root, octave, implementation):
    cells = ";\n".join(f"'{p['files'][0]}', '{p['files'][1]}', {p['h']}, {p['w']}" for p in pairs)
    script = f"{OCTAVE_FUNCTIONS}hdrvdp_root = '{root}';\npairs = {{{cells}}};\n{OCTAVE_MAIN}"
    r = subprocess.run([octave, "--no-gui", "--quiet", "--eval", script], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"Octave failed (exit {r.returncode}): {r.stderr.strip()[-500:]}")
    ppd, results = None, {}
    for line in r.stdout.splitlines():
        f = line.split()
        if f[:1] == ["PPD"]:
            ppd = float(f[1])
        elif f[:1] == ["RESULT"]:
            results[int(f[1]) - 1] = [float(v) for v in f[2:5]]
    out = []
    for i, p in enumerate(pairs):
        if i not in results:
            raise RuntimeError(f"Octave printed no result for {p['test']}: {r.stdout[-300:]}")
        p75, p95, q = results[i]
        out.append({"p_ge_75": p75, "p_ge_95": p95, "q_jod": q, "width": p["w"], "height": p["h"],
                    "luminance_scale": p["k"], "reference": p["reference"], "test": p["test"],
                    "implementation": implementation, "pixels_per_degree": ppd})
    return out


def compare_files(paths, root=None):
    """HDR-VDP-3 results (dicts as printed) of each (reference, test) pair in the flat list
    `paths`; raises Missing, BadInput or RuntimeError."""
    root, octave = find_root(root), find_octave()
    implementation = check(root, octave)
    with tempfile.TemporaryDirectory(prefix="hdrvdp-") as tmp:
        return run(scaled_pairs(paths, tmp), root, octave, implementation)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("paths", nargs="*", help="REF TEST [REF TEST ...] (EXR)")
    ap.add_argument("--hdrvdp", help=f"HDR-VDP-3 source folder (default $TESSERA_HDRVDP, else {DEFAULT_ROOT})")
    ap.add_argument("--check", action="store_true", help="only check Octave, its packages and the sources")
    args = ap.parse_args()
    try:
        if args.check:
            print(check(find_root(args.hdrvdp), find_octave()))
            return 0
        if not args.paths or len(args.paths) % 2:
            raise BadInput(f"{len(args.paths)} paths given: need REF TEST pairs (or --check)")
        for r in compare_files(args.paths, args.hdrvdp):
            print(json.dumps(r))
    except Missing as e:
        print(f"hdrvdp_metric: {e}", file=sys.stderr)
        return 3
    except BadInput as e:
        print(f"hdrvdp_metric: {e}", file=sys.stderr)
        return 2
    except RuntimeError as e:
        print(f"hdrvdp_metric: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
