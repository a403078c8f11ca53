#!/usr/bin/env python3
"""Writes the stand-in scenes for the seed thesis's scenes we have no data for (issue 20):
office, conference, desk, deskar, subdivided and shirley6, plus fog (PM) versions of office,
subdivided and shirley6. Everything is built here from boxes, cylinders, a sphere and one
Loop-subdivided mesh; no downloaded data. scenes/README.md states each scene's dimensions,
materials and light radiances and why the exposure is sensible.

Deterministic: the same files byte for byte on every run (no clock, no unseeded randomness,
fixed formatting; the subdivision is rational arithmetic plus sqrt). Python 3 standard
library only, so the build can run it on a fresh machine.

Two groups of output, paths relative to --out (default: the scenes/ folder above this
script):
  small  the scene JSON files and their OBJ/MTL meshes under standins/ (committed, a few
         hundred kB in all);
  large  generated/subdivided-knot.{obj,mtl}: the 221,184-triangle Loop-subdivided knot of
         the subdivided scenes (about 15 MB, not committed: CMake runs `--what large` at
         build time; scenes/generated/ is in .gitignore).

Usage: standins.py [--out DIR] [--what small|large|all]
tests/scene/standin_scenes_test.cpp regenerates everything into a scratch folder and
compares it byte for byte with the committed files and the build's large mesh.
"""
import argparse
import json
import math
import os
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
SCENES = HERE.parent


def num(x, digits=5):
    """Fixed-point text of x without trailing zeros ('0.5', '-1.25', '2'); never '-0'."""
    s = f"{x:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def write(path, text):
    """Atomic write (temporary file, then rename), so an interrupted run or two builds
    generating at once never leave a truncated file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    with open(tmp, "w", newline="\n") as f:
        f.write(text)
    os.replace(tmp, path)


# ---------------------------------------------------------------------------------------
# Meshes


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


class Mesh:
    """Positions and polygons grouped by material, written as one OBJ + MTL. Polygons are
    wound counter-clockwise seen from the side they face (`facing`), which only matters for
    emitters: Tessera's surfaces reflect on both sides."""

    def __init__(self, name, materials):
        self.name = name
        self.materials = materials  # name -> (r, g, b) albedo, in MTL order
        self.v = []
        self.faces = {m: [] for m in materials}

    def poly(self, mat, pts, facing=None):
        if facing is not None and dot(cross(sub(pts[1], pts[0]), sub(pts[2], pts[0])), facing) < 0:
            pts = pts[::-1]
        base = len(self.v) + 1
        self.v.extend(pts)
        self.faces[mat].append(list(range(base, base + len(pts))))

    def box(self, mat, lo, hi, rot_y=0.0, pivot=None, skip=()):
        """Axis-aligned box lo..hi, faces outward, optionally rotated by rot_y degrees about
        the vertical line through pivot (x, z) (default: the box's centre). `skip` names
        faces to leave out: '-x', '+x', '-y', '+y', '-z', '+z'."""
        px, pz = pivot if pivot else ((lo[0] + hi[0]) / 2, (lo[2] + hi[2]) / 2)
        c, s = math.cos(math.radians(rot_y)), math.sin(math.radians(rot_y))

        def p(i, j, k):
            x, y, z = (lo[0], hi[0])[i], (lo[1], hi[1])[j], (lo[2], hi[2])[k]
            dx, dz = x - px, z - pz
            return (px + c * dx + s * dz, y, pz - s * dx + c * dz)

        def rot(n):
            return (c * n[0] + s * n[2], n[1], -s * n[0] + c * n[2])

        faces = {"-x": ([(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)], (-1, 0, 0)),
                 "+x": ([(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)], (1, 0, 0)),
                 "-y": ([(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)], (0, -1, 0)),
                 "+y": ([(0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)], (0, 1, 0)),
                 "-z": ([(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)], (0, 0, -1)),
                 "+z": ([(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)], (0, 0, 1))}
        for key, (corners, n) in faces.items():
            if key not in skip:
                self.poly(mat, [p(*q) for q in corners], rot(n))

    def room(self, lo, hi, floor, walls, ceiling):
        """A closed room lo..hi with faces pointing inward."""
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        self.poly(floor, [(x0, y0, z0), (x0, y0, z1), (x1, y0, z1), (x1, y0, z0)], (0, 1, 0))
        self.poly(ceiling, [(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)], (0, -1, 0))
        self.poly(walls, [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)], (0, 0, 1))
        self.poly(walls, [(x0, y0, z1), (x0, y1, z1), (x1, y1, z1), (x1, y0, z1)], (0, 0, -1))
        self.poly(walls, [(x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (x0, y0, z1)], (1, 0, 0))
        self.poly(walls, [(x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0)], (-1, 0, 0))

    def cylinder(self, mat, centre, radius, height, segments=24, top=True):
        """Vertical cylinder standing on centre (x, y, z): side quads and a top cap (the
        bottom rests on something)."""
        cx, y0, cz = centre
        ring = [(cx + radius * math.cos(2 * math.pi * i / segments), cz + radius * math.sin(2 * math.pi * i / segments))
                for i in range(segments)]
        for i in range(segments):
            (xa, za), (xb, zb) = ring[i], ring[(i + 1) % segments]
            mid = ((xa + xb) / 2 - cx, 0, (za + zb) / 2 - cz)
            self.poly(mat, [(xa, y0, za), (xb, y0, zb), (xb, y0 + height, zb), (xa, y0 + height, za)], mid)
        if top:
            self.poly(mat, [(x, y0 + height, z) for x, z in ring], (0, 1, 0))

    def sphere(self, mat, centre, radius, stacks=10, slices=16):
        cx, cy, cz = centre

        def p(i, j):
            th, ph = math.pi * i / stacks, 2 * math.pi * j / slices
            return (cx + radius * math.sin(th) * math.cos(ph), cy + radius * math.cos(th),
                    cz + radius * math.sin(th) * math.sin(ph))

        for i in range(stacks):
            for j in range(slices):
                a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)
                out = sub(p(i + 0.5, j + 0.5), centre)
                # the first stack's top corners are the north pole, the last's bottom the south
                self.poly(mat, [a, b, c] if i == 0 else ([a, b, d] if i == stacks - 1 else [a, b, c, d]), out)

    def obj_text(self):
        out = [f"# {self.name}: written by scenes/generate/standins.py (do not edit by hand)",
               f"mtllib {self.name}.mtl"]
        out += [f"v {num(x)} {num(y)} {num(z)}" for x, y, z in self.v]
        for mat in self.materials:
            if self.faces[mat]:
                out.append(f"usemtl {mat}")
                out += ["f " + " ".join(str(i) for i in f) for f in self.faces[mat]]
        return "\n".join(out) + "\n"

    def write(self, folder):
        write(folder / f"{self.name}.obj", self.obj_text())
        write(folder / f"{self.name}.mtl", mtl_text(self.name, self.materials))


def mtl_text(name, materials):
    out = [f"# {name}: written by scenes/generate/standins.py (do not edit by hand)"]
    for m, (r, g, b) in materials.items():
        out += [f"newmtl {m}", f"Kd {num(r, 3)} {num(g, 3)} {num(b, 3)}", ""]
    return "\n".join(out)


# ---------------------------------------------------------------------------------------
# Scene JSON


def light(centre, u, v, radiance, facing):
    """A JSON quad light centred at `centre` with edges u, v; asserts that it emits towards
    `facing` (Tessera's quads emit on the side of cross(edge1, edge2))."""
    assert dot(cross(u, v), facing) > 0, (centre, u, v, facing)
    corner = tuple(centre[i] - u[i] / 2 - v[i] / 2 for i in range(3))
    return {"type": "quad", "corner": list(corner), "edge1": list(u), "edge2": list(v), "radiance": list(radiance)}


def ceiling_light(cx, y, cz, sx, sz, radiance):
    return light((cx, y, cz), (sx, 0, 0), (0, 0, sz), radiance, (0, -1, 0))


def json_value(x):
    if isinstance(x, str):
        return json.dumps(x)
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        return num(x, 4)
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(json_value(e) for e in x) + "]"
    return "{" + ", ".join(f"{json_value(k)}: {json_value(v)}" for k, v in x.items()) + "}"


def scene_json(doc):
    """The scene as JSON: top-level keys one per line, list entries one per line, each
    entry on one line (the layout of the hand-written scenes)."""
    lines = ["{"]
    items = list(doc.items())
    for n, (k, v) in enumerate(items):
        end = "," if n + 1 < len(items) else ""
        if isinstance(v, list) and v and isinstance(v[0], dict):
            lines.append(f'  "{k}": [')
            lines += [f"    {json_value(e)}" + ("," if i + 1 < len(v) else "") for i, e in enumerate(v)]
            lines.append(f"  ]{end}")
        elif isinstance(v, dict) and k in ("camera", "medium"):
            lines.append(f'  "{k}": {{')
            sub_items = list(v.items())
            lines += [f'    "{sk}": {json_value(sv)}' + ("," if i + 1 < len(sub_items) else "")
                      for i, (sk, sv) in enumerate(sub_items)]
            lines.append(f"  }}{end}")
        else:
            lines.append(f'  "{k}": {json_value(v)}{end}')
    return "\n".join(lines + ["}"]) + "\n"


def camera(position, look_at, vfov):
    return {"position": list(position), "look_at": list(look_at), "up": [0, 1, 0], "vfov": vfov,
            "resolution": [512, 512]}


def fog_of(doc, name, stands_in_for, medium):
    fog = dict(doc)
    fog["name"] = name
    fog["stands_in_for"] = stands_in_for
    fog["medium"] = medium
    return fog


def medium(sigma_a, sigma_s, g, lo, hi):
    """A homogeneous medium filling the room lo..hi (coefficients per metre)."""
    return {"sigma_a": [sigma_a] * 3, "sigma_s": [sigma_s] * 3, "g": g, "box": {"min": list(lo), "max": list(hi)}}


class Lcg:
    """Numerical Recipes' 32-bit LCG: a fixed sequence on every Python version (book
    colours and heights)."""

    def __init__(self, seed):
        self.s = seed

    def uniform(self, lo, hi):
        self.s = (1664525 * self.s + 1013904223) % 2 ** 32
        return lo + (hi - lo) * self.s / 2 ** 32


# ---------------------------------------------------------------------------------------
# Furniture (metres; y up, floor at y = 0)

WALL = (0.75, 0.73, 0.68)
CEILING = (0.8, 0.8, 0.78)


def table(m, top_mat, leg_mat, x0, x1, z0, z1, height, legs_x=2, leg=0.05, top=0.04):
    """A table top x0..x1 × z0..z1 at `height` on legs_x × 2 square legs."""
    m.box(top_mat, (x0, height - top, z0), (x1, height, z1))
    for i in range(legs_x):
        x = x0 + 0.05 + (x1 - x0 - 0.1 - leg) * i / (legs_x - 1)
        for z in (z0 + 0.05, z1 - 0.05 - leg):
            m.box(leg_mat, (x, 0, z), (x + leg, height - top, z + leg))


def chair(m, seat_mat, leg_mat, cx, cz, facing_deg, seat=0.45, seat_h=0.45, back_h=0.45, leg=0.03):
    """A chair centred at (cx, cz): seat, backrest and four legs, the sitter facing
    facing_deg about +y from +z (0: faces +z, 90: faces +x)."""
    h = seat / 2
    parts = [((cx - h, seat_h - 0.05, cz - h), (cx + h, seat_h, cz + h), seat_mat),
             ((cx - h, seat_h, cz - h), (cx + h, seat_h + back_h, cz - h + 0.05), seat_mat)]
    for sx in (-1, 1):
        for sz in (-1, 1):
            x = cx + sx * (h - 0.03) - leg / 2
            z = cz + sz * (h - 0.03) - leg / 2
            parts.append(((x, 0, z), (x + leg, seat_h - 0.05, z + leg), leg_mat))
    for lo, hi, mat in parts:
        m.box(mat, lo, hi, rot_y=facing_deg, pivot=(cx, cz))


def bookshelf(m, wood, books, x0, z0, x1, z1, height, shelves, rng, along="z"):
    """An open shelf unit against a wall (its back at x0 for along='z'), with books of
    random width, height and colour (from `books`, a list of material names) on each shelf."""
    t = 0.02
    m.box(wood, (x0, 0, z0), (x1, height, z0 + t))
    m.box(wood, (x0, 0, z1 - t), (x1, height, z1))
    m.box(wood, (x0, 0, z0), (x0 + t, height, z1))
    for i in range(shelves + 1):
        y = i * (height - t) / shelves
        m.box(wood, (x0, y, z0), (x1, y + t, z1))
        if i == shelves:
            break
        z = z0 + t + 0.01
        gap = (height - t) / shelves - t
        while True:
            w = rng.uniform(0.025, 0.06)
            if z + w > z1 - t - 0.01:
                break
            bh = gap * rng.uniform(0.6, 0.9)
            mat = books[int(rng.uniform(0, len(books)))]
            m.box(mat, (x0 + t + 0.02, y + t, z), (x1 - 0.02, y + t + bh, z + w))
            z += w + rng.uniform(0.0, 0.01)


# ---------------------------------------------------------------------------------------
# Scenes


def office(out):
    """Ward's Radiance office of the seed, in spirit: a 6 × 2.8 × 5 m office with two desks
    (monitors, keyboards), two chairs, a bookshelf, a filing cabinet and a whiteboard,
    lit by four ceiling panels. Diffuse only."""
    mats = {"floor": (0.25, 0.27, 0.3), "wall": WALL, "ceiling": CEILING, "desk": (0.55, 0.38, 0.22),
            "metal": (0.35, 0.35, 0.37), "chair": (0.15, 0.2, 0.45), "monitor": (0.04, 0.04, 0.045),
            "keyboard": (0.6, 0.6, 0.6), "shelf": (0.5, 0.35, 0.2), "cabinet": (0.45, 0.47, 0.5),
            "whiteboard": (0.85, 0.85, 0.85), "book-red": (0.55, 0.1, 0.08), "book-green": (0.1, 0.35, 0.15),
            "book-blue": (0.1, 0.15, 0.45), "book-cream": (0.75, 0.7, 0.55)}
    m = Mesh("office", mats)
    m.room((0, 0, 0), (6, 2.8, 5), "floor", "wall", "ceiling")
    for x0 in (0.9, 3.4):
        table(m, "desk", "metal", x0, x0 + 1.6, 0.25, 1.05, 0.74)
        m.box("monitor", (x0 + 0.55, 0.74, 0.4), (x0 + 1.05, 1.08, 0.45))       # screen
        m.box("monitor", (x0 + 0.76, 0.74, 0.45), (x0 + 0.84, 0.9, 0.5))        # stand
        m.box("keyboard", (x0 + 0.55, 0.74, 0.62), (x0 + 1.0, 0.76, 0.78))
        chair(m, "chair", "metal", x0 + 0.8, 1.55, 180)
    bookshelf(m, "shelf", ["book-red", "book-green", "book-blue", "book-cream"],
              0.0, 2.2, 0.35, 3.8, 2.0, 5, Lcg(6))
    m.box("cabinet", (5.45, 0, 0.3), (5.95, 1.3, 0.9))
    m.box("whiteboard", (5.97, 0.9, 2.0), (6.0, 2.0, 3.6))
    m.write(out / "standins")
    warm = [9, 8.5, 7.5]
    doc = {"name": "office",
           "stands_in_for": "the seed's Office (Ward's Radiance office): our own diffuse office, 6 x 2.8 x 5 m, "
                            "desks, chairs, a bookshelf, a cabinet and a whiteboard under four ceiling panels",
           "camera": camera((5.5, 1.65, 4.6), (1.8, 0.7, 1.0), 62.0),
           "objects": [{"mesh": "standins/office.obj"}],
           "lights": [ceiling_light(x, 2.798, z, 1.2, 0.6, warm) for z in (1.3, 3.5) for x in (1.7, 4.3)]}
    write(out / "office.json", scene_json(doc))
    fog = fog_of(doc, "office-fog",
                 "the seed's OfficePM: office.json filled with a thin haze (optical depth 0.3 across the room)",
                 medium(0.005, 0.05, 0.3, (0, 0, 0), (6, 2.8, 5)))
    write(out / "office-fog.json", scene_json(fog))


def conference(out):
    """A 10 × 3 × 6 m conference room: a 6 m table, eighteen chairs (seat, back and four
    thin legs each: many small occluders), a screen and a sideboard, under a row of five
    lights over the table."""
    mats = {"floor": (0.4, 0.3, 0.22), "wall": WALL, "ceiling": CEILING, "table": (0.35, 0.22, 0.12),
            "chair": (0.5, 0.1, 0.08), "metal": (0.5, 0.5, 0.52), "screen": (0.8, 0.8, 0.8),
            "sideboard": (0.3, 0.3, 0.32)}
    m = Mesh("conference", mats)
    m.room((0, 0, 0), (10, 3, 6), "floor", "wall", "ceiling")
    table(m, "table", "metal", 2.0, 8.0, 2.25, 3.75, 0.75, legs_x=4, leg=0.08, top=0.05)
    for i in range(8):
        x = 2.4 + i * 0.74
        chair(m, "chair", "metal", x, 1.85, 0)    # south side, facing the table (+z)
        chair(m, "chair", "metal", x, 4.15, 180)  # north side, facing -z
    chair(m, "chair", "metal", 1.55, 3.0, 90)
    chair(m, "chair", "metal", 8.45, 3.0, -90)
    m.box("screen", (9.97, 0.9, 1.8), (10.0, 2.5, 4.2))
    m.box("sideboard", (0.1, 0, 0.1), (1.8, 0.8, 0.6))
    m.write(out / "standins")
    doc = {"name": "conference",
           "stands_in_for": "the seed's Conference (a conference room): our own 10 x 3 x 6 m room, a 6 m table "
                            "and eighteen chairs (many small occluders, dense soft shadows) under a row of five lights",
           "camera": camera((0.5, 1.9, 3.0), (7.0, 0.55, 3.0), 58.0),
           "objects": [{"mesh": "standins/conference.obj"}],
           "lights": [ceiling_light(x, 2.998, 3.0, 0.6, 0.6, [14, 13.5, 12.5]) for x in (3, 4, 5, 6, 7)]}
    write(out / "conference.json", scene_json(doc))


def wall_shelf(m, board, books, x0, x1, y, depth, rng):
    """A board on the back wall (z = 0) from x0 to x1 at height y, with books standing on it
    along x (random width, height and colour from `books`)."""
    m.box(board, (x0, y - 0.02, 0), (x1, y, depth))
    x = x0 + 0.02
    while True:
        w = rng.uniform(0.02, 0.05)
        if x + w > x1 - 0.02:
            break
        mat = books[int(rng.uniform(0, len(books)))]
        m.box(mat, (x, y, 0.01), (x + w, y + rng.uniform(0.15, 0.24), depth - rng.uniform(0.0, 0.04)))
        x += w + rng.uniform(0.0, 0.008)


def desk_objects(m, rng, clutter):
    """Things on the desk top (y = 0.74, x 0.8..2.4, z 0.05..0.8); more with clutter."""
    y = 0.74
    # books: a stack lying flat
    for i, mat in enumerate(["book-red", "book-blue", "book-green"]):
        m.box(mat, (0.95, y + 0.04 * i, 0.12), (1.2 + 0.01 * i, y + 0.04 * (i + 1), 0.42), rot_y=8 * i - 6)
    m.cylinder("mug", (1.35, y, 0.6), 0.04, 0.1, segments=20)            # mug
    m.box("laptop", (1.5, y, 0.3), (1.85, y + 0.02, 0.55))                # laptop base
    m.box("laptop", (1.5, y + 0.02, 0.27), (1.85, y + 0.25, 0.29))        # screen, upright
    m.box("paper", (1.9, y, 0.5), (2.12, y + 0.004, 0.78), rot_y=12)     # sheet of paper
    m.cylinder("pot", (0.95, y, 0.65), 0.06, 0.1, segments=20)           # plant pot
    m.sphere("plant", (0.95, y + 0.17, 0.65), 0.09)
    if clutter:
        for i in range(10):                                             # pens
            x, z = rng.uniform(1.2, 1.45), rng.uniform(0.45, 0.75)
            m.box("pen", (x, y, z), (x + 0.14, y + 0.01, z + 0.01), rot_y=rng.uniform(0, 180))
        for i in range(6):                                              # paper stack
            m.box("paper", (0.88, y + 0.005 * i, 0.06), (1.12, y + 0.005 * i + 0.003, 0.36), rot_y=rng.uniform(-8, 8))
        wall_shelf(m, "desk", ["book-red", "book-blue", "book-green", "paper"], 0.95, 2.3, 1.3, 0.22, rng)
        m.cylinder("mug", (2.25, y, 0.7), 0.035, 0.09, segments=20)


def lamp(m, x, z, head_y, open_face):
    """A desk lamp: a round base at (x, z) on the desk, a post and a shade (a box open on
    `open_face`) at head height; returns the centre of the opening."""
    y = 0.74
    m.cylinder("lamp", (x, y, z), 0.07, 0.02, segments=20)
    m.box("lamp", (x - 0.01, y + 0.02, z - 0.01), (x + 0.01, head_y + 0.06, z + 0.01))
    if open_face == "-y":   # shade over the desk, opening down, the head 0.2 m towards -x
        hx = x - 0.2
        m.box("lamp", (hx, head_y + 0.05, z - 0.01), (x, head_y + 0.07, z + 0.01))
        m.box("lamp", (hx - 0.09, head_y, z - 0.09), (hx + 0.09, head_y + 0.12, z + 0.09), skip=("-y",))
        return (hx, head_y, z)
    # open_face '-z': the shade faces the wall behind the desk
    m.box("lamp", (x - 0.09, head_y - 0.06, z - 0.12), (x + 0.09, head_y + 0.06, z + 0.06), skip=("-z",))
    return (x, head_y, z - 0.12)


def desk_scene(out, name, variant):
    mats = {"floor": (0.45, 0.32, 0.2), "wall": (0.78, 0.76, 0.7), "ceiling": CEILING, "desk": (0.6, 0.45, 0.3),
            "metal": (0.3, 0.3, 0.32), "chair": (0.2, 0.35, 0.25), "book-red": (0.55, 0.1, 0.08),
            "book-blue": (0.1, 0.15, 0.45), "book-green": (0.1, 0.35, 0.15), "mug": (0.8, 0.78, 0.72),
            "laptop": (0.25, 0.25, 0.27), "paper": (0.85, 0.85, 0.82), "pot": (0.6, 0.3, 0.18),
            "plant": (0.12, 0.35, 0.1), "pen": (0.1, 0.1, 0.5), "lamp": (0.65, 0.6, 0.5)}
    m = Mesh(name, mats)
    m.room((0, 0, 0), (3.5, 2.6, 3.0), "floor", "wall", "ceiling")
    table(m, "desk", "metal", 0.8, 2.4, 0.05, 0.8, 0.74)
    lamp_radiance = [60, 50, 35]
    if variant == "desk":
        desk_objects(m, Lcg(1), clutter=False)
        chair(m, "chair", "metal", 1.6, 1.25, 180)
        opening = lamp(m, 2.25, 0.3, 1.15, "-y")
        emitter = light((opening[0], opening[1] + 0.01, opening[2]), (0.14, 0, 0), (0, 0, 0.14), lamp_radiance,
                        (0, -1, 0))
        window = light((0.002, 1.5, 1.4), (0, 1.0, 0), (0, 0, 1.4), [3.0, 3.4, 4.0], (1, 0, 0))
        cam = camera((2.9, 1.55, 2.6), (1.5, 0.8, 0.4), 50.0)
        stands = ("the seed's Desk (a desk with objects under a desk lamp and a window): our own 3.5 x 2.6 x 3 m "
                  "study, a desk with books, a mug, a laptop, paper and a plant, a lamp shining down onto the "
                  "desk and a window-like area light in the left wall")
    else:
        desk_objects(m, Lcg(2), clutter=True)
        chair(m, "chair", "metal", 1.3, 1.2, 160)
        opening = lamp(m, 1.7, 0.55, 1.0, "-z")
        emitter = light((opening[0], opening[1], opening[2] + 0.01), (0, 0.1, 0), (0.16, 0, 0), lamp_radiance,
                        (0, 0, -1))
        window = light((3.498, 1.55, 1.6), (0, 0, 1.2), (0, 0.9, 0), [3.0, 3.4, 4.0], (-1, 0, 0))
        cam = camera((0.5, 1.3, 2.7), (1.6, 0.85, 0.3), 55.0)
        stands = ("the seed's Deskar, of which only the name and the table rows are known (about half the "
                  "frame rate of Desk): our own variant of desk.json, heavier and lit mostly indirectly: more "
                  "and smaller objects (pens, a paper stack, a shelf of books), the lamp turned to face the "
                  "wall behind the desk (a bright bounce), the window in that wall, a camera from the left")
    m.write(out / "standins")
    doc = {"name": name, "stands_in_for": stands, "camera": cam,
           "objects": [{"mesh": f"standins/{name}.obj"}], "lights": [emitter, window]}
    write(out / f"{name}.json", scene_json(doc))


def shirley6(out):
    """A 4 × 2.8 × 4 m room with three boxes under one ceiling light, in the manner of the
    simple box-and-room test scenes in Shirley's Monte Carlo lighting work."""
    mats = {"floor": (0.55, 0.55, 0.55), "wall": (0.7, 0.7, 0.7), "ceiling": (0.7, 0.7, 0.7),
            "box-orange": (0.7, 0.4, 0.15), "box-blue": (0.15, 0.3, 0.6), "box-white": (0.75, 0.75, 0.75)}
    m = Mesh("shirley6", mats)
    m.room((0, 0, 0), (4, 2.8, 4), "floor", "wall", "ceiling")
    m.box("box-white", (1.0, 0, 1.0), (1.6, 1.4, 1.6), rot_y=20)
    m.box("box-orange", (2.3, 0, 1.5), (3.1, 0.8, 2.3), rot_y=-25)
    m.box("box-blue", (1.3, 0, 2.5), (2.4, 0.3, 3.1), rot_y=10)
    m.write(out / "standins")
    doc = {"name": "shirley6",
           "stands_in_for": "the seed's Shirley6 (a simple room test scene with boxes): our own 4 x 2.8 x 4 m "
                            "room, three boxes and one ceiling light",
           "camera": camera((3.7, 2.1, 3.8), (1.7, 0.5, 1.5), 60.0),
           "objects": [{"mesh": "standins/shirley6.obj"}],
           "lights": [ceiling_light(2.0, 2.798, 2.0, 0.7, 0.7, [20, 19, 17])]}
    write(out / "shirley6.json", scene_json(doc))
    fog = fog_of(doc, "shirley6-fog",
                 "the seed's Shirley6PM: shirley6.json filled with a haze (optical depth 0.4 across the room)",
                 medium(0.01, 0.09, 0.3, (0, 0, 0), (4, 2.8, 4)))
    write(out / "shirley6-fog.json", scene_json(fog))


# ---------------------------------------------------------------------------------------
# The subdivided object


def knot_control_mesh(segments=27, sides=4, radius=0.55):
    """A square tube (`sides` corners) around the trefoil knot (sin t + 2 sin 2t,
    cos t - 2 cos 2t, -sin 3t), `segments` rings, oriented by the Frenet frame; each quad
    split into two triangles. Closed, every vertex of valence 6."""
    def r(t):
        return (math.sin(t) + 2 * math.sin(2 * t), math.cos(t) - 2 * math.cos(2 * t), -math.sin(3 * t))

    def d1(t):
        return (math.cos(t) + 4 * math.cos(2 * t), -math.sin(t) + 4 * math.sin(2 * t), -3 * math.cos(3 * t))

    def d2(t):
        return (-math.sin(t) - 8 * math.sin(2 * t), -math.cos(t) + 8 * math.cos(2 * t), 9 * math.sin(3 * t))

    verts, faces = [], []
    for i in range(segments):
        t = 2 * math.pi * i / segments
        tan = normalize(d1(t))
        b = cross(d1(t), d2(t))
        assert dot(b, b) > 1e-3, "Frenet frame degenerate"
        b = normalize(b)
        n = cross(b, tan)
        c = r(t)
        for j in range(sides):
            a = 2 * math.pi * (j + 0.5) / sides
            ca, sa = math.cos(a) * radius, math.sin(a) * radius
            verts.append(tuple(c[k] + ca * n[k] + sa * b[k] for k in range(3)))
    for i in range(segments):
        for j in range(sides):
            a, b = i * sides + j, i * sides + (j + 1) % sides
            c, d = ((i + 1) % segments) * sides + (j + 1) % sides, ((i + 1) % segments) * sides + j
            faces += [(a, b, c), (a, c, d)]
    return verts, faces


def loop_subdivide(verts, faces):
    """One step of Loop subdivision (Loop 1987) of a closed triangle mesh with Warren's
    vertex weights (beta = 3/16 for valence 3, else 3/(8n)): rational weights, so the
    result depends only on IEEE arithmetic. Each triangle becomes four."""
    opposite = {}
    for a, b, c in faces:
        for u, v, w in ((a, b, c), (b, c, a), (c, a, b)):
            opposite.setdefault((u, v) if u < v else (v, u), []).append(w)
    nbrs = [[] for _ in verts]
    for u, v in opposite:
        nbrs[u].append(v)
        nbrs[v].append(u)
    out = []
    for i, p in enumerate(verts):
        n = len(nbrs[i])
        beta = 3.0 / 16.0 if n == 3 else 3.0 / (8.0 * n)
        s = [sum(verts[j][k] for j in nbrs[i]) for k in range(3)]
        out.append(tuple((1.0 - n * beta) * p[k] + beta * s[k] for k in range(3)))
    mid = {}
    for (u, v), opp in opposite.items():
        assert len(opp) == 2, "loop_subdivide needs a closed manifold mesh"
        c, d = opp
        mid[(u, v)] = len(out)
        out.append(tuple(0.375 * (verts[u][k] + verts[v][k]) + 0.125 * (verts[c][k] + verts[d][k]) for k in range(3)))

    def e(u, v):
        return mid[(u, v) if u < v else (v, u)]

    new_faces = []
    for a, b, c in faces:
        ab, bc, ca = e(a, b), e(b, c), e(c, a)
        new_faces += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return out, new_faces


def vertex_normals(verts, faces):
    """Area-weighted average of the face normals at each vertex (a smooth shading normal)."""
    acc = [[0.0, 0.0, 0.0] for _ in verts]
    for f in faces:
        n = cross(sub(verts[f[1]], verts[f[0]]), sub(verts[f[2]], verts[f[0]]))
        for i in f:
            a = acc[i]
            a[0] += n[0]
            a[1] += n[1]
            a[2] += n[2]
    return [normalize(a) for a in acc]


KNOT_LEVELS = 5  # 27 × 4 × 2 = 216 control triangles × 4^5 = 221,184 triangles


def knot_mesh_text(scale, offset):
    verts, faces = knot_control_mesh()
    for _ in range(KNOT_LEVELS):
        verts, faces = loop_subdivide(verts, faces)
    verts = [tuple(offset[k] + scale * p[k] for k in range(3)) for p in verts]
    normals = vertex_normals(verts, faces)
    out = ["# subdivided-knot: a trefoil tube after " + str(KNOT_LEVELS) + " Loop subdivision steps, "
           f"{len(faces)} triangles; written by scenes/generate/standins.py (do not edit by hand)",
           "mtllib subdivided-knot.mtl"]
    out += [f"v {num(x)} {num(y)} {num(z)}" for x, y, z in verts]
    out += [f"vn {num(x, 4)} {num(y, 4)} {num(z, 4)}" for x, y, z in normals]
    out.append("usemtl knot")
    out += [f"f {a + 1}//{a + 1} {b + 1}//{b + 1} {c + 1}//{c + 1}" for a, b, c in faces]
    return "\n".join(out) + "\n"


# Scaled by 0.2 the subdivided knot spans x ±0.604, y −0.656..0.471, z ±0.255 (about 1.2 m
# across, 0.51 m high); the JSON turns its z to the room's y and lifts it by 0.856 so it
# rests on the 0.6 m pedestal (1 mm above it).
KNOT_SCALE = 0.2


def subdivided_large(out):
    write(out / "generated" / "subdivided-knot.obj", knot_mesh_text(KNOT_SCALE, (0, 0, 0)))
    write(out / "generated" / "subdivided-knot.mtl", mtl_text("subdivided-knot", {"knot": (0.7, 0.62, 0.45)}))


def subdivided_small(out):
    """A 5 × 3 × 5 m room with a pedestal; the knot (generated/, written at build time)
    rests on it, rotated so the knot's z axis points up."""
    mats = {"floor": (0.5, 0.5, 0.5), "wall": (0.6, 0.65, 0.75), "ceiling": CEILING, "pedestal": (0.7, 0.7, 0.7)}
    m = Mesh("subdivided-room", mats)
    m.room((0, 0, 0), (5, 3, 5), "floor", "wall", "ceiling")
    m.box("pedestal", (2.1, 0, 2.1), (2.9, 0.6, 2.9))
    m.write(out / "standins")
    doc = {"name": "subdivided",
           "stands_in_for": "the seed's Subdivided (a room holding a high-polygon subdivision surface): our own "
                            "5 x 3 x 5 m room with a pedestal holding a Loop-subdivided trefoil knot of 221,184 "
                            "triangles (generated at build time into scenes/generated/), one ceiling light",
           "camera": camera((4.4, 1.9, 4.6), (2.5, 0.85, 2.5), 50.0),
           "objects": [{"mesh": "standins/subdivided-room.obj"},
                       {"mesh": "generated/subdivided-knot.obj",
                        "transform": {"rotate": [{"axis": [1, 0, 0], "degrees": -90}], "translate": [2.5, 0.856, 2.5]}}],
           "lights": [ceiling_light(2.5, 2.998, 2.5, 1.0, 1.0, [12, 11.5, 10.5])]}
    write(out / "subdivided.json", scene_json(doc))
    fog = fog_of(doc, "subdivided-fog",
                 "the seed's SubdividedPM: subdivided.json filled with a haze (optical depth 0.4 across the room)",
                 medium(0.008, 0.072, 0.3, (0, 0, 0), (5, 3, 5)))
    write(out / "subdivided-fog.json", scene_json(fog))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(SCENES), help="output folder (default: %(default)s)")
    ap.add_argument("--what", choices=("small", "large", "all"), default="small")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    if args.what in ("small", "all"):
        office(out)
        conference(out)
        desk_scene(out, "desk", "desk")
        desk_scene(out, "deskar", "deskar")
        subdivided_small(out)
        shirley6(out)
    if args.what in ("large", "all"):
        subdivided_large(out)


if __name__ == "__main__":
    main()
