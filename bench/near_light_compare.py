#!/usr/bin/env python3
"""Light samples near an emitter: one frame of the wall beneath a light that touches it,
against `pt`, for two tessera binaries (docs/igi.md §5).

For each binary and method, renders `--seeds` single frames (1 spp, seeds 1..N, Embree)
of the scene and a `pt` reference once (with the new binary); prints, over the band of
rows just beneath the light (rows 0.24-0.34 of the image on the default scene) and over
the whole image, the ratio of the frames' mean to the reference's (bias), the relMSE of
one frame (mean over frames of mean((f - r)² / (r² + 0.01))) and the largest pixel of any
frame against the reference's largest wall pixel there. Radiance is the mean of R, G, B.

Usage: bench/near_light_compare.py OLD_TESSERA NEW_TESSERA [--scene S] [--size N]
       [--seeds K] [--methods M,M] [--ref-spp R] [--band LO,HI]
Defaults: bench/scenes/wall-touching-light.json, 128², 8 seeds, igi,ais,direct, pt at
4,096 spp, band 0.24,0.34. Prints a markdown table."""
import argparse
import tempfile
from pathlib import Path

import numpy as np

from border_compare import render


def row(name: str, frames: list, ref: np.ndarray, band: slice) -> str:
    cells = []
    for sl in (band, slice(None)):
        r = ref[sl]
        bias = np.mean([f[sl].mean() for f in frames]) / r.mean()
        rel = np.mean([np.mean((f[sl] - r) ** 2 / (r ** 2 + 0.01)) for f in frames])
        cells.append(f'{bias:.3f} | {rel:.4f}')
    peak = max(f[band].max() for f in frames)
    return f'| {name} | ' + ' | '.join(cells) + f' | {peak:.2f} |'


def main() -> None:
    root = Path(__file__).resolve().parent
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('old')
    ap.add_argument('new')
    ap.add_argument('--scene', default=str(root / 'scenes' / 'wall-touching-light.json'))
    ap.add_argument('--size', type=int, default=128)
    ap.add_argument('--seeds', type=int, default=8)
    ap.add_argument('--methods', default='igi,ais,direct')
    ap.add_argument('--ref-spp', type=int, default=4096)
    ap.add_argument('--band', default='0.24,0.34')
    a = ap.parse_args()
    lo, hi = (float(x) for x in a.band.split(','))
    band = (slice(int(lo * a.size), int(hi * a.size)), slice(None))
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        ref = render(a.new, a.scene, a.size, ['--method', 'pt', '--spp', str(a.ref_spp)], work / 'ref.exr')
        print(f'{a.size}², one frame, seeds 1–{a.seeds}, against `pt` at {a.ref_spp} spp (largest pixel '
              f'there: {ref[band].max():.2f}); band: rows {band[0].start}–{band[0].stop - 1}\n')
        print('| method, binary | band: mean ratio | band: relMSE | image: mean ratio | image: relMSE '
              '| band: largest pixel |')
        print('|---' * 6 + '|')
        for method in a.methods.split(','):
            for name, exe in (('old', a.old), ('new', a.new)):
                frames = [render(exe, a.scene, a.size, ['--method', method, '--spp', '1', '--seed', str(s)],
                                 work / f'{name}{s}.exr') for s in range(1, a.seeds + 1)]
                print(row(f'{method}, {name}', frames, ref, band))


if __name__ == '__main__':
    main()
