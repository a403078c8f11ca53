#!/usr/bin/env python3
"""Shared parts of Tessera's cross-checks against other renderers
(bench/mitsuba_check.py: Mitsuba 3; bench/cycles_check.py: Blender Cycles).

- Reading a Tessera scene (JSON + OBJ/MTL, scenes/README.md) the way Tessera's loader
  (host/scene/) does: data path, OBJ triangulation, MTL Kd/Ke/map_Kd, material
  overrides, object transforms, JSON quad lights. `SceneExport` turns it into a list of
  world-space triangle groups, one per (object, material), each with reflectance,
  emission and texture; a renderer's exporter subclasses it and writes the groups in
  its own format (`write_shape`, `texture`).
- The comparison of a Tessera image with a reference image: per-channel mean radiance
  ratio, relMSE and per-pixel z-scores (`compare`), and the Markdown/JSON report
  (`markdown`, `write_results`). See bench/README.md.
"""
from __future__ import annotations

import json
import math
import os
import platform
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent

try:
    import numpy as np
except ImportError:  # pragma: no cover
    sys.exit("crosscheck: numpy is missing: pip install -r bench/requirements.txt")
try:
    import tinyobjloader  # optional: the same OBJ parser (and quad split) Tessera uses
except ImportError:
    tinyobjloader = None

# Prefix of error messages; each check sets it to its own name.
TOOL = "crosscheck"


def fail(msg: str) -> "NoReturn":  # noqa: F821
    sys.exit(f"{TOOL}: error: {msg}")


# ----------------------------------------------------------------------------------
# Data path (same order as Tessera: next to the scene, --data-dir, $TESSERA_DATA,
# ../shared/scenes beside the checkout).

def data_dirs(scene_file: Path, data_dir: str | None) -> list[Path]:
    dirs = [scene_file.parent]
    if data_dir:
        dirs.append(Path(data_dir))
    if os.environ.get("TESSERA_DATA"):
        dirs.append(Path(os.environ["TESSERA_DATA"]))
    dirs.append(REPO.parent / "shared" / "scenes")
    return dirs


def resolve(rel: str, dirs: list[Path]) -> Path:
    p = Path(rel)
    if p.is_absolute():
        if p.is_file():
            return p
        fail(f"{rel} not found")
    for d in dirs:
        if (d / p).is_file():
            return (d / p).resolve()
    fail(f"{rel} not found in " + ", ".join(str(d) for d in dirs))


# ----------------------------------------------------------------------------------
# OBJ / MTL

def parse_mtl(path: Path) -> dict[str, dict]:
    """Minimal MTL reader: Kd (clamped to [0, 1] like Tessera), Ke, map_Kd."""
    mats: dict[str, dict] = {}
    cur = None
    for line in path.read_text(errors="replace").splitlines():
        tok = line.split("#", 1)[0].split()
        if not tok:
            continue
        key = tok[0]
        if key == "newmtl":
            cur = mats.setdefault(" ".join(tok[1:]), {"Kd": [0.0] * 3, "Ke": [0.0] * 3, "map_Kd": None})
        elif cur is None:
            continue
        elif key in ("Kd", "Ke") and len(tok) >= 2:
            vals = [float(x) for x in tok[1:4]]
            if len(vals) == 1:
                vals = vals * 3
            cur[key] = vals
        elif key == "map_Kd" and len(tok) >= 2:
            cur["map_Kd"] = tok[-1]  # options before the file name are ignored
    for m in mats.values():
        m["Kd"] = [min(max(c, 0.0), 1.0) for c in m["Kd"]]
    return mats


def _split_polygon(verts, pos):
    """Triangulates one face like tinyobjloader 2.0 (Tessera's parser): a quad is split
    along its shorter diagonal, larger polygons as a fan (approximation)."""
    if len(verts) == 4:
        p = [pos[v[0]] for v in verts]
        d02 = sum((p[2][k] - p[0][k]) ** 2 for k in range(3))
        d13 = sum((p[3][k] - p[1][k]) ** 2 for k in range(3))
        if d02 < d13:
            return [(verts[0], verts[1], verts[2]), (verts[0], verts[2], verts[3])]
        return [(verts[0], verts[1], verts[3]), (verts[1], verts[2], verts[3])]
    return [(verts[0], verts[i], verts[i + 1]) for i in range(1, len(verts) - 1)]


def load_obj_python(path: Path):
    pos, nrm, uv = [], [], []
    mtllib, cur_mat = None, None
    tris = []  # ((v, vt, vn) x3, material name or None)
    for line in path.read_text(errors="replace").splitlines():
        tok = line.split("#", 1)[0].split()
        if not tok:
            continue
        k = tok[0]
        if k == "v":
            pos.append([float(x) for x in tok[1:4]])
        elif k == "vn":
            nrm.append([float(x) for x in tok[1:4]])
        elif k == "vt":
            uv.append([float(x) for x in (tok[1:3] + ["0"])[:2]])
        elif k == "mtllib":
            mtllib = " ".join(tok[1:])
        elif k == "usemtl":
            cur_mat = " ".join(tok[1:])
        elif k == "f":
            verts = []
            for t in tok[1:]:
                parts = (t.split("/") + ["", ""])[:3]

                def idx(s, n):
                    if not s:
                        return -1
                    i = int(s)
                    return i - 1 if i > 0 else n + i
                verts.append((idx(parts[0], len(pos)), idx(parts[1], len(uv)), idx(parts[2], len(nrm))))
            for tri in _split_polygon(verts, pos):
                tris.append((tri, cur_mat))
    return pos, uv, nrm, mtllib, tris


def load_obj(path: Path):
    """Returns (materials: dict name -> mtl dict, groups: dict name|None -> arrays) where
    each group has per-corner positions P (n,3,3), normals N (n,3,3) (NaN where the file
    gives none) and uvs T (n,3,2)."""
    if tinyobjloader is not None:
        reader = tinyobjloader.ObjReader()
        cfg = tinyobjloader.ObjReaderConfig()
        cfg.triangulate = True
        if not reader.ParseFromFile(str(path), cfg):
            fail(f"{path}: OBJ parse error: {reader.Error()}")
        attrib = reader.GetAttrib()
        pos = np.asarray(attrib.vertices, dtype=np.float64).reshape(-1, 3)
        nrm = np.asarray(attrib.normals, dtype=np.float64).reshape(-1, 3)
        uvs = np.asarray(attrib.texcoords, dtype=np.float64).reshape(-1, 2)
        mat_names = [m.name for m in reader.GetMaterials()]
        vi, ti, ni, mids = [], [], [], []
        for shape in reader.GetShapes():
            for i in shape.mesh.indices:
                vi.append(i.vertex_index)
                ti.append(i.texcoord_index)
                ni.append(i.normal_index)
            mids.extend(shape.mesh.material_ids)
        vi, ti, ni = (np.asarray(a, dtype=np.int64).reshape(-1, 3) for a in (vi, ti, ni))
        tri_mat = [mat_names[m] if m >= 0 else None for m in mids]
        mtllib = None
        for line in path.read_text(errors="replace").splitlines():
            if line.strip().startswith("mtllib"):
                mtllib = line.strip().split(None, 1)[1].split("#")[0].strip()
                break
    else:
        pos_l, uv_l, nrm_l, mtllib, tris = load_obj_python(path)
        pos = np.asarray(pos_l, dtype=np.float64).reshape(-1, 3)
        nrm = np.asarray(nrm_l, dtype=np.float64).reshape(-1, 3)
        uvs = np.asarray(uv_l, dtype=np.float64).reshape(-1, 2)
        vi = np.asarray([[c[0] for c in t] for t, _ in tris], dtype=np.int64).reshape(-1, 3)
        ti = np.asarray([[c[1] for c in t] for t, _ in tris], dtype=np.int64).reshape(-1, 3)
        ni = np.asarray([[c[2] for c in t] for t, _ in tris], dtype=np.int64).reshape(-1, 3)
        tri_mat = [m for _, m in tris]
    materials = parse_mtl(path.parent / mtllib) if mtllib else {}
    P = pos[vi]
    N = np.full(P.shape, np.nan)
    if len(nrm):
        ok = ni >= 0
        N[ok] = nrm[ni[ok]]
    T = np.zeros(P.shape[:2] + (2,))
    if len(uvs):
        ok = ti >= 0
        T[ok] = uvs[ti[ok]]
    tri_mat_arr = np.asarray([m if m is not None else "" for m in tri_mat], dtype=object)
    groups = {}
    for name in dict.fromkeys(tri_mat):
        sel = tri_mat_arr == (name if name is not None else "")
        groups[name] = {"P": P[sel], "N": N[sel], "T": T[sel]}
    return materials, groups


# ----------------------------------------------------------------------------------
# Transforms (Tessera: world = T * R_n ... R_1 * S * p)

def rotation(axis, degrees):
    a = np.asarray(axis, dtype=np.float64)
    a = a / np.linalg.norm(a)
    t = math.radians(degrees)
    c, s = math.cos(t), math.sin(t)
    x, y, z = a
    K = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return c * np.eye(3) + s * K + (1 - c) * np.outer(a, a)


def object_transform(tr: dict | None):
    tr = tr or {}
    s = tr.get("scale", 1.0)
    S = np.diag([s, s, s] if isinstance(s, (int, float)) else s).astype(np.float64)
    R = np.eye(3)
    for r in tr.get("rotate", []):
        R = rotation(r["axis"], r["degrees"]) @ R
    return R @ S, np.asarray(tr.get("translate", [0, 0, 0]), dtype=np.float64)


# ----------------------------------------------------------------------------------
# Export: the scene as world-space triangle groups

def srgb_to_linear(c8: np.ndarray) -> np.ndarray:
    c = c8.astype(np.float32) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4).astype(np.float32)


class SceneExport:
    """A Tessera scene as a list of shapes plus camera and medium.

    Each shape is a dict: name, file (what `write_shape` returned), kd and ke (RGB
    lists: reflectance, and radiance in W/(sr·m²) emitted on the side of the geometric
    normal cross(p1 − p0, p2 − p0)), texture (what `texture` returned, or None) and
    face_normals (True when the shape has no usable vertex normals, always for
    emitters). Triangle corners are in world space, P and N of shape (n, 3, 3), uv T of
    shape (n, 3, 2) with Tessera's (OBJ) convention v = 0 at the image's bottom row.
    Subclasses implement `write_shape(index, P, N, T)` (N is None for face normals)
    and `texture(file, kd)`."""

    def __init__(self, scene_file: Path, args, work: Path):
        self.scene_file = scene_file
        self.flip_emitters = getattr(args, "flip_emitters", False)
        self.doc = json.loads(scene_file.read_text())
        self.name = self.doc.get("name", scene_file.stem)
        self.work = work
        self.dirs = data_dirs(scene_file, args.data_dir)
        cam = self.doc["camera"]
        res = cam.get("resolution", [512, 512])
        self.width = args.width or res[0]
        self.height = args.height or res[1]
        self.camera = {"origin": cam["position"], "target": cam["look_at"],
                       "up": cam.get("up", [0, 1, 0]), "vfov": cam.get("vfov", 40.0)}
        self.shapes: list[dict] = []
        self.textures: dict[tuple, object] = {}
        self.medium = self.doc.get("medium")
        self.stats = {"triangles": 0, "emitting_triangles": 0, "textures": 0}
        self._build()

    def write_shape(self, index: int, P: np.ndarray, N: np.ndarray | None, T: np.ndarray):
        raise NotImplementedError

    def texture(self, file: Path, kd) -> object:
        raise NotImplementedError

    def _texture(self, file: Path, kd):
        key = (str(file), tuple(round(c, 9) for c in kd))
        if key not in self.textures:
            self.textures[key] = self.texture(file, kd)
            self.stats["textures"] += 1
        return self.textures[key]

    def _add(self, name, P, N, T, kd, ke, tex_file):
        n = P.shape[0]
        if n == 0:
            return
        emissive = any(c > 0 for c in ke)
        if emissive and self.flip_emitters:  # negative control: lights emit on the wrong side
            P, N, T = P[:, [0, 2, 1]], N[:, [0, 2, 1]], T[:, [0, 2, 1]]
        # Geometric normal cross(p1 - p0, p2 - p0): the face normal of both references,
        # the front side of Tessera's one-sided area lights. Corners without a usable
        # normal use it.
        ng = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
        ln = np.linalg.norm(ng, axis=1, keepdims=True)
        ng = np.where(ln > 0, ng / np.where(ln > 0, ln, 1), np.array([0.0, 1.0, 0.0]))
        use_normals = None
        if not np.all(np.isnan(N)) and not emissive:
            Nn = N.copy()
            l2 = np.sum(Nn * Nn, axis=2, keepdims=True)
            bad = ~(np.isfinite(l2) & (l2 > 0))
            Nn = np.where(bad, np.repeat(ng[:, None, :], 3, axis=1), Nn / np.sqrt(np.where(bad, 1, l2)))
            use_normals = Nn
        path = self.write_shape(len(self.shapes), P, use_normals, T)
        self.shapes.append({"name": name, "file": path, "kd": list(map(float, kd)),
                            "ke": list(map(float, ke)), "texture": tex_file,
                            "face_normals": use_normals is None})
        self.stats["triangles"] += n
        if emissive:
            self.stats["emitting_triangles"] += n

    def _build(self):
        overrides = self.doc.get("materials", {})
        cache = {}
        for i, obj in enumerate(self.doc["objects"]):
            f = resolve(obj["mesh"], self.dirs)
            if f not in cache:
                cache[f] = load_obj(f)
            mats, groups = cache[f]
            L, t = object_transform(obj.get("transform"))
            flip = np.linalg.det(L) < 0
            Ninv = np.linalg.inv(L).T
            for mname, g in groups.items():
                P = g["P"] @ L.T + t
                N = g["N"] @ Ninv.T
                T = g["T"]
                if flip:  # Tessera swaps corners 1 and 2 to keep the front side
                    P, N, T = P[:, [0, 2, 1]], N[:, [0, 2, 1]], T[:, [0, 2, 1]]
                if mname is None:
                    m = {"Kd": [0.5] * 3, "Ke": [0.0] * 3, "map_Kd": None}
                else:
                    if mname not in mats:
                        fail(f"{f}: usemtl {mname} not in the MTL")
                    m = dict(mats[mname])
                    o = overrides.get(mname, {})
                    if "albedo" in o:
                        m["Kd"] = o["albedo"]
                    if "emission" in o:
                        m["Ke"] = o["emission"]
                tex = None
                if m["map_Kd"]:
                    tex = self._texture((f.parent / m["map_Kd"]).resolve(), m["Kd"])
                self._add(f"obj{i}_{mname}", P, N, T, m["Kd"], m["Ke"], tex)
        for i, light in enumerate(self.doc.get("lights", [])):
            if light.get("type") != "quad":
                fail(f"lights[{i}]: unsupported type {light.get('type')}")
            c, e1, e2 = (np.asarray(light[k], dtype=np.float64) for k in ("corner", "edge1", "edge2"))
            p = [c, c + e1, c + e1 + e2, c + e2]
            P = np.array([[p[0], p[1], p[2]], [p[0], p[2], p[3]]])
            T = np.array([[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]], dtype=np.float64)
            self._add(f"json-light-{i}", P, np.full(P.shape, np.nan), T, [0, 0, 0], light["radiance"], None)
        if self.stats["emitting_triangles"] == 0:
            fail("the scene has no emitters")


# ----------------------------------------------------------------------------------
# Comparison

def compare(t_img, t_var, r_img, r_var, z_limit: float, ref: str = "mitsuba"):
    """Tessera image t_img (h, w, 3) against a reference r_img, with the variances of
    both pixel means (t_var, r_var; t_var None: no z-scores). Per channel: means
    (keys tessera_mean and <ref>_mean), their ratio, relMSE and the z statistics; also
    the luminance-weighted ratio (Rec. 709 weights) and the mean fraction of |z| > z_limit."""
    res = {"channels": {}}
    names = "RGB"
    for c in range(3):
        a, b = t_img[:, :, c], r_img[:, :, c]
        d = {"tessera_mean": float(a.mean()), f"{ref}_mean": float(b.mean())}
        d["ratio"] = d["tessera_mean"] / d[f"{ref}_mean"] if d[f"{ref}_mean"] > 0 else float("nan")
        d["relmse"] = float(np.mean((a - b) ** 2 / (b * b + 0.01)))
        if t_var is not None:
            # z only where either side has sampling noise; pixels where both variances
            # are 0 (unlit, occluded, background, constant emission) are compared exactly.
            den = t_var[:, :, c] + r_var[:, :, c]
            diff = a - b
            noisy = den > 0
            z = diff[noisy] / np.sqrt(den[noisy])
            exact_mismatch = ~noisy & (np.abs(diff) > 1e-5 * np.maximum(np.abs(a), np.abs(b)) + 1e-12)
            d["z_pixels"] = int(noisy.sum())
            d["z_mean"] = float(z.mean()) if z.size else float("nan")
            d["z_abs_mean"] = float(np.abs(z).mean()) if z.size else float("nan")
            d["z_frac_over"] = float(np.mean(np.abs(z) > z_limit)) if z.size else float("nan")
            d["zero_variance_pixels"] = int((~noisy).sum())
            d["zero_variance_mismatches"] = int(exact_mismatch.sum())
        res["channels"][names[c]] = d
    res["relmse"] = float(np.mean([res["channels"][n]["relmse"] for n in names]))
    # Brightness (luminance-weighted) ratio and the worst channel.
    w = np.array([0.2126, 0.7152, 0.0722])
    res["luminance_ratio"] = float((t_img.mean(axis=(0, 1)) @ w) / max(r_img.mean(axis=(0, 1)) @ w, 1e-30))
    if t_var is not None:
        res["z_frac_over"] = float(np.mean([res["channels"][n]["z_frac_over"] for n in names]))
    return res


def channels_rgb(ch: dict, prefix: str = "") -> np.ndarray | None:
    keys = [f"{prefix}R", f"{prefix}G", f"{prefix}B"]
    if not all(k in ch for k in keys):
        return None
    return np.stack([ch[k] for k in keys], axis=2)


def add_common_arguments(ap, ref_name: str) -> None:
    """The options both checkers take (Tessera's side, the comparison, where results go).
    ref_name names the other renderer in the help texts ("Mitsuba", "Cycles")."""
    ap.add_argument("--backend", default="embree", choices=["embree", "opencl"])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--tessera", type=Path, default=REPO / "build" / "tessera")
    ap.add_argument("--data-dir")
    ap.add_argument("--tolerance", type=float, default=0.03, help="allowed |ratio - 1| per channel")
    ap.add_argument("--z-limit", type=float, default=3.0)
    ap.add_argument("--work-dir", type=Path, help="where images and exported meshes go (default: a temp dir, kept)")
    ap.add_argument("--flip-emitters", action="store_true",
                    help=f"negative control: reverse the winding of emitting triangles in the {ref_name} "
                         "export (the check must then FAIL)")
    ap.add_argument("--results-dir", type=Path, default=REPO / "bench" / "results")
    ap.add_argument("--machine", help="machine description for the results (default: detected)")
    ap.add_argument("--note", action="append", default=[], help="free-text note for the results (repeatable)")


def machine_note(user: str | None) -> str:
    if user:
        return user
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    virt = ""
    for flag, what in (("--vm", "VM"), ("--container", "container")):
        try:
            r = subprocess.run(["systemd-detect-virt", flag], capture_output=True, text=True)
            if r.returncode == 0 and r.stdout.strip() not in ("", "none"):
                virt += f"{r.stdout.strip()} {what}, "
        except OSError:
            pass
    return f"{virt}{os.cpu_count()} cores, {cpu}, {platform.system()} {platform.release()}"


def markdown(s: dict, title: str, setup: list[str], ref: str = "mitsuba", ref_name: str = "Mitsuba",
             ref_sym: str = "M", ref_poss: str | None = None) -> str:
    """The report: `title`, the date/machine line, the `setup` lines (Markdown list
    items), the per-channel table of `compare`'s result (s["comparison"]), the verdict,
    how to read z, and s["notes"]."""
    ref_poss = ref_poss or f"{ref_name}'s"
    L = [f"# {title}", "", f"- Date: {s['date']}; machine: {s['machine']}"] + setup
    L += ["", f"| channel | Tessera mean | {ref_name} mean | ratio | relMSE | mean z | mean abs z | frac abs z > "
          f"{s['z_limit']:g} | noise-free pixels (mismatched) |", "|---|---|---|---|---|---|---|---|---|"]
    for n, d in s["comparison"]["channels"].items():
        L.append(f"| {n} | {d['tessera_mean']:.5g} | {d[f'{ref}_mean']:.5g} | {d['ratio']:.4f} | "
                 f"{d['relmse']:.3g} | {d.get('z_mean', float('nan')):+.3f} | "
                 f"{d.get('z_abs_mean', float('nan')):.3f} | {100 * d.get('z_frac_over', float('nan')):.2f}% | "
                 f"{d.get('zero_variance_pixels', 0)} ({d.get('zero_variance_mismatches', 0)}) |")
    c = s["comparison"]
    L += ["", f"Luminance ratio {c['luminance_ratio']:.4f}; relMSE {c['relmse']:.3g}; "
          f"tolerance ±{s['tolerance']:g} on each channel's ratio: **{'PASS' if s['pass'] else 'FAIL'}**.",
          "", f"z = (Tessera − {ref_name}) / sqrt(var_T + var_{ref_sym}), with var_T Tessera's `variance.*` channels "
          f"and var_{ref_sym} the variance of {ref_poss} mean across its batches, over the pixels where "
          f"var_T + var_{ref_sym} > 0; the others (no noise on either side) must agree to 1e-5 and are counted "
          "in the last column. For two unbiased renderers "
          "about 0.27% of pixels per channel exceed |z| > 3 (somewhat more at geometric edges, "
          "where the pixel distribution is far from normal, and because both variances are estimates); "
          "mean |z| ≈ 0.80; the mean signed z shows a bias.", ""]
    if s.get("notes"):
        L += ["Notes:", ""] + [f"- {n}" for n in s["notes"]] + [""]
    return "\n".join(L)


def write_results(summary: dict, base: Path, md: str):
    """Writes base.json (the summary) and base.md (the report)."""
    base.parent.mkdir(parents=True, exist_ok=True)
    base.with_suffix(".json").write_text(json.dumps(summary, indent=2) + "\n")
    base.with_suffix(".md").write_text(md)
