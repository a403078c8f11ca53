#!/usr/bin/env python3
"""The discontinuity filter at the image's border: one frame's border rows and columns
against `pt`, for two tessera binaries (docs/igi.md §8).

For each binary, renders `--seeds` single frames (1 spp, seeds 1..N, Embree) of the scene
and a `pt` reference once; prints, per border row and column and for the middle row, the
ratio of the frames' mean to the reference's (bias) and the RMS over frames of each
frame's ratio minus 1 (the error one frame shows). Radiance is the mean of R, G and B.

Usage: bench/border_compare.py OLD_TESSERA NEW_TESSERA [--scene S] [--size N] [--seeds K]
       [--method M] [--ref-spp R]
Defaults: bench/scenes/wall-lit-from-above.json, 256², 8 seeds, igi, pt at 1,024 spp.
Prints a markdown table."""
import argparse
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import OpenEXR
import Imath


def read_mean_rgb(path: Path) -> np.ndarray:
    """An EXR's mean of R, G and B, shape (height, width)."""
    f = OpenEXR.InputFile(str(path))
    dw = f.header()['dataWindow']
    w, h = dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1
    pt = Imath.PixelType(Imath.PixelType.FLOAT)
    return np.mean([np.frombuffer(f.channel(c, pt), np.float32).reshape(h, w) for c in 'RGB'], axis=0)


def render(exe: str, scene: str, size: int, args: list[str], out: Path) -> np.ndarray:
    subprocess.run([exe, 'render', scene, '--width', str(size), '--height', str(size), '--backend', 'embree',
                    '--out', str(out)] + args, check=True, capture_output=True)
    return read_mean_rgb(out)


def main() -> None:
    root = Path(__file__).resolve().parent
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('old')
    ap.add_argument('new')
    ap.add_argument('--scene', default=str(root / 'scenes' / 'wall-lit-from-above.json'))
    ap.add_argument('--size', type=int, default=256)
    ap.add_argument('--seeds', type=int, default=8)
    ap.add_argument('--method', default='igi')
    ap.add_argument('--ref-spp', type=int, default=1024)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        ref = render(a.new, a.scene, a.size, ['--method', 'pt', '--spp', str(a.ref_spp)], work / 'ref.exr')
        parts = {'top row': (0, slice(None)), 'bottom row': (-1, slice(None)), 'left column': (slice(None), 0),
                 'right column': (slice(None), -1), 'middle row': (a.size // 2, slice(None))}
        print(f'{a.size}², `{a.method}` one frame, seeds 1–{a.seeds}, against `pt` at {a.ref_spp} spp: '
              'mean ratio (RMS per frame of ratio − 1)\n')
        print('| binary | ' + ' | '.join(parts) + ' |')
        print('|---' * (len(parts) + 1) + '|')
        for name, exe in (('old', a.old), ('new', a.new)):
            frames = [render(exe, a.scene, a.size, ['--method', a.method, '--spp', '1', '--seed', str(s)],
                             work / f'{name}{s}.exr') for s in range(1, a.seeds + 1)]
            cells = []
            for sl in parts.values():
                r = np.array([f[sl].mean() / ref[sl].mean() for f in frames])
                cells.append(f'{np.mean([f[sl].mean() for f in frames]) / ref[sl].mean():.3f} '
                             f'({np.sqrt(np.mean((r - 1) ** 2)):.3f})')
            print(f'| {name} | ' + ' | '.join(cells) + ' |')


if __name__ == '__main__':
    main()
