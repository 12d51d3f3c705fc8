#!/usr/bin/env python3
"""Writes the measured tables of the docs from their configs, and checks them.

A generated table sits between two markers in a Markdown file:

    <!-- doc-table: configs/docs/x.json rows=technique columns=scene cells=timing.technique.median_ms:,.1f,metrics.visibility.all.rmse:.4f begin -->
    | technique | sphere_grid: ms | sphere_grid: RMSE all | ...
    ...
    (a line naming the fields, the command and the commit)
    <!-- doc-table: end -->

The begin marker says what the table holds:
  - the config, run with `build/shadowbench run CONFIG` (each config once,
    however many tables read it); its results.jsonl holds the figures;
  - rows=KEYS: one row per distinct value of these keys, in job order;
    columns=KEYS (optional): the cells repeat for each distinct value;
    keys: technique (the record's technique_variant), scene (scene_variant),
    resolution;
  - cells=PATH:FORMAT,...: what each cell prints, a path into the record
    (metrics.visibility.all.rmse; a path under timing. is a time; report.COLUMN
    is a column of the run's results.csv, such as report.mc_noise_share) and a
    Python format spec (.4f, ,.1f). An error figure of 0 prints as 0, a
    list as its items with " / " between;
  - where=KEY:VALUE (optional): only the records whose key has that value.

Timings are measured on this host: they are written, never checked. Error
figures are deterministic (reruns are bit-identical on one build), so
--check fails when a committed one differs from what the config produces.

    scripts/doc_tables.py [FILE.md ...]            rewrite the tables (default: docs/*.md)
    scripts/doc_tables.py --check [FILE.md ...]     exit 1 when a committed error figure differs
    scripts/doc_tables.py --list [FILE.md ...]      the tables and their configs, nothing run

--keep-times keeps the committed tables' times (rows matched by label,
columns by position) and writes only the errors: for a run on a loaded
machine. --runs DIR keeps the run folders (DIR/<config stem>) and reads one
that holds a record for every job of its plan instead of running its config
again (one left part-way is resumed); without it every config runs afresh in
a temporary folder. The whole docs' --check takes about 50 minutes on the
2-core VM; CI checks the reduced-size twin (tests/doc_tables/check.md). --self-test checks the parser and the
comparison on a made-up table (no shadowbench run): an edited figure fails.
"""
import argparse
import csv
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEGIN = re.compile(r"^<!-- doc-table: (?P<spec>.+) begin -->$")
END = "<!-- doc-table: end -->"
RUN_NOTE = "doc-tables-run.json"
STATUSES = ("skipped", "failed")
ROW_KEYS = {"technique": "technique_variant", "scene": "scene_variant", "resolution": "resolution"}
# What a reader compares a column with: summary.md's columns by their
# record field (harness/results/report_columns.cpp).
SUMMARY_COLUMNS = {
    "metrics.visibility.geometry.rmse": "rmse",
    "metrics.visibility.penumbra.rmse": "penumbra_rmse",
    "metrics.visibility.geometry.ssim": "ssim",
    "metrics.visibility.near_third.rmse": "near_rmse",
    "metrics.visibility.middle_third.rmse": "middle_rmse",
    "metrics.visibility.far_third.rmse": "far_rmse",
    "metrics.flip_shaded": "flip",
}
STAT_LABELS = {"rmse": "RMSE", "mae": "MAE", "ssim": "SSIM", "flip_mean": "FLIP", "psnr": "PSNR"}


class Spec:
    """One table's begin marker."""

    def __init__(self, text, where):
        self.text = text
        self.where = where
        words = text.split()
        if not words:
            raise SystemExit(f"{where}: doc-table marker without a config")
        self.config = words[0]
        self.rows, self.columns, self.cells, self.where = [], [], [], {}
        for word in words[1:]:
            key, sep, value = word.partition("=")
            if not sep:
                raise SystemExit(f"{where}: '{word}': expected KEY=VALUE")
            if key in ("rows", "columns"):
                keys = value.split(",") if value else []
                for k in keys:
                    if k not in ROW_KEYS:
                        raise SystemExit(f"{where}: {key}: unknown key '{k}' (expected one of: {', '.join(ROW_KEYS)})")
                setattr(self, key, keys)
            elif key == "cells":
                self.cells = parse_cells(value, where)
            elif key == "where":
                k, sep, v = value.partition(":")
                if not sep or k not in ROW_KEYS:
                    raise SystemExit(f"{where}: where: expected KEY:VALUE with KEY one of {', '.join(ROW_KEYS)}")
                self.where[k] = v
            else:
                raise SystemExit(f"{where}: unknown setting '{key}' (expected rows, columns, cells, where)")
        if not self.rows or not self.cells:
            raise SystemExit(f"{where}: a doc-table needs rows= and cells=")


def parse_cells(value, where):
    """[(path, format)] from 'path:fmt,path:fmt' (a format may hold a comma: ',.1f')."""
    cells = []
    for m in re.finditer(r"([A-Za-z_][\w.]*):(,?[^,]*)(?:,|$)", value):
        path, fmt = m.group(1), m.group(2)
        try:
            format(1.5, fmt)
        except ValueError:
            raise SystemExit(f"{where}: cell {path}: bad format '{fmt}'") from None
        cells.append((path, fmt))
    if not cells or ",".join(f"{p}:{f}" for p, f in cells) != value:
        raise SystemExit(f"{where}: cells: expected PATH:FORMAT,... (e.g. metrics.visibility.all.rmse:.4f), found '{value}'")
    return cells


def is_time(path):
    return path.startswith("timing.")


def cell_label(path):
    parts = path.split(".")
    if is_time(path):
        return "ms" if parts[1] == "frame" else f"{parts[1]} ms"
    if len(parts) == 4 and parts[0] in ("metrics", "second_reference"):
        label = f"{STAT_LABELS.get(parts[3], parts[3])} {parts[2]}"
        if parts[1] != "visibility":
            label += f" ({parts[1]})"
        return label if parts[0] == "metrics" else f"{label}, second reference"
    return parts[-1]


def field_note(path):
    """How the line under a table names one cell's field."""
    if is_time(path):
        return f"`{path}`"
    if path.startswith("report."):
        return f"summary.md's `{path[len('report.'):]}` column"
    summary = SUMMARY_COLUMNS.get(path)
    if summary:
        return f"`{path}` (summary.md's `{summary}`)"
    if path == "metrics.visibility.all.rmse":
        # The figure a reader most often compares with summary.md's `rmse`,
        # which is over another region.
        return f"`{path}` (every pixel but the horizon cut; summary.md's `rmse` is over `geometry`)"
    return f"`{path}`"


def lookup(record, path):
    value = record
    for part in path.split("."):
        if not isinstance(value, dict) or part not in value:
            return None
        value = value[part]
    return value


def format_value(value, fmt):
    if value is None:
        return "–"
    if isinstance(value, str):
        return value
    if isinstance(value, list):
        return " / ".join(format_value(v, fmt) for v in value)
    if value == 0:
        return "0"
    return format(value, fmt)


def read_records(run_dir):
    """The last record of each job, in job order."""
    path = os.path.join(run_dir, "results.jsonl")
    records = {}
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.strip():
                r = json.loads(line)
                records[r["job_id"]] = r
    columns = report_columns(run_dir)
    for r in records.values():
        r["report"] = columns.get((r.get("scene_variant"), r.get("resolution"), r.get("technique_variant")), {})
    return sorted(records.values(), key=lambda r: r.get("job_index", 0))


def report_columns(run_dir):
    """results.csv's row of each job, by (scene, resolution, technique): the
    report's own columns (mc_noise_share, ...), as numbers where they are."""
    rows = {}
    try:
        with open(os.path.join(run_dir, "results.csv"), encoding="utf-8", newline="") as f:
            for row in csv.DictReader(f):
                values = {}
                for k, v in row.items():
                    try:
                        values[k] = float(v)
                    except (TypeError, ValueError):
                        values[k] = v if v else None
                rows[(row.get("scene"), row.get("resolution"), row.get("technique"))] = values
    except OSError:
        pass
    return rows


def key_of(record, keys):
    return tuple(record.get(ROW_KEYS[k], "") for k in keys)


def table_lines(spec, records, run_note):
    """The Markdown of one table (header, rows, the line under it)."""
    rows, columns, by_cell = [], [], {}
    for r in records:
        if any(r.get(ROW_KEYS[k]) != v for k, v in spec.where.items()):
            continue
        row, col = key_of(r, spec.rows), key_of(r, spec.columns)
        if row not in rows:
            rows.append(row)
        if col not in columns:
            columns.append(col)
        by_cell[(row, col)] = r
    header = list(spec.rows)
    align = ["---"] * len(spec.rows)
    for col in columns:
        group = "/".join(col)
        for path, _ in spec.cells:
            label = cell_label(path)
            header.append(f"{group}: {label}" if group else label)
            align.append("---:")
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join(align) + "|"]
    for row in rows:
        out = [f"`{v}`" if k == "technique" else v for k, v in zip(spec.rows, row)]
        for col in columns:
            r = by_cell.get((row, col))
            status = r.get("status") if r else None
            for i, (path, fmt) in enumerate(spec.cells):
                if r is None:
                    out.append("")
                elif status != "ok":
                    out.append(status if i == 0 else "")
                else:
                    out.append(format_value(lookup(r, path), fmt))
        lines.append("| " + " | ".join(out) + " |")
    fields = "; ".join(f"{cell_label(p)}: {field_note(p)}" for p, _ in spec.cells)
    lines.append("")
    lines.append(f"Fields: {fields}. {run_note}")
    return lines


def split_row(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def same_figure(a, b):
    """Equal cells, or decimals one unit of their last printed digit apart.

    Errors are deterministic on one machine, but another CPU (Embree's and
    llvmpipe's vector width) may round a figure's last digit the other way;
    a stale table is off by far more (3-7 % for the jitter change)."""
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except ValueError:
        return False
    if "." not in a or "." not in b or len(a.split(".")[1]) != len(b.split(".")[1]):
        return False
    unit = 10.0 ** -len(a.split(".")[1])
    return abs(x - y) <= unit * 1.0001


def compare_tables(spec, committed, produced):
    """Differences in the error figures: [(row label, column, committed, produced)]."""
    ours = [l for l in committed if l.startswith("|")]
    theirs = [l for l in produced if l.startswith("|")]
    if not ours:
        return [("(table)", "", "missing", "generated")]
    head_ours, head_theirs = split_row(ours[0]), split_row(theirs[0])
    if head_ours != head_theirs:
        return [("(header)", "", ours[0], theirs[0])]
    n = len(spec.rows)
    timing = [i >= n and is_time(spec.cells[(i - n) % len(spec.cells)][0]) for i in range(len(head_theirs))]
    diffs = []
    rows_ours = {tuple(split_row(l)[: len(spec.rows)]): split_row(l) for l in ours[2:]}
    for line in theirs[2:]:
        cells = split_row(line)
        label = tuple(cells[: len(spec.rows)])
        mine = rows_ours.pop(label, None)
        if mine is None:
            diffs.append((" ".join(label), "", "missing", "a row"))
            continue
        for i, (a, b) in enumerate(zip(mine, cells)):
            if i >= n and not timing[i] and not same_figure(a, b):
                diffs.append((" ".join(label), head_theirs[i], a, b))
    for label in rows_ours:
        diffs.append((" ".join(label), "", "a row", "missing"))
    return diffs


def keep_times(spec, committed, produced):
    """produced with the time cells of committed's rows of the same label.

    For a run on a loaded machine: its errors are as good as any run's, its
    times are not. Columns are matched by position, so a table typed before
    it was generated keeps its times when it had the same layout."""
    n = len(spec.rows)
    ours = {tuple(split_row(l)[:n]): split_row(l) for l in committed[2:] if l.startswith("|")}
    out = list(produced)
    for k, line in enumerate(produced[2:], start=2):
        if not line.startswith("|"):
            break
        cells = split_row(line)
        mine = ours.get(tuple(cells[:n]))
        if mine is not None and len(mine) != len(cells):
            mine = None
        for i in range(n, len(cells)):
            # A row the table did not have gets no time: this run's would
            # not compare with the kept ones.
            if is_time(spec.cells[(i - n) % len(spec.cells)][0]) and cells[i] not in STATUSES:
                cells[i] = mine[i] if mine else ""
        out[k] = "| " + " | ".join(cells) + " |"
    return out


def find_tables(path):
    """[(spec, begin line index, end line index)] of one Markdown file."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    tables = []
    i = 0
    while i < len(lines):
        m = BEGIN.match(lines[i])
        if m:
            where = f"{os.path.relpath(path, ROOT)}:{i + 1}"
            end = next((j for j in range(i + 1, len(lines)) if lines[j] == END), None)
            if end is None:
                raise SystemExit(f"{where}: doc-table without '{END}'")
            tables.append((Spec(m.group("spec"), where), i, end))
            i = end
        i += 1
    return lines, tables


def locate(lines, spec, path, start):
    """(begin, end) of the first table at or after line start whose marker is spec's."""
    marker = f"<!-- doc-table: {spec.text} begin -->"
    begin = lines.index(marker, start) if marker in lines[start:] else None
    if begin is None or END not in lines[begin:]:
        raise SystemExit(f"{os.path.relpath(path, ROOT)}: the table of '{spec.text}' is gone")
    return begin, lines.index(END, begin)


def git_commit():
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, check=True,
                              capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--", "harness", "techniques", "scenes",
                                "CMakeLists.txt"], cwd=ROOT, check=True, capture_output=True, text=True).stdout
        return head + ("+changes" if dirty.strip() else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def host_of(records):
    r = next((r for r in records if r.get("host")), None)
    if not r:
        return "this host"
    cpu = r["host"].get("cpu", {})
    return f"{cpu.get('model', '?')}, {r['host'].get('hardware_threads', '?')} threads"


def run_config(config, build, runs, fresh_root):
    """The run folder of config: read from runs/<stem> if there, else run into it."""
    stem = os.path.splitext(os.path.basename(config))[0]
    base = runs if runs else fresh_root
    out = os.path.join(base, stem)
    if not (runs and run_complete(out)):
        # shadowbench resumes a folder it left part-way (its records name
        # what each job ran with, so a changed config reruns what changed).
        if not runs and os.path.exists(out):
            shutil.rmtree(out)
        cmd = [os.path.join(build, "shadowbench"), "run", os.path.join(ROOT, config), "--out", out,
               "--no-images", "--quiet", "--cache-dir", os.path.join(base, "cache")]
        start = time.monotonic()
        done = subprocess.run(cmd, cwd=ROOT)
        seconds = time.monotonic() - start
        if done.returncode not in (0, 1):
            raise SystemExit(f"doc_tables: {' '.join(cmd)} exited with {done.returncode}")
        # What else ran shapes the times (not the errors): kept beside the
        # records so that a table read from the folder later says it too.
        run = {"seconds": round(seconds, 1), "load_average": round(os.getloadavg()[0], 1), "commit": git_commit()}
        with open(os.path.join(out, RUN_NOTE), "w", encoding="utf-8") as f:
            json.dump(run, f)
        print(f"doc_tables: {config}: ran in {seconds:.1f} s", file=sys.stderr)
    return out


def run_complete(out):
    """Whether out holds a record for every job of its plan."""
    try:
        with open(os.path.join(out, "plan.json"), encoding="utf-8") as f:
            jobs = len(json.load(f)["jobs"])
        return len(read_records(out)) >= jobs
    except (OSError, ValueError, KeyError):
        return False


def run_note(out):
    """What this script noted when it ran the folder: {} for another's."""
    try:
        with open(os.path.join(out, RUN_NOTE), encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def run_conditions(run):
    if "seconds" not in run or "load_average" not in run:
        return ""
    return f" (the run took {run['seconds']:.0f} s; load average {run['load_average']} at its end)"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="*", help="Markdown files (default: docs/*.md)")
    ap.add_argument("--check", action="store_true", help="compare, write nothing; exit 1 on a differing error figure")
    ap.add_argument("--list", action="store_true", help="list the tables and their configs")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="the build folder holding shadowbench")
    ap.add_argument("--runs", help="keep run folders here, and read one already there instead of running")
    ap.add_argument("--only", help="only the tables of this config")
    ap.add_argument("--keep-times", action="store_true",
                    help="keep the committed tables' times (a loaded machine's errors are good, its times are not)")
    ap.add_argument("--self-test", action="store_true", help="check the parser and comparison on a made-up table")
    args = ap.parse_args(argv)
    if args.self_test:
        return self_test()
    files = args.files or sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
    found = []
    for path in files:
        lines, tables = find_tables(path)
        for spec, begin, end in tables:
            if args.only and os.path.normpath(spec.config) != os.path.normpath(args.only):
                continue
            found.append((path, spec, begin, end))
    if args.list:
        for path, spec, begin, _ in found:
            print(f"{os.path.relpath(path, ROOT)}:{begin + 1}: {spec.config}")
        return 0
    if not found:
        print("doc_tables: no doc-table markers found", file=sys.stderr)
        return 2
    fresh_root = tempfile.mkdtemp(prefix="doc-tables-")
    try:
        return process(args, found, fresh_root)
    finally:
        shutil.rmtree(fresh_root, ignore_errors=True)


def process(args, found, fresh_root):
    commit = git_commit()
    runs, failures = {}, 0
    edits = {}  # path -> (lines, [(begin, end, produced)])
    searched = {}  # path -> where the next table's marker is looked for
    # Every run first, then the files as they are after them (a long run
    # must not write back a file as it was before someone edited it).
    for _, spec, _, _ in found:
        if spec.config not in runs:
            runs[spec.config] = run_config(spec.config, args.build, args.runs, fresh_root)
    for path, spec, _, _ in found:
        out = runs[spec.config]
        records = read_records(out)
        run = run_note(out)
        times = ""
        if any(is_time(p) for p, _ in spec.cells):
            times = "; times are not checked"
            if args.keep_times:
                times = ("; times kept from the table before (`--keep-times`, the run the text describes; none for a"
                         " row it did not have), not checked")
        note = (f"Written by `scripts/doc_tables.py` from `build/shadowbench run {spec.config}` at commit "
                f"{run.get('commit', commit)} on {host_of(records)}{run_conditions(run)}{times}.")
        if path not in edits:
            edits[path] = (find_tables(path)[0], [])
        lines, replacements = edits[path]
        # The file as it is now: it may have been edited while the config ran.
        begin, end = locate(lines, spec, path, searched.get(path, 0))
        searched[path] = end
        produced = table_lines(spec, records, note)
        committed = lines[begin + 1:end]
        if args.keep_times:
            produced = keep_times(spec, committed, produced)
        if args.check:
            diffs = compare_tables(spec, committed, produced)
            rel = os.path.relpath(path, ROOT)
            for row, col, a, b in diffs:
                print(f"{rel}:{begin + 1}: {spec.config}: {row} | {col}: committed {a}, produced {b}")
            failures += len(diffs)
            if not diffs:
                print(f"{rel}:{begin + 1}: {spec.config}: every error figure as committed")
        else:
            replacements.append((begin, end, produced))
    if not args.check:
        for path, (lines, replacements) in edits.items():
            # From the bottom up, so that earlier indices stay valid.
            for begin, end, produced in sorted(replacements, reverse=True):
                lines[begin + 1:end] = produced
            with open(path, "w", encoding="utf-8") as f:
                f.write("\n".join(lines))
            print(f"doc_tables: wrote {os.path.relpath(path, ROOT)}", file=sys.stderr)
    return 1 if failures else 0


def self_test():
    """A made-up record and table: the table checks as itself, an edited figure fails."""
    record = {"job_id": "a", "job_index": 0, "status": "ok", "technique_variant": "t/size=1",
              "scene_variant": "s", "resolution": "8x8",
              "metrics": {"visibility": {"all": {"rmse": 0.012345}}}, "timing": {"frame": {"median_ms": 12.34}}}
    skipped = dict(record, job_id="b", job_index=1, technique_variant="u", status="skipped")
    spec = Spec("configs/x.json rows=technique columns=scene cells=timing.frame.median_ms:,.1f,"
                "metrics.visibility.all.rmse:.4f", "self-test")
    produced = table_lines(spec, [record, skipped], "note")
    problems = []
    if "| `t/size=1` | 12.3 | 0.0123 |" not in produced:
        problems.append(f"unexpected row: {produced}")
    if compare_tables(spec, produced, produced):
        problems.append("a table differs from itself")
    edited = [l.replace("0.0123", "0.0125") for l in produced]
    if len(compare_tables(spec, edited, produced)) != 1:
        problems.append("an edited error figure was not caught")
    rounded = [l.replace("0.0123", "0.0124") for l in produced]
    if compare_tables(spec, rounded, produced):
        problems.append("a last digit rounded the other way was reported")
    retimed = [l.replace("12.3", "99.9") for l in produced]
    if compare_tables(spec, retimed, produced):
        problems.append("a different time was reported (times are not checked)")
    kept = keep_times(spec, retimed, produced)
    if "| `t/size=1` | 99.9 | 0.0123 |" not in kept:
        problems.append(f"--keep-times did not keep the committed time: {kept}")
    for p in problems:
        print(f"doc_tables self-test: {p}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
