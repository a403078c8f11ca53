#!/usr/bin/env python3
"""Independent check of Tessera's path tracer against Blender Cycles (CPU).

Exports a Tessera JSON scene (OBJ/MTL meshes, transforms, quad lights, material
overrides, optional homogeneous medium) to Blender through bench/cycles_scene.py, run by
`blender --background --factory-startup`, renders it with Cycles in independent
batches (different seeds), renders it with `build/tessera render --method pt`, and
compares the two images like bench/mitsuba_check.py: per-channel mean radiance ratio,
relMSE, and per-pixel z-scores. Writes bench/results/cycles_check_<scene>.{json,md}.

See bench/README.md ("Blender Cycles check"). Usage:
    python3 bench/cycles_check.py scenes/cornell-box-fog.json --width 96 --height 96 \
        --spp 256 --cycles-spp 1024 --cycles-batches 16
"""
from __future__ import annotations

import argparse
import datetime
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import crosscheck_common as cc  # noqa: E402
from crosscheck_common import REPO, SceneExport, channels_rgb, compare, fail, machine_note, np  # noqa: E402

cc.TOOL = "cycles_check"
try:
    import OpenEXR
except ImportError:
    sys.exit("cycles_check: the Python package 'OpenEXR' is missing: pip install -r bench/requirements.txt")


def read_exr(path: Path) -> dict[str, np.ndarray]:
    """All channels of an EXR by name (R, G, B, variance.R, ...), top row first, float64."""
    with OpenEXR.File(str(path), separate_channels=True) as f:
        return {k: np.asarray(v.pixels, dtype=np.float64) for k, v in f.channels().items()}


def write_exr(path: Path, rgb: np.ndarray):
    OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage},
                 {"RGB": np.ascontiguousarray(rgb, dtype=np.float32)}).write(str(path))


class CyclesExport(SceneExport):
    """Shapes as .npz triangle soups (P, T, optional N; world space) and textures as
    linear float EXRs with Kd applied, for cycles_scene.py."""

    def texture(self, file: Path, kd) -> Path:
        try:
            from PIL import Image
        except ImportError:
            fail(f"{file}: reading textures needs Pillow (pip install pillow)")
        img = Image.open(file)
        if img.mode not in ("1", "L", "LA", "P", "PA", "RGB", "RGBA", "CMYK", "YCbCr"):
            fail(f"{file}: expected an 8-bit image (Tessera decodes to RGBA8), got mode {img.mode}")
        arr = np.asarray(img.convert("RGB"))  # grey (+ alpha) expands as stb_image does
        lin = cc.srgb_to_linear(arr) * np.asarray(kd, dtype=np.float32)
        out = self.work / f"tex{len(self.textures)}_{file.stem}.exr"
        write_exr(out, lin)
        return out

    def write_shape(self, index, P, N, T) -> Path:
        path = self.work / f"shape{index}.npz"
        arrays = {"P": P.astype(np.float32), "T": T.astype(np.float32)}
        if N is not None:
            arrays["N"] = N.astype(np.float32)
        np.savez(path, **arrays)
        return path

    def manifest(self, args, out_dir: Path, seeds: list[int], per_batch: int) -> dict:
        med = None
        if self.medium is not None:
            med = {k: self.medium.get(k, d) for k, d in (("sigma_a", [0, 0, 0]), ("sigma_s", [0, 0, 0]), ("g", 0.0))}
            box = self.medium.get("box")
            if box is not None:
                e = args.medium_inset
                lo = [float(x) + e for x in box["min"]]
                hi = [float(x) - e for x in box["max"]]
                if any(h <= l for l, h in zip(lo, hi)):
                    fail(f"--medium-inset {e}: the medium box {box} would be empty")
                med["box"] = {"min": lo, "max": hi}
            else:
                med["box"] = None
        return {"camera": self.camera, "width": self.width, "height": self.height,
                "shapes": [{"name": s["name"], "file": str(s["file"]), "kd": s["kd"], "ke": s["ke"],
                            "texture": str(s["texture"]) if s["texture"] else None} for s in self.shapes],
                "medium": med, "out_dir": str(out_dir),
                "render": {"spp": per_batch, "seeds": seeds, "max_bounces": args.max_depth - 1,
                           "threads": args.threads}}


def render_cycles(args, exp: CyclesExport, work: Path):
    """Mean image and variance of the pixel mean over --cycles-batches Cycles renders
    with different seeds, the spp actually rendered, seconds, Blender version."""
    per = max(1, args.cycles_spp // args.cycles_batches)
    seeds = [args.seed * 1000 + b for b in range(args.cycles_batches)]
    out_dir = work / "cycles"
    if out_dir.exists():
        shutil.rmtree(out_dir)
    out_dir.mkdir(parents=True)
    man = work / "manifest.json"
    man.write_text(json.dumps(exp.manifest(args, out_dir, seeds, per), indent=1))
    cmd = [args.blender, "--background", "--factory-startup", "--python",
           str(REPO / "bench" / "cycles_scene.py"), "--", str(man)]
    print("+ " + " ".join(cmd), flush=True)
    # Blender's embedded Python takes its prefix from the first python3 on PATH; a
    # virtualenv's or pyenv's there would hide the system numpy Blender needs.
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYENV", "VIRTUAL_ENV", "PYTHONHOME", "PYTHONPATH"))}
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep)
                                  if ".pyenv" not in p and not (os.environ.get("VIRTUAL_ENV") and
                                                                p.startswith(os.environ["VIRTUAL_ENV"])))
    t0 = time.time()
    with open(work / "blender.log", "w") as log:
        r = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    dt = time.time() - t0
    text = (work / "blender.log").read_text(errors="replace")
    if r.returncode != 0 or "Traceback" in text or not (out_dir / "cycles_times.json").is_file():
        fail(f"blender failed ({r.returncode}); see {work / 'blender.log'}:\n  "
             + "\n  ".join(text.strip().splitlines()[-8:]))
    imgs = []
    for k in range(len(seeds)):
        ch = read_exr(out_dir / f"cycles_{k}.exr")
        img = channels_rgb(ch)
        if img is None:
            fail(f"{out_dir / f'cycles_{k}.exr'}: no R, G, B channels (have {sorted(ch)})")
        imgs.append(img)
    stack = np.stack(imgs)
    mean = stack.mean(axis=0)
    b = len(imgs)
    var = stack.var(axis=0, ddof=1) / b if b > 1 else np.zeros_like(mean)
    info = json.loads((out_dir / "cycles_times.json").read_text())
    return mean, var, per * b, dt, info


def run_tessera(args, scene_file: Path, exp: CyclesExport, out: Path):
    cmd = [str(args.tessera), "render", str(scene_file), "--backend", args.backend,
           "--method", "pt", "--spp", str(args.spp), "--shadow-samples", str(args.shadow_samples),
           "--max-depth", str(args.max_depth),
           "--width", str(exp.width), "--height", str(exp.height), "--seed", str(args.seed),
           "--out", str(out)]
    if args.data_dir:
        cmd += ["--data-dir", args.data_dir]
    print("+ " + " ".join(cmd), flush=True)
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r, cmd, time.time() - t0


def add_ratio_stderr(cmp_: dict, t_img, t_var, c_img, c_var):
    """Standard error of each channel's mean ratio, from the variances of both pixel
    means, pixels taken as independent (delta method: the relative errors of the two
    image means add in quadrature)."""
    for c, n in enumerate("RGB"):
        d = cmp_["channels"][n]
        rt = math.sqrt(t_var[:, :, c].sum()) / t_img[:, :, c].sum()
        rc = math.sqrt(c_var[:, :, c].sum()) / c_img[:, :, c].sum()
        d["ratio_stderr"] = d["ratio"] * math.sqrt(rt * rt + rc * rc)


def box_filter(a: np.ndarray, r: int) -> np.ndarray:
    """Mean over the (2r+1)² window around each pixel of an (h, w, c) image, edges clamped."""
    p = np.pad(a, ((r, r), (r, r), (0, 0)), mode="edge")
    out = np.zeros_like(a)
    for dy in range(2 * r + 1):
        for dx in range(2 * r + 1):
            out += p[dy:dy + a.shape[0], dx:dx + a.shape[1]]
    return out / (2 * r + 1) ** 2


def add_smoothed_z(cmp_: dict, t_img, t_var, c_img, c_var, r: int = 2):
    """Mean z with both variances box-filtered over (2r+1)² pixels. A pixel's mean and
    its own variance estimate are correlated when its samples are right-skewed (a bright
    outlier raises both), which makes the plain mean z negative without any bias (more
    so at low spp and in media); the neighbours' variance is free of that correlation."""
    den = box_filter(t_var, r) + box_filter(c_var, r)
    for c, n in enumerate("RGB"):
        noisy = (t_var[:, :, c] + c_var[:, :, c]) > 0
        z = (t_img[:, :, c] - c_img[:, :, c])[noisy] / np.sqrt(den[:, :, c][noisy])
        cmp_["channels"][n]["z_mean_smoothed_var"] = float(z.mean()) if z.size else float("nan")


def markdown(s: dict) -> str:
    t, c = s["tessera"], s["cycles"]
    setup = [f"- Resolution {s['width']}×{s['height']}; Tessera `pt` ({t['backend']}) {t['spp']} spp, "
             f"max depth {t['max_depth']}, {t['seconds']:.1f} s; Blender {c['version']} Cycles (CPU, "
             f"{c['threads']} threads) {c['spp']} spp in {c['batches']} batches (seeds {c['seeds'][0]}…"
             f"{c['seeds'][-1]}), max bounces {c['max_bounces']}, {c['seconds']:.1f} s "
             f"(render {sum(c['render_seconds']):.1f} s)",
             f"- Exported: {s['export']['triangles']} triangles ({s['export']['emitting_triangles']} emitting), "
             f"{s['export']['shapes']} shapes, {s['export']['textures']} textures; medium: {s['export']['medium']}",
             f"- Load average (1, 5, 15 min): {s['load']['start']} at the start, {s['load']['end']} at the end"]
    ch = s["comparison"]["channels"]
    if all("ratio_stderr" in d for d in ch.values()):
        setup.append("- Standard error of each channel's ratio (both variances, pixels independent): "
                     + ", ".join(f"{n} ±{d['ratio_stderr']:.4f}" for n, d in ch.items()))
    if all("z_mean_smoothed_var" in d for d in ch.values()):
        setup.append("- Mean z with both variances box-filtered over 5×5 pixels (free of the correlation "
                     "of a pixel's mean with its own variance estimate, which pulls the plain mean z "
                     "below 0 for right-skewed pixels): "
                     + ", ".join(f"{n} {d['z_mean_smoothed_var']:+.3f}" for n, d in ch.items()))
    return cc.markdown(s, f"Blender Cycles check: {s['scene']} (pt)", setup, ref="cycles",
                       ref_name="Cycles", ref_sym="C", ref_poss="Cycles'")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", nargs="?", default=str(REPO / "scenes" / "cornell-box.json"))
    ap.add_argument("--width", type=int)
    ap.add_argument("--height", type=int)
    ap.add_argument("--spp", type=int, default=256, help="Tessera passes (default 256)")
    ap.add_argument("--shadow-samples", type=int, default=8, help="Tessera shadow samples (default 8)")
    ap.add_argument("--max-depth", type=int, default=128,
                    help="Tessera --max-depth (scattering vertices per path; default 128, Tessera's default); "
                         "Cycles gets max bounces = this − 1 in every category")
    ap.add_argument("--cycles-spp", type=int, default=1024)
    ap.add_argument("--cycles-batches", type=int, default=16,
                    help="independent Cycles renders (seeds) whose spread gives Cycles' variance")
    ap.add_argument("--medium-inset", type=float, default=0.0005,
                    help="shrink a bounded medium's box by this much (scene units) on every side, so "
                         "its faces do not coincide with walls (default 0.0005: 0.5 mm in the metre scenes)")
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1, help="Cycles render threads")
    ap.add_argument("--blender", default=shutil.which("blender") or "blender")
    cc.add_common_arguments(ap, "Cycles")
    args = ap.parse_args(argv)

    scene_file = Path(args.scene).resolve()
    if not scene_file.is_file():
        fail(f"scene {args.scene} not found")
    if args.max_depth < 1:
        fail(f"--max-depth {args.max_depth}: must be at least 1")
    if not shutil.which(args.blender):
        fail(f"--blender {args.blender}: not found (apt-get install blender, see bench/README.md)")
    if not args.tessera.is_file():
        fail(f"{args.tessera} not found: build Tessera first (scripts/build)")
    load_start = [round(x, 2) for x in os.getloadavg()]
    name = json.loads(scene_file.read_text()).get("name", scene_file.stem)
    work = (args.work_dir or Path(tempfile.gettempdir()) / f"cycles_check_{name}").resolve()
    work.mkdir(parents=True, exist_ok=True)

    t0 = time.time()
    exp = CyclesExport(scene_file, args, work)
    print(f"exported {exp.stats['triangles']} triangles in {len(exp.shapes)} shapes "
          f"({time.time() - t0:.1f} s) to {work}", flush=True)
    notes = list(args.note)
    if args.flip_emitters:
        notes.append("NEGATIVE CONTROL (--flip-emitters): Cycles' lights emit on the wrong side")
    medium_desc = "none"
    if exp.medium is not None:
        if exp.medium.get("box") is None:
            medium_desc = "unbounded (Cycles world volume)"
        else:
            medium_desc = f"box shrunk by {args.medium_inset:g} scene units on every side"
            notes.append(f"the medium box is shrunk by {args.medium_inset:g} scene units on each side in the "
                         "Cycles export (its faces would otherwise coincide with the walls); Tessera "
                         "renders the box as given")

    t_exr = work / "tessera.exr"
    r, cmd, t_sec = run_tessera(args, scene_file, exp, t_exr)
    if r.returncode != 0:
        out = (r.stderr + "\n" + r.stdout).strip().splitlines()
        fail(f"tessera failed ({r.returncode}): " + "\n  ".join([l for l in out if "error" in l] or out[-3:]))
    ch = read_exr(t_exr)
    t_img, t_var = channels_rgb(ch), channels_rgb(ch, "variance.")
    if t_img is None:
        fail(f"{t_exr}: no R, G, B channels (have {sorted(ch)})")
    if t_var is None:
        notes.append("Tessera output has no variance.R/G/B channels: no z-scores")

    print(f"rendering with Cycles ({args.cycles_spp} spp in {args.cycles_batches} batches)...", flush=True)
    c_img, c_var, c_spp, c_sec, info = render_cycles(args, exp, work)
    write_exr(work / "cycles.exr", c_img)
    write_exr(work / "cycles_variance.exr", c_var)
    load_end = [round(x, 2) for x in os.getloadavg()]

    cmp_ = compare(t_img, t_var, c_img, c_var, args.z_limit, ref="cycles")
    if t_var is not None:
        add_ratio_stderr(cmp_, t_img, t_var, c_img, c_var)
        add_smoothed_z(cmp_, t_img, t_var, c_img, c_var)
    ok = all(abs(d["ratio"] - 1) <= args.tolerance for d in cmp_["channels"].values())
    summary = {
        "scene": name, "scene_file": os.path.relpath(scene_file, REPO), "integrator": "path",
        "date": datetime.datetime.now().isoformat(timespec="seconds"),
        "machine": machine_note(args.machine), "load": {"start": load_start, "end": load_end},
        "width": exp.width, "height": exp.height,
        "tessera": {"command": " ".join(os.path.relpath(c, REPO) if c.startswith(str(REPO)) else c for c in cmd),
                    "method": "pt", "backend": args.backend, "spp": args.spp,
                    "shadow_samples": args.shadow_samples, "max_depth": args.max_depth, "seconds": t_sec},
        "cycles": {"version": info["version"], "device": "CPU", "threads": args.threads, "spp": c_spp,
                   "batches": args.cycles_batches, "seeds": [args.seed * 1000 + b for b in range(args.cycles_batches)],
                   "max_bounces": args.max_depth - 1, "pixel_filter": "box, width 1 px",
                   "seconds": c_sec, "render_seconds": info["seconds"]},
        "export": dict(exp.stats, shapes=len(exp.shapes), medium=medium_desc,
                       medium_inset=args.medium_inset if medium_desc.startswith("box") else None,
                       obj_reader="tinyobjloader" if cc.tinyobjloader else "built-in"),
        "comparison": cmp_, "tolerance": args.tolerance, "z_limit": args.z_limit, "pass": ok,
        "work_dir": str(work), "notes": notes,
    }
    base = args.results_dir / f"cycles_check_{name}"
    md = markdown(summary)
    cc.write_results(summary, base, md)
    print(md)
    print(f"images: {work}/{{tessera,cycles,cycles_variance}}.exr, cycles/cycles_<k>.exr; results: {base}.{{json,md}}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
