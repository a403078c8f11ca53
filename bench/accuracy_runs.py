"""Provenance of an accuracy results file (bench/accuracy writes it, bench/accuracy_report
prints it): the runs its rows come from.

`bench/accuracy --merge` keeps the rows of the methods it does not sweep from the earlier
<scene>.json, so one file can hold rows measured on different dates, machines and loads.
Its "runs" list says which: one entry per run, newest first, each {date, machine, cores,
load_average_1min: [before, after], frames_timed, methods, backends}, the methods and
backends being those the file still holds rows of from that run.
"""
import re


def unique(values):
    """values without repeats, in first-seen order."""
    return list(dict.fromkeys(values))


def cores_in(machine):
    """The core count that bench/accuracy's default machine note starts with ('2-core AMD
    EPYC'), or None (a --machine text in another form)."""
    m = re.match(r"(\d+)-core\b", machine or "")
    return int(m.group(1)) if m else None


def runs_of(doc):
    """The runs of a results file: its "runs", or for a file written before they were
    recorded, one run from its header (which a --merge may have made wrong: nothing in
    such a file says so)."""
    if "runs" in doc:
        return doc["runs"]
    return [{"date": doc.get("date"), "machine": doc.get("machine"), "cores": cores_in(doc.get("machine")),
             "load_average_1min": doc.get("reference", {}).get("load_average_1min"),
             "frames_timed": doc.get("frames_timed"),
             "methods": unique(r["method"] for r in doc["rows"]),
             "backends": unique(r["backend"] for r in doc["rows"])}]


def runs_with(runs, rows):
    """The runs that produced `rows`, each narrowed to the methods and backends it has rows
    of there (a --merge keeps only some methods of an earlier run)."""
    out = []
    for run in runs:
        mine = [r for r in rows if r["method"] in run["methods"]]
        if mine:
            out.append({**run, "methods": unique(r["method"] for r in mine),
                        "backends": unique(r["backend"] for r in mine)})
    return out
