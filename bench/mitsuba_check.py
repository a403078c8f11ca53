#!/usr/bin/env python3
"""Independent check of Tessera against Mitsuba 3.

Exports a Tessera JSON scene (OBJ/MTL meshes, transforms, quad lights, material
overrides, optional homogeneous medium) to a Mitsuba 3 scene, renders it with
Mitsuba (scalar_rgb) and with `build/tessera render`, and compares the two images:
per-channel mean radiance ratio, relMSE, and per-pixel Z-scores from the variance
channels of both renderers. Writes bench/results/mitsuba_check_<scene>.{json,md}.

See bench/README.md. Usage:
    python3 bench/mitsuba_check.py scenes/cornell-box.json --integrator direct \
        --width 128 --height 128 --spp 64 --shadow-samples 8 --mitsuba-spp 1024
"""
from __future__ import annotations

import argparse
import datetime
import json
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

cc.TOOL = "mitsuba_check"
try:
    import mitsuba as mi
except ImportError:
    sys.exit("mitsuba_check: the Python package 'mitsuba' (Mitsuba 3) is missing.\n"
             "  pip install -r bench/requirements.txt   (or: pip install mitsuba numpy)")


# ----------------------------------------------------------------------------------
# Export

def write_ply(path: Path, P: np.ndarray, N: np.ndarray | None, T: np.ndarray):
    """Binary PLY, one vertex per triangle corner (no sharing), float32 like Tessera."""
    n = P.shape[0]
    fields = [("x", "<f4"), ("y", "<f4"), ("z", "<f4")]
    if N is not None:
        fields += [("nx", "<f4"), ("ny", "<f4"), ("nz", "<f4")]
    fields += [("u", "<f4"), ("v", "<f4")]
    vert = np.empty(3 * n, dtype=fields)
    flatP = P.reshape(-1, 3)
    vert["x"], vert["y"], vert["z"] = flatP[:, 0], flatP[:, 1], flatP[:, 2]
    if N is not None:
        flatN = N.reshape(-1, 3)
        vert["nx"], vert["ny"], vert["nz"] = flatN[:, 0], flatN[:, 1], flatN[:, 2]
    flatT = T.reshape(-1, 2)
    # Tessera (OBJ convention): v = 0 is the bottom row of the image. Mitsuba's bitmap
    # texture puts uv (0, 0) at the top-left, and its PLY loader (unlike its OBJ loader)
    # does not flip, so store 1 - v.
    vert["u"], vert["v"] = flatT[:, 0], 1.0 - flatT[:, 1]
    faces = np.empty(n, dtype=[("n", "u1"), ("i", "<i4", (3,))])
    faces["n"] = 3
    faces["i"] = np.arange(3 * n, dtype=np.int32).reshape(-1, 3)
    header = ["ply", "format binary_little_endian 1.0", f"element vertex {3 * n}"]
    header += [f"property float {f}" for f, _ in fields]
    header += [f"element face {n}", "property list uchar int vertex_indices", "end_header"]
    with open(path, "wb") as f:
        f.write(("\n".join(header) + "\n").encode())
        f.write(vert.tobytes())
        f.write(faces.tobytes())


class Export(SceneExport):
    """The scene as a list of shapes (PLY file, reflectance, emission) plus camera,
    medium; turns into a Mitsuba dict (and optionally XML)."""

    def texture(self, file: Path, kd) -> Path:
        bmp = mi.Bitmap(str(file))
        arr = np.array(bmp)
        if arr.dtype != np.uint8:
            fail(f"{file}: expected an 8-bit image (Tessera decodes to RGBA8)")
        if arr.ndim == 2:
            arr = arr[:, :, None]
        if arr.shape[2] in (1, 2):  # grey (+ alpha), as stb_image expands it
            arr = np.repeat(arr[:, :, :1], 3, axis=2)
        lin = cc.srgb_to_linear(arr[:, :, :3]) * np.asarray(kd, dtype=np.float32)
        out = self.work / f"tex{len(self.textures)}_{file.stem}.exr"
        mi.Bitmap(np.ascontiguousarray(lin, dtype=np.float32),
                  mi.Bitmap.PixelFormat.RGB).write(str(out))
        return out

    def write_shape(self, index, P, N, T) -> Path:
        path = self.work / f"shape{index}.ply"
        write_ply(path, P, N, T)
        return path

    # -- Mitsuba dict ------------------------------------------------------------
    def medium_dict(self):
        m = self.medium
        sa = np.asarray(m.get("sigma_a", [0, 0, 0]), dtype=np.float64)
        ss = np.asarray(m.get("sigma_s", [0, 0, 0]), dtype=np.float64)
        st = sa + ss
        alb = np.where(st > 0, ss / np.where(st > 0, st, 1), 0.0)
        return {"type": "homogeneous",
                "albedo": {"type": "rgb", "value": alb.tolist()},
                "sigma_t": {"type": "rgb", "value": st.tolist()},
                "scale": 1.0,
                "phase": {"type": "hg", "g": float(m.get("g", 0.0))}}

    def integrator_dict(self, args):
        if args.integrator == "direct" and self.medium is None:
            return {"type": "direct", "emitter_samples": args.mitsuba_emitter_samples,
                    "bsdf_samples": args.mitsuba_bsdf_samples}
        depth = 2 if args.integrator == "direct" else args.max_depth
        return {"type": args.mitsuba_integrator, "max_depth": depth}

    def to_dict(self, args) -> dict:
        c = self.camera
        sensor = {"type": "perspective", "fov": float(c["vfov"]), "fov_axis": "y",
                  "near_clip": 1e-4, "far_clip": 1e7,
                  "to_world": mi.ScalarTransform4f().look_at(origin=c["origin"], target=c["target"], up=c["up"]),
                  "film": {"type": "hdrfilm", "width": self.width, "height": self.height,
                           "pixel_format": "rgb", "component_format": "float32",
                           "rfilter": {"type": "box"}},
                  "sampler": {"type": "independent"}}
        d = {"type": "scene", "integrator": self.integrator_dict(args), "sensor": sensor}
        box = None
        if self.medium is not None:
            box = self.medium.get("box")
            if box is None:
                sensor["medium"] = self.medium_dict()  # scene-filling medium
            else:
                lo, hi = np.asarray(box["min"], float), np.asarray(box["max"], float)
                d["medium_box"] = {
                    "type": "cube",
                    "to_world": mi.ScalarTransform4f().translate(((lo + hi) / 2).tolist())
                    @ mi.ScalarTransform4f().scale(((hi - lo) / 2).tolist()),
                    "bsdf": {"type": "null"},
                    "interior": self.medium_dict()}
        for i, s in enumerate(self.shapes):
            if s["texture"] is not None:
                refl = {"type": "bitmap", "filename": str(s["texture"]), "raw": True,
                        "filter_type": "bilinear", "wrap_mode": "repeat"}
            else:
                refl = {"type": "rgb", "value": s["kd"]}
            shape = {"type": "ply", "filename": str(s["file"]), "face_normals": s["face_normals"],
                     "bsdf": {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": refl}}}
            if any(v > 0 for v in s["ke"]):
                shape["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": s["ke"]}}
            if box is not None and self.medium.get("box") is not None:
                pass  # surfaces inside the box would need interior/exterior media too
            d[f"shape{i}"] = shape
        return d

    def write_xml(self, path: Path, args):
        """Mitsuba 3 XML of the same scene; PLY/EXR files are copied beside it."""
        path = path.resolve()
        assets = path.parent / (path.stem + "_assets")
        assets.mkdir(parents=True, exist_ok=True)

        def rgb(name, v):
            return f'<rgb name="{name}" value="{v[0]:.9g}, {v[1]:.9g}, {v[2]:.9g}"/>'

        c = self.camera
        integ = self.integrator_dict(args)
        ints = "".join(f'<integer name="{k}" value="{v}"/>' for k, v in integ.items() if k != "type")
        lines = ['<scene version="3.0.0">', f'  <integrator type="{integ["type"]}">{ints}</integrator>',
                 '  <sensor type="perspective">',
                 f'    <float name="fov" value="{c["vfov"]}"/><string name="fov_axis" value="y"/>',
                 '    <float name="near_clip" value="0.0001"/><float name="far_clip" value="1e7"/>',
                 '    <transform name="to_world"><lookat origin="{}" target="{}" up="{}"/></transform>'.format(
                     *(", ".join(f"{x:.9g}" for x in c[k]) for k in ("origin", "target", "up"))),
                 '    <sampler type="independent"><integer name="sample_count" value="%d"/></sampler>' % args.mitsuba_spp,
                 f'    <film type="hdrfilm"><integer name="width" value="{self.width}"/>'
                 f'<integer name="height" value="{self.height}"/><rfilter type="box"/></film>']
        med_xml = None
        if self.medium is not None:
            md = self.medium_dict()
            med_xml = (f'<medium type="homogeneous" name="{{}}">{rgb("albedo", md["albedo"]["value"])}'
                       f'{rgb("sigma_t", md["sigma_t"]["value"])}<float name="scale" value="1"/>'
                       f'<phase type="hg"><float name="g" value="{md["phase"]["g"]}"/></phase></medium>')
            if self.medium.get("box") is None:
                lines.append("    " + med_xml.format("medium"))
        lines.append("  </sensor>")
        if med_xml and self.medium.get("box") is not None:
            lo, hi = np.asarray(self.medium["box"]["min"], float), np.asarray(self.medium["box"]["max"], float)
            ctr, half = (lo + hi) / 2, (hi - lo) / 2
            lines.append('  <shape type="cube"><transform name="to_world">'
                         f'<scale value="{half[0]:.9g}, {half[1]:.9g}, {half[2]:.9g}"/>'
                         f'<translate value="{ctr[0]:.9g}, {ctr[1]:.9g}, {ctr[2]:.9g}"/></transform>'
                         '<bsdf type="null"/>' + med_xml.format("interior") + "</shape>")
        for s in self.shapes:
            ply = assets / s["file"].name
            shutil.copy(s["file"], ply)
            if s["texture"] is not None:
                tex = assets / s["texture"].name
                shutil.copy(s["texture"], tex)
                refl = (f'<texture type="bitmap" name="reflectance"><string name="filename" '
                        f'value="{tex.relative_to(path.parent)}"/><boolean name="raw" value="true"/></texture>')
            else:
                refl = rgb("reflectance", s["kd"])
            em = ""
            if any(v > 0 for v in s["ke"]):
                em = f'<emitter type="area">{rgb("radiance", s["ke"])}</emitter>'
            lines.append(f'  <shape type="ply" id="{s["name"]}"><string name="filename" '
                         f'value="{ply.relative_to(path.parent)}"/>'
                         f'<boolean name="face_normals" value="{str(s["face_normals"]).lower()}"/>'
                         f'<bsdf type="twosided"><bsdf type="diffuse">{refl}</bsdf></bsdf>{em}</shape>')
        lines.append("</scene>")
        path.write_text("\n".join(lines) + "\n")


# ----------------------------------------------------------------------------------
# Rendering

def render_mitsuba(scene_xml: Path, spp: int, batches: int, seed: int):
    """Mean image and variance of the pixel mean, from `batches` independent renders of
    the exported XML scene."""
    scene = mi.load_file(str(scene_xml))
    per = max(1, spp // batches)
    imgs = []
    for b in range(batches):
        img = mi.render(scene, spp=per, seed=seed * 1000 + b)
        imgs.append(np.array(img, dtype=np.float64)[:, :, :3])
    stack = np.stack(imgs)
    mean = stack.mean(axis=0)
    var = stack.var(axis=0, ddof=1) / batches if batches > 1 else np.zeros_like(mean)
    return mean, var, per * batches


def read_exr(path: Path) -> dict[str, np.ndarray]:
    """All channels of an EXR by name (e.g. R, G, B, variance.R), read with mi.Bitmap."""
    bmp = mi.Bitmap(str(path))
    arr = np.array(bmp, dtype=np.float64)
    if arr.ndim == 2:
        arr = arr[:, :, None]
    st = bmp.struct_()
    return {st[k].name: arr[:, :, k] for k in range(bmp.channel_count())}


def run_tessera(args, scene_file: Path, exp: Export, out: Path):
    method = "direct" if args.integrator == "direct" else "pt"
    cmd = [str(args.tessera), "render", str(scene_file), "--backend", args.backend,
           "--method", method, "--spp", str(args.spp), "--shadow-samples", str(args.shadow_samples),
           "--width", str(exp.width), "--height", str(exp.height), "--seed", str(args.seed),
           "--out", str(out)]
    if args.data_dir:
        cmd += ["--data-dir", args.data_dir]
    if args.integrator == "path" and args.max_depth >= 0 and args.pass_max_depth:
        # Mitsuba's max_depth counts segments (2: direct light); Tessera's, the vertices
        # that connect to a light (1: direct light).
        cmd += ["--max-depth", str(args.max_depth - 1)]
    print("+ " + " ".join(cmd), flush=True)
    t0 = time.time()
    r = subprocess.run(cmd, capture_output=True, text=True)
    dt = time.time() - t0
    return r, cmd, dt


def markdown(summary: dict) -> str:
    s = summary
    setup = [f"- Resolution {s['width']}×{s['height']}; Tessera `{s['tessera']['method']}` "
             f"({s['tessera']['backend']}) {s['tessera']['spp']} spp × {s['tessera']['shadow_samples']} "
             f"shadow samples, {s['tessera']['seconds']:.1f} s; Mitsuba {s['mitsuba']['version']} "
             f"`{s['mitsuba']['variant']}` `{s['mitsuba']['integrator']['type']}` {s['mitsuba']['spp']} spp "
             f"in {s['mitsuba']['batches']} batches, {s['mitsuba']['seconds']:.1f} s",
             f"- Exported: {s['export']['triangles']} triangles ({s['export']['emitting_triangles']} emitting), "
             f"{s['export']['shapes']} shapes, {s['export']['textures']} textures"]
    return cc.markdown(s, f"Mitsuba 3 check: {s['scene']} ({s['integrator']})", setup)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", nargs="?", default=str(REPO / "scenes" / "cornell-box.json"))
    ap.add_argument("--integrator", choices=["direct", "path"], default="direct")
    ap.add_argument("--mitsuba-integrator", default="volpath", choices=["volpath", "volpathmis", "path"],
                    help="Mitsuba integrator for --integrator path (and for direct with a medium)")
    ap.add_argument("--max-depth", type=int, default=-1, help="Mitsuba path/volpath max_depth (-1: unlimited)")
    ap.add_argument("--pass-max-depth", action="store_true",
                    help="also pass max_depth - 1 to tessera --max-depth (the same paths)")
    ap.add_argument("--width", type=int)
    ap.add_argument("--height", type=int)
    ap.add_argument("--spp", type=int, default=64, help="Tessera passes (default 64)")
    ap.add_argument("--shadow-samples", type=int, default=8, help="Tessera shadow samples (default 8)")
    ap.add_argument("--mitsuba-spp", type=int, default=1024)
    ap.add_argument("--mitsuba-batches", type=int, default=16,
                    help="independent Mitsuba renders whose spread gives Mitsuba's variance")
    ap.add_argument("--mitsuba-emitter-samples", type=int, default=4)
    ap.add_argument("--mitsuba-bsdf-samples", type=int, default=1)
    ap.add_argument("--write-xml", type=Path, help="also write the Mitsuba scene as XML (assets beside it)")
    cc.add_common_arguments(ap, "Mitsuba")
    args = ap.parse_args(argv)

    if args.pass_max_depth and args.integrator == "path" and 0 <= args.max_depth < 2:
        fail(f"--max-depth {args.max_depth} with --pass-max-depth: Tessera's pt needs at least 2 (direct light)")
    scene_file = Path(args.scene).resolve()
    if not scene_file.is_file():
        fail(f"scene {args.scene} not found")
    mi.set_variant("scalar_rgb")
    mi.set_log_level(mi.LogLevel.Warn)
    name = json.loads(scene_file.read_text()).get("name", scene_file.stem)
    work = args.work_dir or Path(tempfile.gettempdir()) / f"mitsuba_check_{name}_{args.integrator}"
    work.mkdir(parents=True, exist_ok=True)

    t0 = time.time()
    exp = Export(scene_file, args, work)
    print(f"exported {exp.stats['triangles']} triangles in {len(exp.shapes)} shapes "
          f"({time.time() - t0:.1f} s) to {work}", flush=True)
    notes = list(args.note)
    if args.flip_emitters:
        notes.append("NEGATIVE CONTROL (--flip-emitters): Mitsuba's lights emit on the wrong side")
    if exp.medium is not None:
        notes.append("scene has a `medium` block: exported as a Mitsuba homogeneous medium (hg phase), "
                     "rendered with the chosen Mitsuba volumetric integrator")
    if args.write_xml:
        exp.write_xml(args.write_xml, args)
        print(f"wrote {args.write_xml}")

    # Tessera first: it is fast and may reject the method (pt is not there yet).
    if not args.tessera.is_file():
        fail(f"{args.tessera} not found: build Tessera first (scripts/build)")
    t_exr = work / "tessera.exr"
    r, cmd, t_sec = run_tessera(args, scene_file, exp, t_exr)
    if r.returncode != 0:
        out = (r.stderr + "\n" + r.stdout).strip().splitlines()
        msg = "\n  ".join([l for l in out if "error" in l] or out[-3:])
        if args.integrator == "path" and ("method" in msg or "pt" in msg):
            print(f"mitsuba_check: SKIPPED: tessera does not support --method pt yet:\n  {msg}")
            return 0
        fail(f"tessera failed ({r.returncode}): {msg}")
    ch = read_exr(t_exr)
    t_img = channels_rgb(ch)
    t_var = channels_rgb(ch, "variance.")
    if t_img is None:
        fail(f"{t_exr}: no R, G, B channels (have {sorted(ch)})")
    if t_var is None:
        notes.append("Tessera output has no variance.R/G/B channels: no z-scores")

    sd = exp.to_dict(args)
    print(f"rendering with Mitsuba {mi.__version__} ({sd['integrator']['type']}, "
          f"{args.mitsuba_spp} spp)...", flush=True)
    t1 = time.time()
    scene_xml = work / "scene.xml"
    exp.write_xml(scene_xml, args)
    m_img, m_var, m_spp = render_mitsuba(scene_xml, args.mitsuba_spp, args.mitsuba_batches, args.seed)
    m_sec = time.time() - t1
    mi.Bitmap(m_img.astype(np.float32), mi.Bitmap.PixelFormat.RGB).write(str(work / "mitsuba.exr"))
    mi.Bitmap(m_var.astype(np.float32), mi.Bitmap.PixelFormat.RGB).write(str(work / "mitsuba_variance.exr"))
    for tag, img in (("tessera", t_img), ("mitsuba", m_img)):
        png = np.clip(img, 0, None) ** (1 / 2.2)
        mi.Bitmap(np.clip(png * 255 + 0.5, 0, 255).astype(np.uint8), mi.Bitmap.PixelFormat.RGB).write(
            str(work / f"{tag}.png"))
    ratio_img = np.log2((t_img.mean(axis=2) + 1e-3) / (m_img.mean(axis=2) + 1e-3))
    diff = np.clip(128 + 255 * ratio_img, 0, 255).astype(np.uint8)
    mi.Bitmap(diff).write(str(work / "log2_ratio.png"))

    cmp_ = compare(t_img, t_var, m_img, m_var, args.z_limit)
    ok = all(abs(d["ratio"] - 1) <= args.tolerance for d in cmp_["channels"].values())
    rel_scene = os.path.relpath(scene_file, REPO)
    summary = {
        "scene": name, "scene_file": rel_scene, "integrator": args.integrator,
        "date": datetime.datetime.now().isoformat(timespec="seconds"),
        "machine": machine_note(args.machine), "width": exp.width, "height": exp.height,
        "tessera": {"command": " ".join(os.path.relpath(c, REPO) if c.startswith(str(REPO)) else c for c in cmd),
                    "method": "direct" if args.integrator == "direct" else "pt", "backend": args.backend,
                    "spp": args.spp, "shadow_samples": args.shadow_samples, "seconds": t_sec},
        "mitsuba": {"version": mi.__version__, "variant": mi.variant(), "integrator": sd["integrator"],
                    "spp": m_spp, "batches": args.mitsuba_batches, "seconds": m_sec},
        "export": dict(exp.stats, shapes=len(exp.shapes),
                       obj_reader="tinyobjloader" if cc.tinyobjloader else "built-in"),
        "comparison": cmp_, "tolerance": args.tolerance, "z_limit": args.z_limit, "pass": ok,
        "work_dir": str(work), "notes": notes,
    }
    args.results_dir.mkdir(parents=True, exist_ok=True)
    suffix = "" if args.integrator == "direct" else f"_{args.integrator}"
    base = args.results_dir / f"mitsuba_check_{name}{suffix}"
    base.with_suffix(".json").write_text(json.dumps(summary, indent=2) + "\n")
    md = markdown(summary)
    base.with_suffix(".md").write_text(md)
    print(md)
    print(f"images: {work}/{{tessera,mitsuba}}.{{exr,png}}, mitsuba_variance.exr, log2_ratio.png; results: {base}.{{json,md}}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
