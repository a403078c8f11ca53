#!/usr/bin/env python3
"""Writes the seed corpus of the scene-loader fuzzer (tests/fuzz/corpus/) from the
scene fixtures in tests/data and the shipped Cornell box scenes: each seed is the JSON,
the OBJ, the MTL and the texture a scene names, joined by lines "@@@@" (the format
scene_loader_fuzzer.cpp reads), with the file names rewritten to mesh.obj, mesh.mtl and
tex.png. Run from anywhere; it replaces the corpus's seed-* files."""
import json
import pathlib
import re

root = pathlib.Path(__file__).resolve().parents[2]
data = root / "tests" / "data"
out = root / "tests" / "fuzz" / "corpus"
SEP = b"\n@@@@\n"


def read(p):
    return p.read_bytes() if p.is_file() else None


def seed_for(scene_path):
    text = scene_path.read_text()
    try:
        doc = json.loads(text)
    except json.JSONDecodeError:
        return text.encode()  # a malformed fixture is a seed as it is
    obj_name = None
    for o in doc.get("objects", []) if isinstance(doc, dict) else []:
        if isinstance(o, dict) and isinstance(o.get("mesh"), str):
            obj_name = obj_name or o["mesh"]
            o["mesh"] = "mesh.obj"
    parts = [json.dumps(doc).encode()]
    obj = read(scene_path.parent / obj_name) if obj_name else None
    if obj is None:
        return parts[0]
    mtl_name = re.search(rb"^mtllib\s+(\S+)", obj, re.M)
    obj = re.sub(rb"^mtllib\s+\S+", b"mtllib mesh.mtl", obj, flags=re.M)
    parts.append(obj)
    mtl = read(scene_path.parent / mtl_name.group(1).decode()) if mtl_name else None
    if mtl is None:
        return SEP.join(parts)
    tex_name = re.search(rb"map_Kd\s+(\S+)", mtl)
    parts.append(re.sub(rb"map_Kd\s+\S+", b"map_Kd tex.png", mtl))
    tex = read(scene_path.parent / tex_name.group(1).decode()) if tex_name else None
    if tex is not None:
        parts.append(tex)
    return SEP.join(parts)


out.mkdir(parents=True, exist_ok=True)
for old in out.glob("seed-*"):
    old.unlink()
for scene in sorted(data.glob("*.json")):
    (out / f"seed-{scene.stem}").write_bytes(seed_for(scene))
# A medium block, from the shipped fog scene, on the quad fixture.
fog = json.loads((root / "scenes" / "cornell-box-fog.json").read_text())["medium"]
doc = json.loads((data / "light.json").read_text())
doc["objects"][0]["mesh"] = "mesh.obj"
doc["medium"] = fog
doc["medium"]["box"] = {"min": [-1, -1, -1], "max": [2, 3, 2]}
(out / "seed-medium").write_bytes(SEP.join([json.dumps(doc).encode(), read(data / "quad.obj").replace(b"quad.mtl", b"mesh.mtl"), read(data / "quad.mtl")]))
print(f"wrote {len(list(out.glob('seed-*')))} seeds to {out}")
