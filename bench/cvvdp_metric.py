#!/usr/bin/env python3
"""Perceptual, HDR-aware difference of a test EXR against a reference EXR, from ColorVideoVDP
(PyPI package `cvvdp`, module `pycvvdp`; Mantiuk, Hanji, Ashraf, Asano, Chapiro,
"ColorVideoVDP: A visual difference predictor for image, video and display distortions",
SIGGRAPH 2024; from the authors of HDR-VDP). It needs PyTorch: an optional, heavy
dependency (bench/README.md, "Perceptual metric"); it runs on the CPU.

Viewing conditions (also written to the output JSON under "viewing"):
  * luminance: inputs are linear Rec. 709 RGB radiance; both images are multiplied by one
    factor so that the reference's mean luminance (Y = 0.2126 R + 0.7152 G + 0.0722 B) is
    100 cd/m^2, as the HDR-VDP-3 protocol does (../shared/tools/README.md);
  * display photometry: cvvdp's `standard_hdr_linear` display: linear BT.709 input in
    cd/m^2, peak 1500 cd/m^2 (brighter pixels clip, as on that display), contrast
    1,000,000:1, 10 lux ambient light, screen reflectivity 0.5%;
  * geometry: 32.45 pixels per degree at every eccentricity (the HDR-VDP-3 protocol's; a
    256-pixel-wide image spans 7.9 degrees of visual field, e.g. 256 pixels of a 30-inch 4K
    monitor seen from 1.0 m).
--ppd, --peak and --mean-luminance change these; the JSON says what was used.

Outputs (one JSON object on stdout):
  "jod": the pooled quality in just-objectionable-difference units: 10 = no visible
      difference, lower = more visible (a 1 JOD gap: 75% of observers pick the better image).
  "p_ge_1jod", "p_ge_2_44jod": % of pixels whose cvvdp distortion map D (the "raw" heatmap,
      D = 1 - JOD_local / 10, so 0 where the images match) is >= 0.1 (a local difference of
      1 JOD) and >= 0.2439 (2.44 JOD). Why these thresholds: on the JOD scale (Thurstone case
      V) a difference of 1 JOD is chosen by 75% of observers and one of 2.44 JOD by 95%
      (Phi^-1(0.95) / Phi^-1(0.75) = 1.6449 / 0.6745), so the two shares are laid out like
      the seed thesis's HDR-VDP P(X) >= 75% / >= 95% (its Table 5.3). They are NOT HDR-VDP's
      per-pixel probability of detection: JOD is a preference (quality) scale, and the map is
      cvvdp's per-pixel localisation of its pooled difference, not a calibrated per-pixel
      detection probability. Compare them with each other, not with HDR-VDP percentages.
  "d_mean", "d_max": mean and maximum of D; "width", "height", "implementation", "viewing".
--heatmap FILE.png writes cvvdp's own "threshold" visualisation of D (blue = none, red >= 1
JOD) over the reference's tone-mapped luminance.

Exit status: 0 on success; 3 if pycvvdp (or torch, numpy, OpenEXR) cannot be imported (the
message says so and how to install); 2 for bad input (unreadable file, no R/G/B channel,
NaN or infinite values, different sizes, a reference with zero mean luminance).
`--check` only imports pycvvdp and prints its version (exit 0 or 3): `tessera compare
--cvvdp` runs it before any work. `tessera compare --cvvdp` and bench/accuracy run this
script with the interpreter $TESSERA_CVVDP_PYTHON (or `--cvvdp-python`).
"""
import argparse
import json
import math
import sys

PPD = 32.45                 # pixels per degree: the HDR-VDP-3 protocol's
MEAN_LUMINANCE = 100.0      # cd/m^2 of the reference's mean luminance: the protocol's
DISPLAY = "standard_hdr_linear"  # cvvdp's display model: photometry (peak, contrast, ambient)
D_1JOD = 0.1                # D = 1 - JOD_local/10 at a local difference of 1 JOD (75% choose)
JOD_95 = 1.6448536269514722 / 0.6744897501960817  # 2.4387 JOD: 95% choose (Thurstone case V)
D_95 = JOD_95 / 10.0
REC709_Y = (0.2126, 0.7152, 0.0722)


class BadInput(Exception):
    pass


def import_cvvdp():
    """(pycvvdp, torch, numpy, OpenEXR, version string); raises ImportError naming what is missing."""
    import numpy as np
    import OpenEXR
    import torch
    import pycvvdp
    try:
        from importlib.metadata import version
        v = "cvvdp " + version("cvvdp") + ", torch " + torch.__version__
    except Exception:
        v = "cvvdp, torch " + torch.__version__
    return pycvvdp, torch, np, OpenEXR, v


def read_rgb(path, np, OpenEXR):
    """HxWx3 float32 linear RGB (top row first) from the EXR's R, G, B channels."""
    try:
        with OpenEXR.File(str(path), separate_channels=True) as f:
            ch = f.channels()
            missing = [c for c in "RGB" if c not in ch]
            if missing:
                raise BadInput(f"{path}: no '{missing[0]}' channel")
            img = np.stack([np.asarray(ch[c].pixels, dtype=np.float32) for c in "RGB"], axis=-1)
    except BadInput:
        raise
    except Exception as e:
        raise BadInput(f"cannot read {path}: {e}") from None
    if not np.all(np.isfinite(img)):
        raise BadInput(f"{path}: NaN or infinite values")
    # Radiance is non-negative; tiny negatives come only from rounding.
    return np.maximum(img, 0.0)


def viewing(ppd, peak, mean_luminance):
    return {"display_photometry": DISPLAY, "colorspace": "BT.709-linear", "peak_cd_m2": peak,
            "contrast": 1e6, "ambient_lux": 10, "screen_reflectivity": 0.005,
            "pixels_per_degree": ppd, "reference_mean_luminance_cd_m2": mean_luminance,
            "scaling": "both images x (mean_luminance / reference's mean Rec. 709 Y)",
            "thresholds": {"p_ge_1jod": "D >= 0.1 (1 JOD: 75% of observers choose the reference)",
                           "p_ge_2_44jod": f"D >= {D_95:.4f} (2.44 JOD: 95% choose the reference)"}}


class Metric:
    """One cvvdp instance (the model loads once) for many image pairs."""

    def __init__(self, ppd=PPD, peak=1500.0, mean_luminance=MEAN_LUMINANCE, heatmap="raw"):
        self.cvvdp, self.torch, self.np, self.OpenEXR, self.implementation = import_cvvdp()
        self.ppd, self.peak, self.mean_luminance = ppd, peak, mean_luminance
        photometry = self.cvvdp.vvdp_display_photo_eotf(
            peak, contrast=1e6, source_colorspace="BT.709-linear", E_ambient=10, k_refl=0.005)
        self.photometry = photometry
        self.heatmap_kind = heatmap
        self.metrics = {}

    def _metric(self, width, height, heatmap):
        key = (width, height, heatmap)
        if key not in self.metrics:
            geometry = self.cvvdp.vvdp_display_geometry((width, height), ppd=self.ppd)
            self.metrics[key] = self.cvvdp.cvvdp(display_photometry=self.photometry, display_geometry=geometry,
                                                 heatmap=heatmap, quiet=True, device=self.torch.device("cpu"))
        return self.metrics[key]

    def scale(self, ref):
        """The factor that brings the reference's mean luminance to mean_luminance cd/m^2."""
        y = float((ref * self.np.asarray(REC709_Y, dtype=self.np.float32)).sum(axis=-1).mean())
        if not y > 0.0:
            raise BadInput("reference has zero mean luminance: cannot scale it to "
                           f"{self.mean_luminance} cd/m^2")
        return self.mean_luminance / y

    def compare(self, ref, test, heatmap_png=None):
        """JOD and distortion-map statistics of HxWx3 linear RGB `test` against `ref`."""
        np, torch = self.np, self.torch
        if ref.shape != test.shape:
            raise BadInput(f"image sizes differ: {ref.shape[1]}x{ref.shape[0]} vs {test.shape[1]}x{test.shape[0]}")
        k = self.scale(ref)
        h, w = ref.shape[:2]
        t_ref = torch.from_numpy(np.ascontiguousarray(ref * k, dtype=np.float32))
        t_test = torch.from_numpy(np.ascontiguousarray(test * k, dtype=np.float32))
        with torch.no_grad():
            jod, stats = self._metric(w, h, "raw").predict(t_test, t_ref, dim_order="HWC")
        d = stats["heatmap"].float().reshape(h, w).numpy()
        if heatmap_png:
            with torch.no_grad():
                _, vis = self._metric(w, h, "threshold").predict(t_test, t_ref, dim_order="HWC")
            rgb = vis["heatmap"].float().reshape(3, h, w).permute(1, 2, 0).clamp(0, 1).numpy()
            write_png(heatmap_png, rgb)
        return {"jod": float(jod), "p_ge_1jod": 100.0 * float(np.mean(d >= D_1JOD)),
                "p_ge_2_44jod": 100.0 * float(np.mean(d >= D_95)), "d_mean": float(d.mean()),
                "d_max": float(d.max()), "width": int(w), "height": int(h), "luminance_scale": k,
                "implementation": self.implementation,
                "viewing": viewing(self.ppd, self.peak, self.mean_luminance)}

    def compare_files(self, ref_path, test_path, heatmap_png=None):
        ref = read_rgb(ref_path, self.np, self.OpenEXR)
        test = read_rgb(test_path, self.np, self.OpenEXR)
        return self.compare(ref, test, heatmap_png)


def write_png(path, rgb01):
    """Writes an HxWx3 array in [0, 1] (already display-encoded) as an 8-bit PNG."""
    import numpy as np
    from PIL import Image  # a dependency of matplotlib, which cvvdp requires
    # format given: `tessera compare` passes a temporary name (.map.png.tmp.XXXXXX) that it
    # renames over the map once every output is written, and PIL guesses from the extension.
    Image.fromarray((np.clip(rgb01, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8), "RGB").save(path, format="PNG")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("reference", nargs="?")
    ap.add_argument("test", nargs="?")
    ap.add_argument("--heatmap", help="write cvvdp's threshold visualisation of the distortion map to this PNG")
    ap.add_argument("--ppd", type=float, default=PPD, help=f"pixels per degree (default {PPD})")
    ap.add_argument("--peak", type=float, default=1500.0, help="display peak luminance, cd/m^2 (default 1500)")
    ap.add_argument("--mean-luminance", type=float, default=MEAN_LUMINANCE,
                    help=f"the reference's mean luminance after scaling, cd/m^2 (default {MEAN_LUMINANCE:g})")
    ap.add_argument("--check", action="store_true", help="only check that pycvvdp imports; print its version")
    args = ap.parse_args()
    try:
        if args.check:
            print(import_cvvdp()[-1])
            return 0
    except ImportError as e:
        print(f"cvvdp_metric: {e} (install: bench/README.md, 'Perceptual metric')", file=sys.stderr)
        return 3
    if args.reference is None or args.test is None:
        ap.error("REFERENCE and TEST EXR files are required (or --check)")
    for name in ("ppd", "peak", "mean_luminance"):
        v = getattr(args, name)
        if not (math.isfinite(v) and v > 0):
            print(f"cvvdp_metric: --{name.replace('_', '-')} {v}: must be a positive number", file=sys.stderr)
            return 2
    try:
        metric = Metric(args.ppd, args.peak, args.mean_luminance)
    except ImportError as e:
        print(f"cvvdp_metric: {e} (install: bench/README.md, 'Perceptual metric')", file=sys.stderr)
        return 3
    try:
        result = metric.compare_files(args.reference, args.test, args.heatmap)
    except BadInput as e:
        print(f"cvvdp_metric: {e}", file=sys.stderr)
        return 2
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
