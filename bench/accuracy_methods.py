"""The methods the accuracy sweep (bench/accuracy) knows, one table entry each.

A method is its `tessera render --method` name plus a grid of quality settings: each grid
key is a `tessera render` option without the leading `--`, each value a list to sweep. The
key `spp` is special: it is the number of passes accumulated into one image. The time
charged to an image is spp x the median time of one pass (a pass of a progressive method
is one frame); every other key changes the cost of a pass, so the sweep times each
combination of the other keys once, over several passes.

`operating` is the setting quoted in the report's fps and FLIP tables (Tables 5.1 and 5.3
of the seed thesis); `converges_to_reference` is False for a method whose limit is not the
pt reference (its error floors). Adding a method (igi, ais, ais-max, ic, tic) is one entry;
`method` is the `--method` it renders with where the entry's name is a variant (ais-old:
ais with the defaults before the clamp decay; ais-uniform: before VPLs for the view;
ais-noedge: without edge samples; ais-nocomp: without the clamp compensation;
ais-pointvpl: the march's medium VPLs instead of ray lights; so one sweep shows old against
new).
"""
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Method:
    name: str
    grid: dict
    operating: dict
    converges_to_reference: bool = True
    note: str = ""
    extra_args: tuple = field(default_factory=tuple)
    method: str = ""  # `tessera render --method`; empty: the entry's name

    @property
    def render_method(self):
        return self.method or self.name


METHODS = {
    "pt": Method(
        "pt", {"spp": [1, 2, 4, 8, 16, 32, 64, 128]}, {"spp": 1},
        note="volumetric path tracing; the reference method (error -> 0 as spp grows)"),
    "direct": Method(
        "direct", {"spp": [1, 4, 16, 64], "shadow-samples": [1, 4, 16]}, {"spp": 1, "shadow-samples": 4},
        converges_to_reference=False,
        note="direct light only: no indirect light, so its error against the pt reference floors"),
    "igi": Method(
        "igi", {"spp": [1, 2, 4, 8, 16], "tile": [1, 2, 3, 4, 5, 8], "vpl-paths": [8, 32, 128],
                "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        note="instant global illumination; the VPL geometry term is clamped (c = 0.1) and the clamp "
             "loosens over passes (--clamp-decay 0.25, docs/igi.md section 4), so accumulated passes converge "
             "to the pt reference, slowly (a fixed clamp floored: ais-old); "
             "in media it gathers VPLs left by light paths that scatter in the medium (multiple scattering; --single-scattering: pt --max-scatter 1)"),
    "ais": Method(
        "ais", {"spp": [1, 2, 4, 8], "tile": [3, 5, 8], "vpl-paths": [8, 32], "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        note="adaptive interleaved sampling, mode A (graded extra sets where guidance flags); same clamp as igi"),
    "ais-old": Method(
        "ais-old", {"spp": [1, 2, 4, 8], "tile": [3, 5, 8], "vpl-paths": [8, 32], "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        converges_to_reference=False, method="ais", extra_args=("--clamp", "0.05", "--clamp-decay", "0"),
        note="ais with the old defaults (clamp c = 0.05, fixed over passes): its error floors at the clamp's bias"),
    "ais-nocomp": Method(
        "ais-nocomp", {"spp": [1, 2, 4, 8], "tile": [3, 5, 8], "vpl-paths": [8, 32], "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        method="ais", extra_args=("--no-clamp-compensation",),
        note="ais without the clamp's screen-space compensation (docs/igi.md section 4): the clamped estimate alone"),
    "ais-pointvpl": Method(
        "ais-pointvpl", {"spp": [1, 2, 4, 8], "tile": [3, 5, 8], "vpl-paths": [8, 32], "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        method="ais", extra_args=("--point-medium-vpls",),
        note="ais whose ray march gathers the medium VPLs (clamped) instead of virtual ray lights (docs/igi.md "
             "section 6); the same images without a medium"),
    "ais-uniform": Method(
        "ais-uniform", {"spp": [1, 2, 4, 8], "tile": [3, 5, 8], "vpl-paths": [8, 32], "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        method="ais", extra_args=("--vpl-importance", "1"),
        note="ais with every VPL of M paths per set, as before VPLs for the view (docs/igi.md section 3b)"),
    "ais-noedge": Method(
        "ais-noedge", {"spp": [1, 2, 4, 8], "tile": [3, 5, 8], "vpl-paths": [8, 32], "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        method="ais", extra_args=("--components", "ss,id,pm"),
        note="ais without its edge samples (docs/ais.md section 9): one camera sample per pixel and pass"),
    "ais-max": Method(
        "ais-max", {"spp": [1, 2, 4, 8], "tile": [3, 5, 8], "vpl-paths": [8, 32], "shadow-samples": [1, 4]},
        {"spp": 1, "tile": 3, "vpl-paths": 32, "shadow-samples": 4},
        note="adaptive interleaved sampling, mode A-MAX (all sets for every flagged pixel)"),
    "ic": Method(
        "ic", {"spp": [1, 2, 4], "ic-paths": [64, 256, 1024], "ic-error": [0.1, 0.3, 0.5], "shadow-samples": [1, 4]},
        {"spp": 1, "ic-paths": 256, "ic-error": 0.3, "shadow-samples": 4},
        note="instant caching: igi's direct light and media, indirect light from an irradiance cache rebuilt "
             "each pass from --ic-paths light paths (one set); same clamp and decay as igi"),
    "tic": Method(
        "tic", {"spp": [1, 2, 4], "ic-paths": [64, 256, 1024], "ic-error": [0.3], "shadow-samples": [1, 4]},
        {"spp": 1, "ic-paths": 256, "ic-error": 0.3, "shadow-samples": 4},
        converges_to_reference=False,
        note="temporal instant caching on a still frame: the cache persists over the passes (one VPL set, "
             "records added where new camera jitter needs them, a fixed clamp), so passes after the first cost little; "
             "its frame-to-frame cost over animations is in ic_bench"),
}


def parse_grid_override(text):
    """'pt:spp=1,4,16' -> ('pt', 'spp', [1, 4, 16]); values are ints where they parse, else floats."""
    try:
        method, rest = text.split(":", 1)
        key, values = rest.split("=", 1)
        vals = [int(v) if v.strip().lstrip("-").isdigit() else float(v) for v in values.split(",") if v.strip()]
    except ValueError:
        raise ValueError(f"--grid {text!r}: expected METHOD:OPTION=v1,v2,...") from None
    if not vals:
        raise ValueError(f"--grid {text!r}: no values")
    return method, key, vals
