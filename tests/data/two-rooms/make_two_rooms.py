#!/usr/bin/env python3
"""Writes two-rooms.{obj,mtl}: a scene for the instant cache's tests in which one room is
lit only indirectly. Two 4 x 2.5 x 4 m rooms side by side (x 0..4 and 4.1..8.1) share a
10 cm partition with a 0.9 x 2 m doorway (z 1.55..2.45); the only light hangs in the
far room (two-rooms.json), so the near room, where the camera stands, receives light
only through the doorway. The side walls, floor and ceiling run through both rooms, the
case where a cache record on one side of the partition could serve the other.
Deterministic; uses the mesh writer of scenes/generate/standins.py."""
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[2] / "scenes" / "generate"))
import standins  # noqa: E402

mesh = standins.Mesh("two-rooms", {"white": (0.75, 0.75, 0.72), "floor": (0.6, 0.55, 0.5),
                                   "blue": (0.3, 0.4, 0.7), "red": (0.7, 0.25, 0.2)})
mesh.room((0, 0, 0), (8.1, 2.5, 4), "floor", "white", "white")
# The partition: two wall pieces beside the doorway and a lintel above it.
mesh.box("blue", (4.0, 0, 0), (4.1, 2.5, 1.55), skip=("-z",))
mesh.box("blue", (4.0, 0, 2.45), (4.1, 2.5, 4.0), skip=("+z",))
mesh.box("blue", (4.0, 2.0, 1.55), (4.1, 2.5, 2.45))
# A block in the near room, lit only by bounced light.
mesh.box("red", (6.2, 0, 2.6), (6.9, 0.8, 3.3), rot_y=20)
text = mesh.obj_text().replace("scenes/generate/standins.py", "tests/data/two-rooms/make_two_rooms.py")
standins.write(HERE / "two-rooms.obj", text)
standins.write(HERE / "two-rooms.mtl", standins.mtl_text("two-rooms", mesh.materials).replace(
    "scenes/generate/standins.py", "tests/data/two-rooms/make_two_rooms.py"))
