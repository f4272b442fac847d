#!/usr/bin/env python3
"""Rerun the evaluation and replace the generated tables of docs/evaluation.md.

Usage:
  python3 scripts/update_evaluation.py [--evaluate build/bench/xparam_evaluate]
      [--bench build/bench/xparam_bench] [--data DIR] [--doc docs/evaluation.md] [--keep-output DIR]
  python3 scripts/update_evaluation.py --from-output TABLE REALISTIC PAPER BENCH_JSON [--doc ...]

Three runs of `xparam_evaluate` (bench/evaluate/evaluate_pairs.cpp): the table set under every
configuration (the paper's Table 1 columns and ours), and the realistic set under the default and
under the paper's map ("Balanced + merging, no relaxation": no relaxation of the patch maps, no map
optimization); then every benchmark of `xparam_bench` (bench/), its JSON output. The printed rows
are turned into tables, each written between the markers
<!-- BEGIN generated: NAME --> and <!-- END generated: NAME --> of the document; nothing outside
the markers changes. The document is written only when every block's markers are there and the
runs mapped at least one pair; otherwise it is left as it was and the problem is named.

--from-output makes the tables from the saved output of those four runs instead of running them
(--keep-output DIR saves it: table.txt, realistic.txt, realistic_paper.txt, bench.json).
"""

import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys

DEFAULT = "Balanced + merging"
PAPER_MAP = "Balanced + merging, no relaxation"
HEADER = re.compile(r"^(?P<name>.+): (?P<anchors>\d+) anchors, \d+ / \d+ vertices, floor [0-9.]+ s")
BLOCKS = ("stamp", "table1", "table1_folds_truth", "table1_default", "realistic", "hands_feet", "summary",
          "benchmarks")
# The keys of a Google Benchmark JSON run that are not the benchmark's own counters.
BENCHMARK_KEYS = {"name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
                  "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit",
                  "aggregate_name", "aggregate_unit", "error_occurred", "error_message", "label"}


class Pair:
    """One pair of an evaluation run: its name, its anchors and its row per configuration."""

    def __init__(self, name, anchors):
        self.name = name
        self.anchors = anchors
        self.rows = {}  # configuration -> {column: text}, or a failure message (str)


def parse(text):
    """The pairs of one run of xparam_evaluate, in order, and its summary lines."""
    pairs, summary, columns, pair = [], [], None, None
    in_summary = False
    for line in text.splitlines():
        header = HEADER.match(line)
        if header:
            pair = Pair(header["name"], int(header["anchors"]))
            pairs.append(pair)
            continue
        if line.startswith("Summary over the pairs run"):
            in_summary = True
            continue
        if in_summary:
            if line.startswith("- "):
                summary.append(line[2:])
            continue
        if not line.startswith("| ") or pair is None:
            continue
        cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
        if cells[0] == "configuration":
            columns = cells
        elif len(cells) == 2 and cells[1].startswith("failed"):
            pair.rows[cells[0]] = cells[1]
        elif columns and len(cells) == len(columns):
            pair.rows[cells[0]] = dict(zip(columns, cells))
    return pairs, summary


def configurations_of(pairs):
    """The configurations run, in the order they were printed."""
    seen = []
    for pair in pairs:
        for name in pair.rows:
            if name not in seen:
                seen.append(name)
    return seen


def table(head, rows):
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def cell(pair, configuration, render):
    row = pair.rows.get(configuration)
    if row is None:
        return "not run"
    if isinstance(row, str):
        return row
    return render(row)


def short(value):
    """A distortion figure to three decimals, fewer as it grows (E_L2 of a tangled map runs to
    thousands)."""
    try:
        number = float(value)
    except ValueError:
        return value
    if number < 10:
        return f"{number:.3f}"
    return f"{number:.1f}" if number < 1000 else f"{number:.0f}"


def table1(pairs):
    configurations = configurations_of(pairs)
    rows = [[f"{p.name} ({p.anchors})"] +
            [cell(p, c, lambda r: f"{short(r['E_L2'])} / {short(r['E_ang'])}") for c in configurations]
            for p in pairs]
    return table(["pair (anchors)"] + configurations, rows)


def table1_folds_truth(pairs):
    configurations = configurations_of(pairs)
    rows = [[p.name] + [cell(p, c, lambda r: f"{r['strict']} / {r['gt error % sqrt(A)']}") for c in configurations]
            for p in pairs]
    return table(["pair"] + configurations, rows)


# The columns of the default's row per pair: (the table's heading, the program's column).
DEFAULT_COLUMNS = [("E_L2", "E_L2"), ("E_ang", "E_ang"), ("flipped", "flipped"), ("strict", "strict"),
                   ("area ratio", "area ratio"), ("gt % √A", "gt error % sqrt(A)"), ("swaps", "swaps"),
                   ("merges", "merges"), ("optimize s", "optimize s"), ("optimize map s", "optimize map s"),
                   ("total s", "total s"), ("floor x", "floor x"), ("worse hand", "worse hand gt % sqrt(A)"),
                   ("worse foot", "worse foot gt % sqrt(A)")]


def table1_default(pairs):
    rows = []
    for p in pairs:
        row = p.rows.get(DEFAULT)
        if isinstance(row, dict):
            rows.append([p.name] + [row[key] for _, key in DEFAULT_COLUMNS])
        else:
            rows.append([p.name, row or "not run"] + [""] * (len(DEFAULT_COLUMNS) - 1))
    return table(["pair"] + [heading for heading, _ in DEFAULT_COLUMNS], rows)


def compact(row):
    """E_L2 / flipped / strict / area ratio / ground truth % sqrt(A) / seconds."""
    return " / ".join([short(row["E_L2"]), row["flipped"], row["strict"], row["area ratio"],
                       row["gt error % sqrt(A)"], row["total s"]])


def realistic(default_pairs, paper_pairs):
    paper = {p.name: p for p in paper_pairs}
    rows = []
    for p in default_pairs:
        other = paper.get(p.name)
        rows.append([p.name, cell(p, DEFAULT, compact), cell(p, DEFAULT, lambda r: r["floor x"]),
                     cell(other, PAPER_MAP, compact) if other else "not run"])
    return table(["pair [landmarks]", "the default", "floor x", "the paper's map"], rows)


def hands_feet(pairs):
    """The worse hand and foot of each pair whose default map has them (an SMPL template with a truth)."""
    def measured(pair):
        row = pair.rows.get(DEFAULT)
        return isinstance(row, dict) and row["worse hand gt % sqrt(A)"] != "-"

    rows = [[p.name, p.rows[DEFAULT]["worse hand gt % sqrt(A)"], p.rows[DEFAULT]["worse foot gt % sqrt(A)"]]
            for p in pairs if measured(p)]
    return table(["pair [landmarks]", "worse hand, gt % √A", "worse foot, gt % √A"], rows)


def summary(runs):
    parts = []
    for title, lines_of_run in runs:
        parts.append(f"{title}:\n\n" + "\n".join(f"- {line}" for line in lines_of_run))
    return "\n\n".join(parts)


def benchmarks(report):
    """One row per benchmark of a Google Benchmark JSON report: its wall time and its counters."""
    rows = []
    for run in report.get("benchmarks", []):
        if run.get("error_occurred"):
            rows.append([f"`{run['name']}`", "failed", run.get("error_message", "")])
            continue
        counters = ", ".join(f"{key} {counter(value)}" for key, value in run.items()
                             if key not in BENCHMARK_KEYS and isinstance(value, (int, float)))
        rows.append([f"`{run['name']}`", duration(run["real_time"], run["time_unit"]), counters])
    return table(["benchmark", "wall time", "counters"], rows)


def duration(value, unit):
    """A benchmark's time in the largest unit it fills (3.041 s, not 3041 ms)."""
    seconds = value * {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}[unit]
    for scale, name in ((1.0, "s"), (1e-3, "ms"), (1e-6, "µs")):
        if seconds >= scale:
            return f"{seconds / scale:.4g} {name}"
    return f"{seconds / 1e-9:.4g} ns"


def counter(value):
    return str(int(value)) if float(value).is_integer() and abs(value) < 1e12 else f"{value:.4g}"


def machine():
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            for line in cpuinfo:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores"


def splice(document, name, body):
    """`document` with the text between block `name`'s markers replaced by `body`."""
    begin, end = f"<!-- BEGIN generated: {name} -->", f"<!-- END generated: {name} -->"
    start = document.find(begin)
    stop = document.find(end)
    if start < 0 or stop < start or document.count(begin) != 1 or document.count(end) != 1:
        raise ValueError(f"block '{name}': the document needs exactly one '{begin}' followed by one '{end}'")
    return document[:start + len(begin)] + "\n\n" + body + "\n\n" + document[stop:]


def run(program, data, arguments):
    """What `program` prints on standard output, run with `arguments` (and --data DATA)."""
    command = [program] + (["--data", data] if data else []) + arguments
    print("running:", " ".join(f'"{a}"' if " " in a else a for a in command), file=sys.stderr, flush=True)
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{program} exited with {result.returncode}")
    return result.stdout


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--evaluate", default=os.path.join(here, "..", "build", "bench", "xparam_evaluate"),
                        help="the xparam_evaluate program (default: build/bench/xparam_evaluate)")
    parser.add_argument("--data", help="xparam_evaluate's data folder (default: ../shared/data beside the "
                                       "checkout; the benchmarks always read that one)")
    parser.add_argument("--doc", default=os.path.join(here, "..", "docs", "evaluation.md"),
                        help="the document whose generated blocks are replaced (default: docs/evaluation.md)")
    parser.add_argument("--bench", default=os.path.join(here, "..", "build", "bench", "xparam_bench"),
                        help="the xparam_bench program (default: build/bench/xparam_bench)")
    parser.add_argument("--from-output", nargs=4, metavar=("TABLE", "REALISTIC", "PAPER", "BENCH_JSON"),
                        help="the saved output of the four runs, instead of running them")
    parser.add_argument("--keep-output", metavar="DIR", help="save the four runs' output in DIR")
    parser.add_argument("--date", help="the date stamped on the tables (default: today)")
    args = parser.parse_args()

    try:
        with open(args.doc, encoding="utf-8") as f:
            document = f.read()
        for name in BLOCKS:  # refused before the runs, not after them
            splice(document, name, "")
        if args.from_output:
            outputs = []
            for path in args.from_output:
                with open(path, encoding="utf-8") as f:
                    outputs.append(f.read())
        else:
            for program in (args.evaluate, args.bench):
                if not os.access(program, os.X_OK):
                    raise RuntimeError(f"{program}: no such program; build it first (scripts/test.sh build)")
            outputs = [run(args.evaluate, args.data, ["--set", "table"]),
                       run(args.evaluate, args.data, ["--set", "realistic", "--configuration", DEFAULT]),
                       run(args.evaluate, args.data, ["--set", "realistic", "--configuration", PAPER_MAP]),
                       run(args.bench, None, ["--benchmark_format=json"])]
            if args.keep_output:
                os.makedirs(args.keep_output, exist_ok=True)
                for file_name, text in zip(("table.txt", "realistic.txt", "realistic_paper.txt", "bench.json"),
                                           outputs):
                    with open(os.path.join(args.keep_output, file_name), "w", encoding="utf-8") as f:
                        f.write(text)
        (table_pairs, table_summary), (default_pairs, default_summary), (paper_pairs, paper_summary) = \
            [parse(text) for text in outputs[:3]]
        if not table_pairs and not default_pairs:
            raise RuntimeError("no pair was mapped (is the data folder there? xparam_evaluate --list shows the pairs)")
        try:
            bench_report = json.loads(outputs[3])
        except json.JSONDecodeError as error:
            raise ValueError(f"the benchmarks' output is not JSON ({error})") from error
        date = args.date or datetime.date.today().isoformat()
        stamp = (f"Generated by `scripts/update_evaluation.py` on {date} ({machine()}); "
                 f"{len(table_pairs)} pairs of the table set, {len(default_pairs)} of the realistic set.")
        blocks = {
            "stamp": stamp,
            "table1": table1(table_pairs),
            "table1_folds_truth": table1_folds_truth(table_pairs),
            "table1_default": table1_default(table_pairs),
            "realistic": realistic(default_pairs, paper_pairs),
            "hands_feet": hands_feet(default_pairs),
            "summary": summary([("The table set", table_summary), ("The realistic set, the default", default_summary),
                                ("The realistic set, the paper's map", paper_summary)]),
            "benchmarks": benchmarks(bench_report),
        }
        for name in BLOCKS:
            document = splice(document, name, blocks[name])
    except (OSError, ValueError, RuntimeError) as error:
        print(f"update_evaluation: {error}; {args.doc} is unchanged", file=sys.stderr)
        return 1
    # Written beside and renamed over it: a run stopped half-way leaves the old document whole.
    written = args.doc + ".new"
    with open(written, "w", encoding="utf-8") as f:
        f.write(document)
    os.replace(written, args.doc)
    print(f"update_evaluation: wrote {len(BLOCKS)} blocks of {args.doc}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
