#!/usr/bin/env python3
"""Draws shadowbench's comparison charts as SVG and PNG with matplotlib (Agg).

usage: plot_charts.py DATA.json...

Each DATA.json is one chart prepared by harness/results/charts.cpp (kinds
error_time, error_memory, time_triangles, error_triangles, time_resolution,
passes) or by harness/history/history_report.cpp (kind history); it names its
own output files. "style": "paper" draws a chart for a paper (PAPER_RC), as
PDF too ("pdf"). Exit codes: 0 all drawn, 1 some chart failed (tracebacks on
stderr, the other charts are still drawn), 2 usage, 3 matplotlib missing.
No network is used; text stays text in the SVG (svg.fonttype none).
"""
import json
import math
import os
import re
import sys
import tempfile
import traceback
import warnings

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import ticker
    from matplotlib.text import Text
except ImportError as e:
    print(f"plot_charts.py: cannot import matplotlib ({e}): apt-get install python3-matplotlib",
          file=sys.stderr)
    sys.exit(3)

matplotlib.rcParams.update({
    "svg.fonttype": "none",        # text as <text>, searchable
    "svg.hashsalt": "shadowbench",  # stable ids: the same data give the same SVG
    "text.parse_math": False,      # a '$' in a variant name is just a '$'
    "font.size": 8,
    "axes.titlesize": 9,
    "axes.labelsize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 7,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.5,
})

# --style paper (a chart's "style": "paper"): a two-column paper's column
# width, 8 pt Computer Modern from matplotlib's own mathtext fonts (no TeX
# needed), TrueType fonts in the PDF (no Type 3, which publishers refuse), no
# title (the caption says it) and the legend under the axes, so that the page
# is exactly PAPER_WIDTH wide.
PAPER_WIDTH = 3.3  # inches
PAPER_RC = {
    "font.family": "serif",
    "font.serif": ["cmr10"],
    "font.monospace": ["cmtt10"],  # technique names: cmr10 has no '_', '<', '>' or '|'
    "mathtext.fontset": "cm",
    "axes.unicode_minus": False,  # cmr10 has no U+2212
    # (axes.formatter.use_mathtext would print "$\\mathdefault{...}$": text.parse_math
    # is off, so that a '$' in a name stays a '$'; plain tick labels are cmr10 all the same,
    # and matplotlib's warning that says otherwise is silenced in draw_paper.)
    "font.size": 8,
    "axes.labelsize": 8,
    "xtick.labelsize": 7,
    "ytick.labelsize": 7,
    "legend.fontsize": 6.5,
    "axes.linewidth": 0.6,
    "lines.linewidth": 0.9,
    "pdf.fonttype": 42,
    "svg.fonttype": "path",  # the SVG looks as the PDF does where cmr10 is not installed
}


def paper_label(text):
    """An axis label shortened for a 3.3 in figure: no "(lower is better)",
    no "; bars p10-p90" (the bars are still drawn)."""
    text = re.sub(r" \((lower|higher) is better\)$", "", text)
    return re.sub(r"; bars p10.p90\)", ")", text).replace("\u2013", "-").replace("\u00d7", "x")


def move_legend_below(ax, lax, reverse=False):
    handles, labels = ax.get_legend_handles_labels()
    if ax.get_legend() is not None:
        ax.get_legend().remove()
    if reverse:
        handles, labels = handles[::-1], labels[::-1]
    lax.axis("off")
    if handles:
        lax.legend(handles, labels, loc="upper center", ncol=legend_columns(labels), frameon=False,
                   borderaxespad=0, handletextpad=0.4, columnspacing=1.0,
                   prop={"family": "monospace", "size": PAPER_RC["legend.fontsize"]})


def legend_columns(labels):
    """Two legend columns while the longest name fits in half of PAPER_WIDTH
    (cmtt10 at 6.5 pt: 3.4 pt a character), else one."""
    return 2 if max((len(x) for x in labels), default=0) <= 26 else 1


def draw_paper(d, kind, draw_kind):
    """One chart in the paper style: PDF (vector), SVG and PNG of the same page."""
    entries = len(d.get("points") or d.get("series") or d.get("bars") or [])
    if kind == "passes":
        entries = len({s["name"] for b in d["bars"] for s in b["segments"]})
    names = [p["label"] for p in d.get("points", [])] + [s["label"] for s in d.get("series", [])]
    names += [s["name"] for b in d.get("bars", []) for s in b["segments"]]
    legend_rows = math.ceil((entries + 1) / legend_columns(names))  # + 1: "Pareto front"
    plot_height = 2.3 if kind != "passes" else 2.3 + 0.05 * max(len(b["label"]) for b in d["bars"])
    legend_height = 0.05 + 0.12 * legend_rows
    with matplotlib.rc_context(PAPER_RC), warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="cmr10 font should ideally be used with mathtext")
        fig = plt.figure(figsize=(PAPER_WIDTH, plot_height + legend_height), layout="constrained")
        try:
            grid = fig.add_gridspec(2, 1, height_ratios=[plot_height, legend_height])
            ax = fig.add_subplot(grid[0])
            lax = fig.add_subplot(grid[1])
            draw_kind(fig, ax, d)
            if "xlabel" in d:
                ax.set_xlabel(paper_label(d["xlabel"]))
            ax.set_ylabel(paper_label(d["ylabel"]))
            move_legend_below(ax, lax, reverse=kind == "passes")
            if kind == "passes":  # technique names under the bars
                for label in ax.get_xticklabels():
                    label.set_family("monospace")
            save(fig, d["pdf"], "pdf", tight=False, metadata={"CreationDate": None})
            save(fig, d["svg"], "svg", tight=False, metadata={"Date": None})
            save(fig, d["png"], "png", tight=False, dpi=300)
        finally:
            plt.close(fig)


# tab10 without its grey (grey means "shared pass"); colours and markers cycle together.
COLOURS = [c for i, c in enumerate(plt.get_cmap("tab10").colors) if i != 7]
MARKERS = ["o", "s", "^", "D", "v", "P", "X"]  # 9 colours × 7 markers: 63 distinct styles
SHARED = {"gbuffer (shared)": "#8c8c8c", "shading (shared)": "#c8c8c8"}


def style(i):
    return COLOURS[i % len(COLOURS)], MARKERS[i % len(MARKERS)]


def log_scale(ax, which):
    """Log scale on ax's "x" or "y" axis, with 1-2-5 ticks labelled as plain numbers."""
    getattr(ax, f"set_{which}scale")("log")
    axis = getattr(ax, f"{which}axis")
    axis.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(ticker.FormatStrFormatter("%g"))
    axis.set_minor_locator(ticker.LogLocator(base=10, subs=tuple(range(1, 10))))
    axis.set_minor_formatter(ticker.NullFormatter())


def legend_outside(ax, **kw):
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0,
                  frameon=False, ncol=1 + len(labels) // 24, **kw)  # columns beyond 23 entries


def overlap(a, b):
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w * h if w > 0 and h > 0 else 0.0


# Offsets (points) and alignments tried for each Pareto label, best first: next
# to the point, then on rings further out (with a leader line).
CANDIDATES = [((6, 5), "left", "bottom"), ((6, -5), "left", "top"), ((-6, 5), "right", "bottom"),
              ((-6, -5), "right", "top"), ((0, 9), "center", "bottom"),
              ((0, -9), "center", "top"), ((9, 0), "left", "center"), ((-9, 0), "right", "center")]
for radius in (20, 32, 46, 64, 90):
    for degrees in (30, -30, 150, -150, 60, -60, 120, -120, 90, -90, 0, 180):
        dx = radius * math.cos(math.radians(degrees))
        dy = radius * math.sin(math.radians(degrees))
        CANDIDATES.append(((round(dx), round(dy)),
                           "left" if dx > 1 else "right" if dx < -1 else "center",
                           "bottom" if dy > 1 else "top" if dy < -1 else "center"))


def place_labels(fig, ax, front, all_xy):
    """Greedy placement: each label where it covers the fewest other labels and markers."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    axes_box = ax.get_window_extent(renderer)
    px = fig.dpi / 72.0
    markers = []
    for x, y in all_xy:
        cx, cy = ax.transData.transform((x, y))
        r = 7 * px  # a margin around each marker, so a label sits nearest its own point
        markers.append(((x, y), matplotlib.transforms.Bbox.from_extents(cx - r, cy - r, cx + r,
                                                                        cy + r)))
    placed = []
    for p in front:
        best = None
        for offset, ha, va in CANDIDATES:
            t = ax.annotate(p["label"], (p["x"], p["y"]), xytext=offset, textcoords="offset points",
                            ha=ha, va=va, fontsize=6.5,
                            bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8),
                            arrowprops=dict(arrowstyle="-", lw=0.4, color="0.4",
                                            shrinkA=0, shrinkB=3) if max(map(abs, offset)) > 10 else None,
                            zorder=5)
            t.update_positions(renderer)
            box = Text.get_window_extent(t, renderer).padded(1.5 * px)  # the text, not its leader
            cost = sum(overlap(box, b) for b in placed) * 4 + sum(
                overlap(box, m) for xy, m in markers if xy != (p["x"], p["y"]))
            outside = box.width * box.height - overlap(box, axes_box)
            cost += outside * 8
            if best is None or cost < best[0]:
                if best is not None:
                    best[1].remove()
                best = (cost, t, box)
            else:
                t.remove()
            if cost == 0:
                break
        placed.append(best[2])


def error_cost(fig, ax, d):
    for p in d["points"]:
        colour, marker = style(p["style"])
        xerr = None
        if p["xlo"] is not None and p["xhi"] is not None:
            xerr = [[max(p["x"] - p["xlo"], 0)], [max(p["xhi"] - p["x"], 0)]]
        if p.get("control"):  # a reference, not a competitor: hollow, grey, named so
            ax.errorbar([p["x"]], [p["y"]], xerr=xerr, fmt=marker, color="0.45", mfc="none",
                        ms=5, capsize=2, elinewidth=0.8, label=p["label"] + " (control)", zorder=3)
            continue
        ax.errorbar([p["x"]], [p["y"]], xerr=xerr, fmt=marker, color=colour, ms=5, capsize=2,
                    elinewidth=0.8, label=p["label"], zorder=3)
    front = d["front"]
    if front:
        ax.plot([p["x"] for p in front], [p["y"] for p in front], drawstyle="steps-post",
                color="black", lw=1.0, alpha=0.55, zorder=2, label="Pareto front")
        ax.scatter([p["x"] for p in front], [p["y"] for p in front], s=70, facecolors="none",
                   edgecolors="black", linewidths=0.7, zorder=4)
    if d["xlog"]:
        log_scale(ax, "x")
    ax.margins(x=0.08, y=0.1)
    if d.get("style") == "paper":  # the legend names the points; no room for labels
        return
    if d["missing"]:
        fig.text(0.01, -0.02, "not drawn (no finite time or error): " + ", ".join(d["missing"]),
                 fontsize=6.5, ha="left", va="top")
    legend_outside(ax)
    place_labels(fig, ax, front, [(p["x"], p["y"]) for p in d["points"]])


def time_lines(fig, ax, d):
    for s in d["series"]:
        colour, marker = style(s["style"])
        pts = s["points"]
        xs = [p["x"] for p in pts]
        ys = [p["y"] for p in pts]
        lo = [max(p["y"] - p["ylo"], 0) if p["ylo"] is not None else 0 for p in pts]
        hi = [max(p["yhi"] - p["y"], 0) if p["yhi"] is not None else 0 for p in pts]
        ax.errorbar(xs, ys, yerr=[lo, hi], fmt="-" + marker, color=colour, ms=4, lw=1, capsize=2,
                    elinewidth=0.8, label=s["label"])
    if d.get("xlog"):
        log_scale(ax, "x")
    if d.get("ylog"):
        log_scale(ax, "y")
    if "xticks" in d:
        ax.set_xticks([t["value"] for t in d["xticks"]], [t["label"] for t in d["xticks"]])
        ax.xaxis.set_minor_locator(ticker.NullLocator())
    else:
        ax.xaxis.set_major_formatter(ticker.EngFormatter(sep=""))
    ax.margins(x=0.06)
    legend_outside(ax)


def passes(fig, ax, d):
    bars = d["bars"]
    seen = set()
    for i, bar in enumerate(bars):
        bottom = 0.0
        for s in bar["segments"]:
            colour = SHARED.get(s["name"], "#bbbbbb") if s["shared"] else style(s["style"])[0]
            label = None if s["name"] in seen else s["name"]
            seen.add(s["name"])
            ax.bar(i, s["ms"], bottom=bottom, width=0.7, color=colour, edgecolor="white",
                   linewidth=0.4, label=label)
            bottom += s["ms"]
        ax.text(i, bottom, f"{bottom:.3g}", ha="center", va="bottom", fontsize=6)
    ax.set_xticks(range(len(bars)), [b["label"] for b in bars], rotation=35, ha="right",
                  rotation_mode="anchor")
    ax.set_xlim(-0.6, len(bars) - 0.4)
    ax.margins(y=0.08)
    ax.grid(axis="x", visible=False)
    # Legend: shared passes first (bottom of each bar), then the technique passes.
    handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles[::-1], labels[::-1], loc="upper left", bbox_to_anchor=(1.02, 1.0),
              borderaxespad=0, frameon=False, title="pass (median)", title_fontsize=7)


def history(d):
    """A series across runs: one panel per quantity against run order, a
    marker per host, each segment's median as a line and each step as a
    dashed red line between the last run before it and the first after."""
    panels = d["panels"]
    n = len(d["ticks"])
    fig, axes = plt.subplots(len(panels), 1, figsize=(max(6.0, min(14.0, 2.5 + 0.28 * n)), 2.4 * len(panels)),
                             sharex=True, squeeze=False)
    xs = list(range(1, n + 1))
    for ax, p in zip(axes[:, 0], panels):
        pts = [(x, v, h) for x, v, h in zip(xs, p["values"], d["hosts"]) if v is not None]
        ax.plot([x for x, _, _ in pts], [v for _, v, _ in pts], color="#9aa3b2", linewidth=0.8, zorder=1)
        for h, label in enumerate(d["host_labels"]):
            mine = [(x, v) for x, v, hh in pts if hh == h]
            if mine:
                colour, marker = style(h)
                ax.scatter([x for x, _ in mine], [v for _, v in mine], s=16, color=colour, marker=marker,
                           label=label, zorder=3)
        for seg in p["segments"]:
            ax.hlines(seg["level"], seg["from"] + 0.6, seg["to"] + 0.4, colors="#1d2330", linewidth=1.2, zorder=2)
        for i, at in enumerate(p["steps"]):
            ax.axvline(at + 0.5, color="#d0342c", linestyle="--", linewidth=1.0, zorder=2,
                       label="step" if i == 0 else None)
        ax.set_ylabel(p["ylabel"])
        if len(d["host_labels"]) > 1 or p["steps"]:
            ax.legend(loc="best")
    axes[0, 0].set_title(d["title"])
    bottom = axes[-1, 0]
    every = max(1, math.ceil(n / 30))
    bottom.set_xticks(xs[::every])
    bottom.set_xticklabels([f"{x}\n{t}" for x, t in zip(xs, d["ticks"])][::every], fontsize=6)
    bottom.set_xlim(0.5, n + 0.5)
    bottom.set_xlabel(d["xlabel"])
    fig.tight_layout()
    return fig


def save(fig, path, fmt, tight=True, **kw):
    # As core/atomic_file does: a temporary file this process creates
    # (mkstemp: O_CREAT|O_EXCL, never through a symlink planted in a run
    # folder from elsewhere), renamed over the target (a symlink there is
    # replaced, not followed).
    folder, name = os.path.split(path)
    fd, tmp = tempfile.mkstemp(prefix=name + ".tmp-", dir=folder or ".")
    try:
        with os.fdopen(fd, "wb") as f:
            fig.savefig(f, format=fmt, bbox_inches="tight" if tight else None, **kw)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def draw(data_path):
    with open(data_path, encoding="utf-8") as f:
        d = json.load(f)
    kind = d["kind"]
    if kind == "history":
        fig = history(d)
        try:
            save(fig, d["svg"], "svg", metadata={"Date": None})
            save(fig, d["png"], "png", dpi=150)
        finally:
            plt.close(fig)
        return
    draw_kind = {"error_time": error_cost, "error_memory": error_cost, "time_triangles": time_lines,
                 "error_triangles": time_lines, "time_resolution": time_lines, "passes": passes}[kind]
    if d.get("style") == "paper":
        draw_paper(d, kind, draw_kind)
        return
    width = 7.5
    if kind == "passes":
        width = max(5.5, 2.5 + 0.45 * len(d["bars"]))
    height = 4.2
    if kind in ("error_time", "error_memory"):  # room for the labels of a long front
        height += 0.12 * max(0, len(d["front"]) - 6)
    fig, ax = plt.subplots(figsize=(width, height))
    try:
        draw_kind(fig, ax, d)
        ax.set_title(d["title"])
        if "xlabel" in d:
            ax.set_xlabel(d["xlabel"])
        ax.set_ylabel(d["ylabel"])
        save(fig, d["svg"], "svg", metadata={"Date": None})
        save(fig, d["png"], "png", dpi=150)
    finally:
        plt.close(fig)


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    failed = 0
    for path in argv[1:]:
        try:
            draw(path)
        except Exception:  # one bad chart must not hide the others
            failed += 1
            print(f"plot_charts.py: {path}:", file=sys.stderr)
            traceback.print_exc()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
