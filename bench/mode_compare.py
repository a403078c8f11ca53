"""One AIS frame in two modes, both backends: the shared part of bench/march_compare.py and
bench/edge_compare.py.

For each scene: one frame of `ais` at the `ais_bench` settings (tile 3, 32 VPL paths per set,
4 light samples, 8 march steps, one pass) in each mode (extra `tessera render` arguments), on
Embree and OpenCL, seeds 1-3. Per mode and backend: the frame time (median over the seeds,
from --stats-json: set-up excluded), relMSE and HDR-FLIP (`tessera compare`) and HDR-VDP-3
(bench/hdrvdp_metric.py, the protocol of ../shared/tools/README.md; skipped with a note when
Octave is missing): medians over the seeds, with the ratio first mode / second mode. Beside
them, the reference's own noise: `pt` at --floor-spp with seed 2 against it.

The reference: --reference DIR/<scene>.exr if there, else `pt` on Embree at --reference-spp
(SCENE=N items per scene) with seed 7919, written to DIR (reused when it exists; give the spp
it was made with, which the table names).
"""
import argparse
import datetime
import json
import platform
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import hdrvdp_metric

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT.parent / "shared" / "scenes"
AIS_BENCH = ["--method", "ais", "--spp", "1", "--tile", "3", "--vpl-paths", "32", "--shadow-samples", "4",
             "--march-steps", "8"]
BACKENDS = ("embree", "opencl")
SEEDS = (1, 2, 3)


def render(binary, scene, args, size, out, key="seconds"):
    cmd = [binary, "render", str(scene), "--data-dir", str(DATA), "--width", str(size[0]), "--height",
           str(size[1]), "--out", str(out), "--stats-json", str(out.with_suffix(".json"))] + args
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    return json.loads(out.with_suffix(".json").read_text())[key]


def compare(binary, ref, test):
    r = subprocess.run([binary, "compare", str(ref), str(test), "--json"], check=True, capture_output=True, text=True)
    d = json.loads(r.stdout)
    out = {"relmse": d["relmse"]}
    if "mean" in d["flip"]:  # without flip-evaluator compare reports {"unavailable": why}: a "—" cell
        out.update(flip_gt_0_1=d["flip"]["p_gt_0_1"], flip_mean=d["flip"]["mean"])
    return out


def hdrvdp(pairs, tool):
    """HDR-VDP-3 of each (ref, test) pair, or None (with the reason on stderr) without Octave."""
    try:
        return hdrvdp_metric.compare_files([str(p) for pair in pairs for p in pair])
    except hdrvdp_metric.Missing as e:
        print(f"{tool}: no HDR-VDP-3: {e}", file=sys.stderr)
        return None


class Comparison:
    """scenes: {name: scene file}; modes: {mode: extra render arguments}, the ratio taken as
    first / second; title and about: the report's heading and the sentence naming the modes."""

    def __init__(self, tool, scenes, modes, title, about, default_spp):
        self.tool, self.scenes, self.modes = tool, scenes, modes
        self.title, self.about, self.default_spp = title, about, default_spp

    def reference_spp(self, args, name):
        return args.reference_spp.get(name, args.reference_spp.get("", self.default_spp))

    def reference(self, binary, name, size, args):
        path = Path(args.reference) / f"{name}.exr"
        if not path.exists():
            path.parent.mkdir(parents=True, exist_ok=True)
            render(binary, self.scenes[name], ["--method", "pt", "--spp", str(self.reference_spp(args, name)),
                                               "--seed", "7919", "--backend", "embree"], size, path)
        return path

    def measure(self, binary, name, size, args, tmp):
        scene = self.scenes[name]
        ref = self.reference(binary, name, size, args)
        runs = []
        for mode, extra in self.modes.items():
            for backend in BACKENDS:
                for seed in SEEDS:
                    out = tmp / f"{name}-{mode}-{backend}-{seed}.exr"
                    t = render(binary, scene, AIS_BENCH + extra + ["--backend", backend, "--seed", str(seed)], size,
                               out)
                    runs.append({"mode": mode, "backend": backend, "seed": seed, "seconds": t, "exr": out,
                                 **compare(binary, ref, out)})
        # Pass times: --time-passes passes per render (their median, --stats-json), three
        # rounds with the modes and backends alternating, so that a slow spell of a shared
        # machine hits every mode alike.
        for _ in range(3 if args.time_passes else 0):
            for mode, extra in self.modes.items():
                for backend in BACKENDS:
                    out = tmp / f"{name}-timing.exr"
                    args_t = AIS_BENCH + extra + ["--backend", backend, "--seed", "1"]
                    args_t[args_t.index("--spp") + 1] = str(args.time_passes)
                    t = render(binary, scene, args_t, size, out, "median_pass_seconds")
                    runs.append({"mode": mode, "backend": backend, "pass_seconds": t})
        floor = None
        if args.floor_spp:
            out = tmp / f"{name}-floor.exr"
            render(binary, scene, ["--method", "pt", "--spp", str(args.floor_spp), "--seed", "2", "--backend",
                                   "embree"], size, out)
            floor = {"spp": args.floor_spp, "exr": out, **compare(binary, ref, out)}
        images = [r for r in runs if "exr" in r] + ([floor] if floor else [])
        vdp = hdrvdp([(ref, r["exr"]) for r in images], self.tool)
        if vdp:
            for r, v in zip(images, vdp):
                r.update({"p_ge_75": v["p_ge_75"], "p_ge_95": v["p_ge_95"], "q_jod": v["q_jod"]})
        for r in images:
            del r["exr"]
        return {"scene": name, "reference": str(ref), "reference_spp": self.reference_spp(args, name), "runs": runs,
                "floor": floor}

    def markdown(self, results, size, machine):
        first, second = list(self.modes)[:2]
        lines = [f"# {self.title}", "",
                 f"Machine: {machine}. {size[0]}x{size[1]}, `ais` at the `ais_bench` settings (tile 3, 32 VPL paths "
                 "per set, 4 light samples, 8 march steps), one pass, seeds 1-3: medians over the seeds. "
                 f"{self.about} Time: the one-pass frame's seconds from `--stats-json` (set-up excluded); pass "
                 "time: the median pass of a render of --time-passes passes (seed 1), median of three rounds with "
                 "the modes and backends alternating. HDR-VDP-3: % of pixels with P >= 75% / >= 95% and Q_JOD "
                 "(bench/hdrvdp_metric.py, the protocol of ../shared/tools/README.md). Generated by "
                 f"`bench/{self.tool}.py`.", "",
                 "| scene | backend | mode | time (s) | pass time (s) | relMSE | FLIP > 0.1 (mean) | HDR-VDP-3 P≥75 / "
                 "P≥95 | Q_JOD |",
                 "|---|---|---|---|---|---|---|---|---|"]
        for res in results:
            for backend in BACKENDS:
                for mode in self.modes:
                    g = lambda k: median(res["runs"], mode, backend, k)  # noqa: E731
                    lines.append(f"| {res['scene']} | {backend} | {mode} | {fmt(g('seconds'), '.3f')} | "
                                 f"{fmt(g('pass_seconds'), '.3f')} | "
                                 f"{fmt(g('relmse'), '.5f')} | {fmt(g('flip_gt_0_1'), '.2f')}% "
                                 f"({fmt(g('flip_mean'), '.4f')}) | {fmt(g('p_ge_75'), '.2f')}% / "
                                 f"{fmt(g('p_ge_95'), '.2f')}% | {fmt(g('q_jod'), '.3f')} |")
                keys = ("seconds", "pass_seconds", "relmse", "p_ge_75")
                a = {k: median(res["runs"], first, backend, k) for k in keys}
                b = {k: median(res["runs"], second, backend, k) for k in keys}
                ratio = lambda k: fmt(a[k] / b[k] if a[k] is not None and b[k] else None, ".3f")  # noqa: E731
                lines.append(f"| {res['scene']} | {backend} | {first} / {second} | {ratio('seconds')} | "
                             f"{ratio('pass_seconds')} | {ratio('relmse')} | | {ratio('p_ge_75')} (P≥75) | |")
        lines += ["", "Reference noise (`pt` at the floor's spp, seed 2, against the reference; a reference of k x "
                  "more spp has 1/sqrt(k) of that noise):", "",
                  "| scene | reference | floor | relMSE | FLIP > 0.1 | HDR-VDP-3 P≥75 / P≥95 |", "|---|---|---|---|---|---|"]
        for res in results:
            f = res["floor"]
            if f:
                lines.append(f"| {res['scene']} | pt {res['reference_spp']} spp | pt {f['spp']} spp | "
                             f"{f['relmse']:.5f} | {fmt(f.get('flip_gt_0_1'), '.2f')}% | {fmt(f.get('p_ge_75'), '.2f')}% / "
                             f"{fmt(f.get('p_ge_95'), '.2f')}% |")
        return "\n".join(lines) + "\n"

    def main(self, doc, default_out):
        ap = argparse.ArgumentParser(description=doc.splitlines()[0])
        ap.add_argument("--tessera", default=str(ROOT / "build/tessera"))
        ap.add_argument("--size", type=int, nargs=2, default=(256, 256))
        ap.add_argument("--reference", default=str(ROOT / "out/references"), help="folder of <scene>.exr references")
        ap.add_argument("--reference-spp", nargs="*", default=[str(self.default_spp)],
                        help="spp of the references rendered (and named in the table): N and/or SCENE=N items")
        ap.add_argument("--floor-spp", type=int, default=256, help="spp of the reference-noise render (0: none)")
        ap.add_argument("--time-passes", type=int, default=4, help="passes of each pass-time render (0: none)")
        ap.add_argument("--scenes", nargs="*", default=list(self.scenes))
        ap.add_argument("--machine", default=f"{platform.node()} ({platform.processor() or platform.machine()})")
        ap.add_argument("--out", default=str(ROOT / default_out))
        args = ap.parse_args()
        spp = {}
        for item in args.reference_spp:
            name, _, n = item.rpartition("=")
            if not n.isdigit() or int(n) < 1 or (name and name not in self.scenes):
                ap.error(f"--reference-spp {item}: expected N or SCENE=N with N >= 1 and SCENE one of "
                         f"{', '.join(self.scenes)}")
            spp[name] = int(n)
        args.reference_spp = spp
        unknown = [s for s in args.scenes if s not in self.scenes]
        if unknown:
            ap.error(f"--scenes {unknown[0]}: not one of {', '.join(self.scenes)}")
        with tempfile.TemporaryDirectory(prefix=f"{self.tool}-") as tmp:
            results = [self.measure(args.tessera, s, args.size, args, Path(tmp)) for s in args.scenes]
        out = Path(args.out)
        machine = f"{args.machine}, {datetime.date.today().isoformat()}"
        out.write_text(self.markdown(results, args.size, machine))
        out.with_suffix(".json").write_text(json.dumps({"machine": machine, "size": list(args.size),
                                                        "modes": self.modes, "results": results}, indent=1) + "\n")
        print(out)
        return 0


def median(runs, mode, backend, key):
    vals = [r[key] for r in runs if r["mode"] == mode and r["backend"] == backend and key in r]
    return statistics.median(vals) if vals else None


def fmt(v, spec):
    return "—" if v is None else format(v, spec)
