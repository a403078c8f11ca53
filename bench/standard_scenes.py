"""The standard scenes of the seed-style tables, in the rows of the seed thesis's Tables
5.1-5.3: Cornell, Deskar, Subdivided, Desk, Sibenik, Office, Conference, Shirley6, then the
PM versions of Subdivided, Office and Shirley6 (stand-ins: scenes/README.md). Same list as
bench::standard_scenes() in bench/igi_timing.h, which the C++ benchmarks read."""
from pathlib import Path

STANDARD_SCENES = ["cornell-box", "deskar", "subdivided", "desk", "sibenik", "office", "conference", "shirley6",
                   "subdivided-fog", "office-fog", "shirley6-fog"]


def standard_scene_paths(root):
    """The scene files under <root>/scenes, in row order."""
    return [str(Path(root) / "scenes" / f"{n}.json") for n in STANDARD_SCENES]


def row_order(name):
    """Sort key: the standard scenes in the seed's row order, then any other by name."""
    return (STANDARD_SCENES.index(name), "") if name in STANDARD_SCENES else (len(STANDARD_SCENES), name)
