#!/usr/bin/env python3
"""Turns raykit_bench's Google Benchmark JSON into docs/benchmarks.md and speed-vs-error plots.

Usage: python3 scripts/bench_report.py --json build/bench.json [--json MORE.json ...] [--out-dir docs]
           [--merged-out build/bench.json] [--previous build/bench.prev.json] [--binary-sha256 SHA]

Several --json files are the same benchmarks run in separate processes (scripts/bench.sh): they are
merged (each iteration entry tagged with its process, the first file's context kept) and, with
--merged-out, written as one JSON. A row's value is then the median over the processes and its
range the range of the per-process values (each process's own median over its repetitions).
--previous names an earlier merged JSON: when its raykit_binary_sha256 equals --binary-sha256 (the
same build), the report states how many rows of each run lie inside the other's range.

Writes OUT_DIR/benchmarks.md (machine context, then one section per bench file ("suite"), each with
its plot and one table per family, in registration order) and, per suite with plotted families,
OUT_DIR/img/bench_<suite>.dat and, when gnuplot is on PATH, OUT_DIR/img/bench_<suite>_speed_error.png.
The octree build suite (bench/bench_svo.cpp: rows with a bytes_thesis counter) gets its own section
instead: one table per mesh, the thesis's goals said met / missed / not measured, and
OUT_DIR/img/bench_svo_build.dat and .png (build time and bytes per voxel vs depth).
Pure standard library.

Everything the report says about a benchmark comes from the JSON written by bench/bench_*.cpp
(see bench/bench_common.hpp and bench/bench_main.cpp):
  name     BM_<suite>/<variant>/<parameters>
  label    "<family>|<function>|<what the error is measured against>[|<flags>]", flags a comma list
           ("cross": the error is against a different formula, drawn in another colour)
  counters items_per_second, max_abs_err, mean_abs_err, max_ulp (optional), worst_at or
           worst_at_r/g/b (an RGB input)
  context  raykit_suites, raykit_suite:<suite>:<title|source|unit|baseline|families|plot_families|
           about|gpu>, raykit_family:<family> = title, raykit_build_type...
JSON without raykit_suites (older raykit_bench) is read as one suite, "fresnel", with
raykit_baseline and raykit_plot_families.
With --benchmark_repetitions the median aggregate is used (and the cv aggregate, when present, is
shown as the run-to-run spread); without, the median of whatever iteration runs there are.
"""

import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rerun_stats  # noqa: E402  (scripts/rerun_stats.py)

DEFAULT_SUITE = "fresnel"
DEFAULT_BASELINE = "BM_fresnel/schlick/eta:1.52"


def png_name(suite):
    return "bench_%s_speed_error.png" % suite


def dat_name(suite):
    return "bench_%s.dat" % suite


# ------------------------------------------------------------------------------------------------
# Reading the JSON


class Row:
    """One benchmark (all repetitions folded into one value)."""

    def __init__(self, name, entry):
        self.name = name
        parts = name.split("/")
        self.suite = parts[0][3:] if parts[0].startswith("BM_") else parts[0]
        self.variant = parts[1] if len(parts) > 1 else name
        self.params = "/".join(parts[2:])
        label = entry.get("label", "")
        fields = label.split("|") if label else []
        self.family = fields[0] if len(fields) > 0 and fields[0] else "other"
        self.function = fields[1] if len(fields) > 1 else self.variant
        self.against = fields[2] if len(fields) > 2 else ""
        self.flags = set(f.strip() for f in fields[3].split(",") if f.strip()) if len(fields) > 3 else set()
        self.max_abs = entry.get("max_abs_err")
        self.mean_abs = entry.get("mean_abs_err")
        self.max_ulp = entry.get("max_ulp")
        self.worst_at = entry.get("worst_at")
        rgb = [entry.get("worst_at_" + c) for c in "rgb"]
        self.worst_rgb = rgb if all(v is not None for v in rgb) else None
        self.ns = ns_per_call(entry)
        self.entry = entry  # every field and counter, for sections that read their own (octree build)
        self.cv = None  # relative run-to-run spread of the time, when repetitions were aggregated
        self.reps = 1
        self.samples = 1  # how many values the range is taken over (processes, else repetitions)
        # Paired timing (bench_common.hpp run_paired): (median, min, max) over the repetitions.
        self.rel = None        # own / baseline, harness subtracted from both
        self.rel_gross = None  # own / baseline, harness included
        self.harness_ns = None
        # Registration order (stable even with --benchmark_enable_random_interleaving).
        self.order = (entry.get("family_index", 0), entry.get("per_family_instance_index", 0))
        self.add_paired([entry])

    def add_paired(self, runs):
        self.rel = paired_stats(runs, "rel_cost")
        self.rel_gross = paired_stats(runs, "rel_cost_gross")
        h = paired_stats(runs, "harness_per_call")
        self.harness_ns = h[0] * 1e9 if h else None


def ns_per_call(entry):
    tpc = entry.get("time_per_call")  # the median of the timed passes (bench_common.hpp)
    if tpc:
        return tpc * 1e9
    ips = entry.get("items_per_second")
    if ips:
        return 1e9 / ips
    return None


def strip_manual(name):
    """Google Benchmark appends "/manual_time" to rows timed by hand (the paired rows)."""
    return name[:-len("/manual_time")] if name.endswith("/manual_time") else name


def per_process(runs, key):
    """The values of `key` the spread is taken over: one per process (the median of that process's
    repetitions) when the runs come from several processes, else one per repetition."""
    groups = {}
    for r in runs:
        v = key(r) if callable(key) else r.get(key)
        if v is not None:
            groups.setdefault(r.get("raykit_process", 0), []).append(v)
    if len(groups) > 1:
        return [statistics.median(v) for _, v in sorted(groups.items())]
    return next(iter(groups.values()), [])


def paired_stats(runs, key):
    """(median, min, max) of a paired counter over the processes (or the repetitions), or None."""
    vals = per_process(runs, key)
    if not vals:
        return None
    return statistics.median(vals), min(vals), max(vals)


def merge_json(paths, binary_sha256=None):
    """One Google Benchmark JSON from several processes' files: the first file's context (plus
    raykit_processes and raykit_binary_sha256), every file's benchmarks, each iteration entry tagged
    with "raykit_process" (1, 2, ...)."""
    merged = None
    for k, path in enumerate(paths, start=1):
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        if merged is None:
            merged = {"context": dict(data.get("context", {})), "benchmarks": []}
        for e in data.get("benchmarks", []):
            e = dict(e)
            e["raykit_process"] = k
            merged["benchmarks"].append(e)
    merged["context"]["raykit_processes"] = len(paths)
    if binary_sha256:
        merged["context"]["raykit_binary_sha256"] = binary_sha256
    return merged


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def load(data):
    """(context, rows) of a Google Benchmark JSON (a dict, see read_json and merge_json)."""
    context = data.get("context", {})
    entries = data.get("benchmarks", [])

    order = []  # run names in first-seen order
    iterations = {}
    medians = {}
    cvs = {}
    for e in entries:
        if e.get("error_occurred"):
            continue
        run = strip_manual(e.get("run_name", e.get("name", "")))
        if run not in order:
            order.append(run)
        if e.get("run_type") == "aggregate":
            agg = e.get("aggregate_name")
            if agg == "median":
                medians[run] = e
            elif agg == "cv":
                cvs[run] = e
        else:
            iterations.setdefault(run, []).append(e)

    rows = []
    for run in order:
        if run in iterations and (len(iterations[run]) > 1 or run not in medians):
            runs = iterations[run]
            row = Row(run, runs[0])
            times = per_process(runs, ns_per_call)
            row.ns = statistics.median(times) if times else None
            row.reps = len(runs)
            row.samples = len(times)
            if len(times) > 1 and row.ns:
                row.cv = statistics.stdev(times) / statistics.mean(times)
            row.add_paired(runs)
        elif run in medians:
            row = Row(run, medians[run])
            row.reps = medians[run].get("repetitions", 1)
            row.samples = row.reps
            cv = cvs.get(run)
            if cv is not None and cv.get("cpu_time") is not None:
                row.cv = cv["cpu_time"]  # a fraction (aggregate_unit "percentage")
        else:
            continue
        rows.append(row)
    rows.sort(key=lambda r: r.order)  # stable: equal keys keep first-seen order
    return context, rows


def load_errors(data):
    """[(run name, error message)] of the benchmarks that skipped with an error (load() drops them)."""
    out = []
    for e in data.get("benchmarks", []):
        if e.get("error_occurred"):
            run = strip_manual(e.get("run_name", e.get("name", "")))
            if run not in [r for r, _ in out]:
                out.append((run, e.get("error_message", "")))
    return out


# ------------------------------------------------------------------------------------------------
# Suites: one per bench_<tech>.cpp, each with its families in registration order


class Suite:
    def __init__(self, name, context, rows, legacy=False):
        key = "raykit_suite:%s:" % name
        self.name = name
        self.rows = rows
        self.title = context.get(key + "title", name)
        self.source = context.get(key + "source", "")
        self.unit = context.get(key + "unit", "call")
        self.about = context.get(key + "about", "")
        self.gpu = context.get(key + "gpu", "")
        self.plot_error = "mean" if context.get(key + "plot_error") == "mean" else "max"
        if legacy:
            baseline_name = context.get("raykit_baseline", DEFAULT_BASELINE)
            listed_plot = context.get("raykit_plot_families")
        else:
            baseline_name = context.get(key + "baseline", "")
            listed_plot = context.get(key + "plot_families")
        self.baseline_name = baseline_name
        self.baseline = next((r for r in rows if r.name == baseline_name and r.ns), None)

        present = []
        for r in rows:
            if r.family not in present:
                present.append(r.family)
        listed = [f for f in context.get(key + "families", "").split(",") if f]
        self.families = [f for f in listed if f in present] + [f for f in present if f not in listed]

        wanted = [f for f in (listed_plot or "").split(",") if f]
        fams = [f for f in wanted if f in present] if listed_plot is not None else present
        self.plot_families = [f for f in fams if any(plottable(r) for r in self.family_rows(f))]

    def family_rows(self, family):
        return [r for r in self.rows if r.family == family]

    def per(self):
        """The unit in a column header: "call" -> "call", "RGB pixel" -> "pixel"."""
        return self.unit.split()[-1] if self.unit.split() else "call"

    def short_name(self):
        """"Fresnel: shaders/raykit/fresnel.glsl" -> "fresnel.glsl" (for the plot's title)."""
        head, _, rest = self.title.partition(":")
        return re.sub(r"[^\s,]*/", "", rest).strip() if rest else head.strip()


def make_suites(context, rows):
    names = [n for n in context.get("raykit_suites", "").split(",") if n]
    legacy = not names
    if legacy:
        names = [DEFAULT_SUITE]
    by_suite = {}
    for r in rows:
        suite = r.suite if r.suite in names or not legacy else DEFAULT_SUITE
        by_suite.setdefault(suite, []).append(r)
    extra = [n for n in by_suite if n not in names]  # benchmarks of suites the context does not describe
    return [Suite(n, context, by_suite[n], legacy) for n in names + extra if n in by_suite]


# ------------------------------------------------------------------------------------------------
# Formatting


def fmt_err(v):
    if v is None:
        return "—"
    if v == 0:
        return "0"
    if math.isinf(v) or math.isnan(v):
        return str(v)
    return "%.2e" % v


def fmt_ns(row):
    if row.ns is None:
        return "—"
    s = "%.2f" % row.ns
    if row.cv is not None:
        s += " ±%.0f%%" % (100.0 * row.cv)
    return s


def fmt_rel(row, base):
    """Relative cost: the paired, harness-subtracted ratio (median of repetitions, with their range);
    for JSON without paired counters, the ratio of the two rows' times."""
    if row.rel is not None:
        med, lo, hi = row.rel
        if hi < 0.05:
            return "< 0.05 (harness level)"
        s = "%.2f" % med
        if row.samples > 1:
            s += " (%.2f–%.2f)" % (lo, hi)
        return s
    return "%.2f" % (row.ns / base.ns) if (base and row.ns and base.ns) else "—"


def fmt_function(text):
    # "rk_x(a, b) [note]" -> `rk_x(a, b)` note
    if "[" in text:
        code, note = text.split("[", 1)
        return "`%s` %s" % (code.strip(), note.rstrip("]").strip())
    return "`%s`" % text


def family_title(context, family):
    return context.get("raykit_family:" + family, family)


def short_title(context, family):
    title = family_title(context, family)
    return title.split(":", 1)[0].strip() if ":" in title else title


def fmt_worst(row):
    if row.worst_rgb is not None:
        return "(%s)" % ", ".join("%.4g" % v for v in row.worst_rgb)
    return "%.4g" % row.worst_at if row.worst_at is not None else "—"


def md_escape(text):
    return text.replace("|", "\\|")


def machine_table(context, rows):
    lines = ["| | |", "|---|---|"]

    def add(key, value):
        lines.append("| %s | %s |" % (key, md_escape(str(value))))

    add("host", context.get("host_name", "?"))
    cpus = context.get("num_cpus", "?")
    mhz = context.get("mhz_per_cpu", "?")
    add("CPUs", "%s × %s MHz (CPU frequency scaling: %s)" % (
        cpus, mhz, "enabled" if context.get("cpu_scaling_enabled") else "disabled"))
    caches = context.get("caches") or []
    if caches:
        parts = []
        for c in caches:
            size = c.get("size", 0)
            size_s = "%d MiB" % (size // 1048576) if size >= 1048576 else "%d KiB" % (size // 1024)
            parts.append("L%s %s %s" % (c.get("level", "?"), c.get("type", ""), size_s))
        add("caches", ", ".join(parts))
    if context.get("load_avg"):
        add("load average at start", ", ".join("%.2f" % v for v in context["load_avg"]))
    add("date", context.get("date", "?"))
    add("raykit build", "%s, %s" % (context.get("raykit_build_type", "?"), context.get("raykit_compiler", "?")))
    add("Google Benchmark library build type", "%s (the harness library as packaged, not the measured code)"
        % context.get("library_build_type", "?"))
    reps = max((r.reps for r in rows), default=1)
    procs = int(context.get("raykit_processes", 1))
    if procs > 1:
        add("repetitions", "%d processes, %d repetition%s each, rows randomly interleaved in each (median "
            "shown; ± and ranges are the spread over the processes)" % (
                procs, max(1, reps // procs), "" if reps // procs <= 1 else "s"))
    else:
        add("repetitions", "%d, randomly interleaved (median shown; ± and ranges are the run-to-run spread)" % reps
            if reps > 1 else "1")
    add("calls per iteration", context.get("raykit_inputs_per_iteration", "?"))
    add("accuracy sweep points", context.get("raykit_sweep_points", "?"))
    return lines


# ------------------------------------------------------------------------------------------------
# Plot


def plottable(r):
    return r.ns is not None and r.max_abs is not None and math.isfinite(r.max_abs)


def point_labels(pts):
    """The variant, or, where a family times a variant more than once, variant/params without the
    parameters all of those rows share; "(exact)" added for zero error (drawn at the axis floor)."""
    labels = []
    for r in pts:
        same = [q for q in pts if q.variant == r.variant]
        text = r.variant
        if len(same) > 1 and r.params:
            common = set.intersection(*(set(q.params.split("/")) for q in same))
            own = [p for p in r.params.split("/") if p not in common]
            text += "/" + "/".join(own) if own else "/" + r.params
        if r.max_abs == 0:
            text += " (exact)"
        labels.append(text)
    return labels


def layout_labels(points, xlo, xhi, ylo, yhi, plot_w_px, plot_h_px):
    """Places one label per point (both axes log) so labels do not overlap each other.

    Returns [(lx, ly, align)] in data coordinates. Greedy: each label goes right of its point
    (left of it near the right edge), moved up or down in line-height steps until its box is free.
    """
    char_w, line_h, gap = 6.8 / plot_w_px, 15.0 / plot_h_px, 10.0 / plot_w_px
    pad_x, pad_y = 9.0 / plot_w_px, 6.0 / plot_h_px  # a point marker's radius plus a little
    lx0, lx1 = math.log10(xlo), math.log10(xhi)

    def nx(x):
        return (math.log10(x) - lx0) / (lx1 - lx0)

    ly0, ly1 = math.log10(ylo), math.log10(yhi)

    def ny(y):
        return (math.log10(y) - ly0) / (ly1 - ly0)

    boxes = []  # placed label boxes (x0, x1, y0, y1) in normalised plot coordinates
    marks = [(nx(x), ny(y)) for x, y, _ in points]
    placed = [None] * len(points)
    for i in sorted(range(len(points)), key=lambda k: (points[k][1], points[k][0])):
        x, y, text = points[i]
        px, py = nx(x), ny(y)
        w = char_w * len(text)
        align = "left" if px + gap + w < 0.98 else "right"
        x0 = px + gap if align == "left" else px - gap - w
        best = None
        for step in range(0, 40):
            for sign in ((0,) if step == 0 else (1, -1)):
                cy = py + sign * step * line_h * 0.5
                if cy < line_h * 0.5 or cy > 1.0 - line_h * 0.5:
                    continue
                box = (x0, x0 + w, cy - line_h * 0.45, cy + line_h * 0.45)
                clash = any(b[0] < box[1] and box[0] < b[1] and b[2] < box[3] and box[2] < b[3] for b in boxes)
                clash = clash or any(
                    j != i and box[0] - pad_x < mx < box[1] + pad_x and box[2] - pad_y < my < box[3] + pad_y
                    for j, (mx, my) in enumerate(marks))
                if not clash:
                    best = (box, cy)
                    break
            if best:
                break
        if best is None:
            best = ((x0, x0 + w, py - line_h * 0.45, py + line_h * 0.45), py)
        boxes.append(best[0])
        ax = best[0][0] if align == "left" else best[0][1]
        lx = 10 ** (lx0 + ax * (lx1 - lx0))
        ly = 10 ** (ly0 + best[1] * (ly1 - ly0))
        placed[i] = (lx, ly, align)
    return placed


def write_plot(context, suite, img_dir):
    fams = suite.plot_families
    if not fams:
        return None
    os.makedirs(img_dir, exist_ok=True)
    dat_path = os.path.join(img_dir, dat_name(suite.name))
    png_path = os.path.join(img_dir, png_name(suite.name))

    ncols = 2 if len(fams) > 1 else 1
    nrows = (len(fams) + ncols - 1) // ncols
    most = max(len([r for r in suite.family_rows(f) if plottable(r)]) for f in fams)
    panel_w, panel_h = (760, 520) if ncols > 1 or most <= 12 else (1100, 760)
    plot_w_px, plot_h_px = panel_w - 150, panel_h - 120

    blocks, panels = [], []
    for fam in fams:
        pts = [r for r in suite.family_rows(fam) if plottable(r)]
        err = (lambda r: r.mean_abs or 0.0) if suite.plot_error == "mean" else (lambda r: r.max_abs)
        errs = [err(r) for r in pts if err(r) > 0]
        floor = min(errs) / 2 if errs else 1e-9
        xs = [max(err(r), floor) for r in pts]
        ys = [r.ns for r in pts]
        xlo = 10 ** math.floor(math.log10(min(xs)) - 0.3)
        xhi = 10 ** math.ceil(math.log10(max(xs)) + 0.3)
        ylo = 10 ** math.floor(math.log10(min(ys) / 1.3))
        yhi = max(ys) * 2.0
        texts = point_labels(pts)
        labels = layout_labels(list(zip(xs, ys, texts)), xlo, xhi, ylo, yhi, plot_w_px, plot_h_px)
        lines = ["# family %s: %s" % (fam, family_title(context, fam)),
                 "# %s_abs_err ns_per_call label_x label_y align(0 left, 1 right) label cross(1: error vs another formula)"
                 % suite.plot_error]
        for x, y, r, text, (lx, ly, align) in zip(xs, ys, pts, texts, labels):
            lines.append("%.6e %.6f %.6e %.6f %d \"%s\" %d" % (
                x, y, lx, ly, 0 if align == "left" else 1, text, 1 if "cross" in r.flags else 0))
        blocks.append("\n".join(lines))
        panels.append((fam, xlo, xhi, ylo, yhi, any("cross" in r.flags for r in pts)))

    with open(dat_path, "w", encoding="utf-8") as f:
        f.write("# raykit_bench %s: speed vs error, written by scripts/bench_report.py (one block per family)\n"
                % suite.name)
        f.write("\n\n\n".join(blocks) + "\n")

    if shutil.which("gnuplot") is None:
        print("bench_report: warning: gnuplot not found on PATH, %s not drawn" % png_name(suite.name), file=sys.stderr)
        return None

    def q(text):
        return text.replace("'", "''")

    g = []
    g.append("set terminal pngcairo size %d,%d font 'Sans,10' enhanced" % (panel_w * ncols, panel_h * nrows))
    g.append("set output '%s'" % q(png_path))
    g.append("set multiplot layout %d,%d title '%s' font 'Sans,13' noenhanced" % (nrows, ncols, q(
        "raykit %s: CPU time per %s vs %s abs error (median of repetitions; CPU times are ratios only)"
        % (suite.short_name(), suite.unit, suite.plot_error))))
    g.append("set logscale xy")
    g.append("set format x '10^{%L}'")
    g.append("set grid xtics ytics mytics lc rgb '#dddddd'")
    g.append("set ytics (0.5, 1, 2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100, 150, 200, 300, 500, 1000)")
    g.append("set xlabel '%s abs error vs %s (log scale)'" % (
        suite.plot_error, "the exact reference" if suite.plot_error == "mean" else "float64 reference"))
    g.append("set ylabel 'ns / %s (CPU, log scale)'" % q(suite.unit))
    g.append("set tmargin 3")
    dat = q(dat_path)
    for idx, (fam, xlo, xhi, ylo, yhi, cross) in enumerate(panels):
        g.append("set title '%s' font 'Sans,11' noenhanced" % q(short_title(context, fam)))
        g.append("set xrange [%g:%g]" % (xlo, xhi))
        g.append("set yrange [%g:%g]" % (ylo, yhi))
        g.append("set key bottom right box opaque font 'Sans,9' noenhanced" if cross else "set key off")
        g.append(
            "plot '{d}' index {i} using 1:(abs($4/$2-1) > 0.01 ? $2 : 1/0):($3-$1):($4-$2) "
            "with vectors nohead lc rgb '#aaaaaa' notitle, \\\n"
            "  '{d}' index {i} using 1:($7 == 0 ? $2 : 1/0) with points pt 7 ps 1.3 lc rgb '#1f77b4' "
            "title 'error vs its own formula', \\\n"
            "  '{d}' index {i} using 1:($7 == 1 ? $2 : 1/0) with points pt 5 ps 1.3 lc rgb '#ff7f0e' "
            "title 'error vs another formula (cross-reference, see table)', \\\n"
            "  '{d}' index {i} using 3:($5 == 0 ? $4 : 1/0):6 with labels left font 'Sans,9' noenhanced notitle, \\\n"
            "  '{d}' index {i} using 3:($5 == 1 ? $4 : 1/0):6 with labels right font 'Sans,9' noenhanced notitle"
            .format(d=dat, i=idx))
    g.append("unset multiplot")
    script = "\n".join(g) + "\n"
    res = subprocess.run(["gnuplot"], input=script, text=True, capture_output=True)
    if res.returncode != 0 or not os.path.exists(png_path):
        print("bench_report: warning: gnuplot failed:\n" + res.stderr, file=sys.stderr)
        return None
    if res.stderr.strip():
        print("bench_report: gnuplot said:\n" + res.stderr, file=sys.stderr)
    return png_path


# ------------------------------------------------------------------------------------------------
# Octree build (bench/bench_svo.cpp): rows BM_svo/<mesh>/depth:<d>/threads:<t>[/...] with size and
# memory counters instead of an error; one table per mesh, a time / bytes-per-voxel plot and the
# thesis's goals, each said to be met, missed or not measured.

SVO_PNG = "bench_svo_build.png"
SVO_DAT = "bench_svo_build.dat"
SVO_ONE_K = "figure"          # the ~1k-triangle mesh (thesis: a 1,027-triangle character in its bounding cube)
SVO_ONE_K_DENSE = "icosphere3"  # ~1k triangles filling their cube: about 4x the voxels, the worst case
SVO_ONE_K_COLOUR = "figure_colour"  # the figure with the colour stream only, as the thesis stores
SVO_ONE_K_SMOOTH = "figure_smooth"  # the figure with vertex normals: the builder's general (clipping) path
SVO_SEVENTY_K = "uvsphere256"  # the ~70k-triangle mesh
SVO_GOAL_1K_S = 0.5
SVO_GOAL_70K_S = 3.0
SVO_GOAL_DEPTH13_BYTES = 4e9
SVO_THESIS_S, SVO_THESIS_MB = 14.9, 113.0

TIME_UNITS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def is_octree_suite(suite):
    return any("bytes_thesis" in r.entry for r in suite.rows)


class SvoRow:
    """One octree build row: mesh, depth, threads, wall seconds and the counters."""

    def __init__(self, row):
        self.row = row
        e = row.entry
        self.mesh = row.variant
        m = re.search(r"/depth:(\d+)", row.name)
        self.depth = int(m.group(1)) if m else None
        m = re.search(r"/threads:(\d+)", row.name)
        self.threads = int(m.group(1)) if m else None
        t = e.get("real_time")
        self.seconds = t * TIME_UNITS.get(e.get("time_unit", "ns"), 1e-9) if t is not None else None
        if e.get("seconds_median"):
            self.seconds = e["seconds_median"]  # median over iterations, where the bench recorded it
        self.c = e

    def get(self, key):
        return self.c.get(key)


def svo_parse_name(name):
    """(mesh, depth, threads) of a BM_svo/... run name, for skipped rows."""
    parts = name.split("/")
    mesh = parts[1] if len(parts) > 1 else name
    d = re.search(r"/depth:(\d+)", name)
    t = re.search(r"/threads:(\d+)", name)
    return mesh, int(d.group(1)) if d else None, int(t.group(1)) if t else None


class SvoData:
    def __init__(self, context, suite, errors):
        self.context = context
        self.rows = [SvoRow(r) for r in suite.rows if r.entry.get("bytes_thesis") is not None]
        listed = [m for m in context.get("raykit_svo:meshes", "").split(",") if m]
        present = []
        for r in self.rows:
            if r.mesh not in present:
                present.append(r.mesh)
        prefix = "BM_%s/" % suite.name
        self.skipped = [(n, msg) for n, msg in errors if n.startswith(prefix)]
        for n, _ in self.skipped:
            m = svo_parse_name(n)[0]
            if m not in present:
                present.append(m)
        self.meshes = [m for m in listed if m in present] + [m for m in present if m not in listed]

    def find(self, mesh, depth, threads):
        return next((r for r in self.rows if r.mesh == mesh and r.depth == depth and r.threads == threads), None)

    def depths(self, mesh):
        ds = set(r.depth for r in self.rows if r.mesh == mesh and r.depth is not None)
        ds |= set(d for n, _ in self.skipped for m, d, _t in [svo_parse_name(n)] if m == mesh and d is not None)
        return sorted(ds)

    def any_row(self, mesh, depth):
        """The 1-thread row, else any row of that mesh and depth (size counters do not depend on threads)."""
        r = self.find(mesh, depth, 1)
        return r or next((x for x in self.rows if x.mesh == mesh and x.depth == depth), None)

    def mesh_title(self, mesh):
        return self.context.get("raykit_svo:mesh:" + mesh, mesh)

    def skip_reason(self, mesh, depth, threads):
        for n, msg in self.skipped:
            if svo_parse_name(n) == (mesh, depth, threads):
                return re.sub(r"^skipped:\s*", "", msg)
        return None


def fmt_seconds(s):
    if s is None:
        return "—"
    if s >= 1.0:
        return "%.2f s" % s
    if s >= 0.01:
        return "%.0f ms" % (s * 1e3)
    return "%.1f ms" % (s * 1e3)


def fmt_mb(b):
    if b is None:
        return "—"
    if b == 0:
        return "0"
    mb = b / 1e6
    return "%.0f" % mb if mb >= 100 else ("%.1f" % mb if mb >= 1 else "%.2f" % mb)


def fmt_count(v):
    if v is None:
        return "—"
    v = float(v)
    if v >= 1e6:
        return "%.2f M" % (v / 1e6)
    if v >= 1e3:
        return "%.1f k" % (v / 1e3)
    return "%.0f" % v


def fmt_f(v, digits=2):
    return "—" if v is None else ("%." + str(digits) + "f") % v


def svo_time(data, mesh, depth, threads):
    """Wall seconds of a build: the row's own time, else the paired median of the 2-thread row."""
    r = data.find(mesh, depth, threads)
    if r is not None and r.seconds is not None:
        return r.seconds
    if threads == 1:
        p = data.find(mesh, depth, 2)
        if p is not None and p.get("t1_paired_s"):
            return p.get("t1_paired_s")
    return None


def svo_measured_peak(r):
    """The larger of the builder's accounting and the RSS rise (bytes), None without a row."""
    if r is None:
        return None
    vals = [v for v in (r.get("peak_bytes"), r.get("rss_peak_bytes")) if v]
    return max(vals) if vals else None


def write_svo_plot(data, img_dir):
    if not data.rows:
        return None
    os.makedirs(img_dir, exist_ok=True)
    dat_path = os.path.join(img_dir, SVO_DAT)
    png_path = os.path.join(img_dir, SVO_PNG)

    def v(x):
        return "?" if x is None else "%.6g" % x

    blocks = []
    for mesh in data.meshes:
        lines = ["# mesh %s: %s" % (mesh, data.mesh_title(mesh)),
                 "# depth seconds_1T seconds_2T B_struct_per_voxel B_color_per_voxel B_attr_per_voxel "
                 "B_thesis_per_voxel"]
        for d in data.depths(mesh):
            r = data.any_row(mesh, d)
            vox = r.get("voxels") if r else None
            thesis = r.get("bytes_thesis") / vox if (r and vox) else None
            lines.append("%d %s %s %s %s %s %s" % (
                d, v(svo_time(data, mesh, d, 1)), v(svo_time(data, mesh, d, 2)),
                v(r.get("B_struct_per_voxel") if r else None), v(r.get("B_color_per_voxel") if r else None),
                v(r.get("B_attr_per_voxel") if r else None), v(thesis)))
        blocks.append("\n".join(lines))
    with open(dat_path, "w", encoding="utf-8") as f:
        f.write("# raykit_bench svo: octree build time and bytes per voxel vs depth, written by "
                "scripts/bench_report.py (one block per mesh)\n")
        f.write("\n\n\n".join(blocks) + "\n")

    if shutil.which("gnuplot") is None:
        print("bench_report: warning: gnuplot not found on PATH, %s not drawn" % SVO_PNG, file=sys.stderr)
        return None

    def q(text):
        return text.replace("'", "''")

    colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"]
    depths = sorted(set(d for m in data.meshes for d in data.depths(m)))
    dlo, dhi = min(depths[0], 6) - 0.3, max(depths[-1], 11) + 0.3  # the anchors are at depth 11
    dat = q(dat_path)
    g = ["set terminal pngcairo size 1500,760 font 'Sans,10' enhanced",
         "set output '%s'" % q(png_path),
         "set datafile missing '?'",
         "set multiplot layout 1,2 title 'raykit octree build (build\\_svo, surface, colour + normal + material): "
         "wall time and bytes per voxel vs depth' font 'Sans,13'",
         "set logscale y",
         "set grid xtics ytics mytics lc rgb '#dddddd'",
         "set xlabel 'depth (levels below the root)' offset 0,0.5",
         "set bmargin 10",
         "set xtics 1",
         "set xrange [%g:%g]" % (dlo, dhi),
         "set key below box font 'Sans,9' noenhanced samplen 4",
         # Left: time.
         "set title 'build time (wall clock; solid 1 thread, dashed 2 threads)' font 'Sans,11'",
         "set ylabel 'seconds (log scale)'",
         "set format y '%g'"]
    plots = []
    for i, mesh in enumerate(data.meshes):
        c = colours[i % len(colours)]
        plots.append("'%s' index %d using 1:2 with linespoints lw 2 pt 7 lc rgb '%s' dt 1 title '%s'" % (dat, i, c, q(mesh)))
        plots.append("'%s' index %d using 1:3 with linespoints lw 2 pt 5 lc rgb '%s' dt 2 notitle" % (dat, i, c))
    plots.append("'-' using 1:2 with points pt 9 ps 2 lc rgb 'black' title 'thesis: 1,027 triangles, depth 11, 14.9 s'")
    plots.append("'-' using 1:2 with points pt 6 ps 2 lw 2 lc rgb '%s' title 'goal: ~1k triangles, depth 11, 0.5 s (2 cores)'" % colours[0])
    plots.append("'-' using 1:2 with points pt 4 ps 2 lw 2 lc rgb '%s' title 'goal: ~70k triangles, depth 11, 3 s (2 cores)'" % colours[2 % len(colours)])
    g.append("plot " + ", \\\n  ".join(plots))
    g += ["11 %g" % SVO_THESIS_S, "e", "11 %g" % SVO_GOAL_1K_S, "e", "11 %g" % SVO_GOAL_70K_S, "e"]
    # Right: bytes per voxel.
    g += ["set title 'bytes per leaf voxel (solid structure, dashed colour, dotted all attributes, thin thesis format)' font 'Sans,11'",
          "set ylabel 'bytes / voxel (log scale)'"]
    plots = []
    for i, mesh in enumerate(data.meshes):
        c = colours[i % len(colours)]
        plots.append("'%s' index %d using 1:4 with linespoints lw 2 pt 7 lc rgb '%s' dt 1 title '%s'" % (dat, i, c, q(mesh)))
        plots.append("'%s' index %d using 1:5 with linespoints lw 2 pt 5 lc rgb '%s' dt 2 notitle" % (dat, i, c))
        plots.append("'%s' index %d using 1:6 with linespoints lw 2 pt 13 lc rgb '%s' dt 3 notitle" % (dat, i, c))
        plots.append("'%s' index %d using 1:7 with lines lw 1 lc rgb '%s' dt 1 notitle" % (dat, i, c))
    plots.append("1 with lines lw 2 lc rgb 'black' dt 4 title 'ESVO ~1 B/voxel (goal: structure <= 1 at depth >= 10)'")
    g.append("plot " + ", \\\n  ".join(plots))
    g.append("unset multiplot")
    res = subprocess.run(["gnuplot"], input="\n".join(g) + "\n", text=True, capture_output=True)
    if res.returncode != 0 or not os.path.exists(png_path):
        print("bench_report: warning: gnuplot failed:\n" + res.stderr, file=sys.stderr)
        return None
    if res.stderr.strip():
        print("bench_report: gnuplot said:\n" + res.stderr, file=sys.stderr)
    return png_path


def svo_goals(data):
    """Markdown bullets: each of the thesis-derived goals, met / MISSED / not measured, with numbers."""
    out = []
    deep = [r for r in data.rows if r.depth is not None and r.depth >= 10]
    max_depth = max((r.depth for r in data.rows if r.depth is not None), default=None)
    not_run = "not measured in this run (depths up to %s; `RAYKIT_BENCH_SVO_FULL=1` runs 6..11, 12..13 for %s)" % (
        max_depth, SVO_ONE_K)

    def verdict(ok):
        return "**met**" if ok else "**missed**"

    def span(lo, hi):
        return "%.3f" % lo if "%.3f" % lo == "%.3f" % hi else "%.3f to %.3f" % (lo, hi)

    def absent(mesh, depth, value=None, goal=None, unit=""):
        """Why a goal's row is missing, plus, where value(row) is given, an extrapolation from the
        deepest measured depth, if within two levels (x4 per level: surface voxels grow as the square of
        the resolution; shallower rows are dominated by per-triangle work)."""
        why = data.skip_reason(mesh, depth, 2) or data.skip_reason(mesh, depth, 1)
        text = ("not measured: skipped, " + why) if why else not_run
        if value is not None:
            known = [(d, value(d)) for d in data.depths(mesh) if depth - 2 <= d < depth and value(d)]
            if known:
                d0, v0 = known[-1]
                guess = v0 * 4.0 ** (depth - d0)
                text += "; extrapolated x4 per level from depth %d: ~%s%s (%s)" % (
                    d0, "%.3g" % guess, unit, "would miss" if guess > goal else "would meet")
        return text

    # 1. Structure bytes per voxel.
    if deep:
        worst = max(deep, key=lambda r: r.get("B_struct_per_voxel") or 0)
        w = worst.get("B_struct_per_voxel")
        out.append("- Structure <= 1 B/voxel at depth >= 10: %s — at most %.3f B/voxel (%s, depth %d) over %d rows."
                   % (verdict(w <= 1.0), w, worst.mesh, worst.depth, len(deep)))
    else:
        out.append("- Structure <= 1 B/voxel at depth >= 10: " + not_run + ".")
    # 2. Bytes against the thesis.
    pool_all = deep or data.rows
    # Trees with shared sub-node attributes (the compact level of detail) are reported apart.
    pool = [r for r in pool_all if not r.mesh.endswith("_shared")]
    shared = [r for r in pool_all if r.mesh.endswith("_shared")]
    if pool:
        ratios = [r.get("thesis_ratio") for r in pool if r.get("thesis_ratio") is not None]
        alls = [(r.get("bytes_total") / r.get("bytes_thesis")) for r in pool
                if r.get("bytes_total") is not None and r.get("bytes_thesis")]
        out.append("- <= 1/4 of the thesis's bytes for the same tree (structure + colour, as the thesis stores): %s — "
                   "%s at depth %s%s with every level's attributes; with colour + normal + material %s." % (
                       verdict(max(ratios) <= 0.25), span(min(ratios), max(ratios)),
                       ">= 10" if deep else "6..%s" % max_depth, "" if deep else " (deeper rows not run)",
                       span(min(alls), max(alls))))
    if shared:
        sr = [r.get("thesis_ratio") for r in shared if r.get("thesis_ratio") is not None]
        if sr:
            out.append("- The same with shared sub-node attributes (SvoBuildOptions::shared_sub_attributes: a stop at "
                       "level depth-1 reads its brick's colour): %s — %s." % (verdict(max(sr) <= 0.25), span(min(sr), max(sr))))
    # 3, 4. Build times on 2 cores at depth 11.
    for mesh, goal, what in ((SVO_ONE_K_COLOUR, SVO_GOAL_1K_S, "~1k triangles, colour only as in the thesis"),
                             (SVO_ONE_K, SVO_GOAL_1K_S, "~1k triangles, colour + normal + material"),
                             (SVO_ONE_K_SMOOTH, SVO_GOAL_1K_S, "~1k triangles, all streams, smooth vertex normals"),
                             (SVO_ONE_K_DENSE, SVO_GOAL_1K_S, "~1k triangles, sphere filling its cube"),
                             (SVO_SEVENTY_K, SVO_GOAL_70K_S, "~70k triangles")):
        t = svo_time(data, mesh, 11, 2)
        if t is None:
            out.append("- %s (%s) at depth 11 <= %g s on 2 cores: %s." % (
                what, mesh, goal, absent(mesh, 11, lambda d, m=mesh: svo_time(data, m, d, 2), goal, " s")))
        else:
            t1 = svo_time(data, mesh, 11, 1)
            out.append("- %s (%s) at depth 11 <= %g s on 2 cores: %s — %s with 2 threads%s (%.1fx the goal)." % (
                what, mesh, goal, verdict(t <= goal), fmt_seconds(t),
                ", %s with 1" % fmt_seconds(t1) if t1 else "", t / goal))
            r11 = data.find(mesh, 11, 2)
            nonleaf = r11.get("nonleaf_nodes") if r11 is not None else None
            if mesh in (SVO_ONE_K, SVO_ONE_K_DENSE) and nonleaf:
                # The thesis's file, 4 + 8 (1 + 8 N) bytes, gives its N non-leaf nodes; the build time
                # grows with the tree, so scale ours to a tree of the thesis's size.
                thesis_nonleaf = (SVO_THESIS_MB * 1e6 - 12.0) / 64.0
                k = thesis_nonleaf / nonleaf
                out.append("  The thesis's depth-11 tree (%.0f MB in its format) has %.2f M non-leaf nodes, %.2fx this "
                           "mesh's %.2f M: scaled by that, a tree of the thesis's size would take about %s on 2 threads (%s)."
                           % (SVO_THESIS_MB, thesis_nonleaf / 1e6, k, nonleaf / 1e6, fmt_seconds(t * k),
                              "within the goal" if t * k <= goal else "%.2fx the goal" % (t * k / goal)))
    # 5. Depth 13 memory.
    for one_k in (SVO_ONE_K, SVO_ONE_K_DENSE):
        r13 = data.find(one_k, 13, 2) or data.find(one_k, 13, 1)
        if r13 is not None:
            peak = svo_measured_peak(r13)
            out.append("- Depth 13 (%s) within 4 GB: %s — measured peak %s GB (builder %s GB, RSS rise %s GB), estimate %s GB."
                       % (one_k, verdict(peak is not None and peak <= SVO_GOAL_DEPTH13_BYTES),
                          "%.2f" % (peak / 1e9) if peak else "—", "%.2f" % (r13.get("peak_bytes") / 1e9),
                          "%.2f" % (r13.get("rss_peak_bytes") / 1e9), "%.2f" % (r13.get("est_peak_bytes") / 1e9)))
        else:
            def peak_gb(d):
                p = svo_measured_peak(data.find(one_k, d, 2) or data.find(one_k, d, 1))
                return p / 1e9 if p else None

            out.append("- Depth 13 (%s) within 4 GB: %s." % (
                one_k, absent(one_k, 13, peak_gb, SVO_GOAL_DEPTH13_BYTES / 1e9, " GB peak")))
    return out


def svo_section(context, suite, errors, png):
    """The "Octree build" section (Markdown lines) for the suite of bench/bench_svo.cpp."""
    data = SvoData(context, suite, errors)
    md = ["## " + suite.title, ""]
    loads = [r.get("load_avg_1m") for r in data.rows if r.get("load_avg_1m") is not None and r.get("load_avg_1m") >= 0]
    load_text = ""
    if loads:
        load_text = " The 1-minute load average after the rows ranged from %.2f to %.2f on %s CPUs" % (
            min(loads), max(loads), context.get("num_cpus", "?"))
        ncpu = context.get("num_cpus")
        if isinstance(ncpu, (int, float)) and max(loads) > ncpu:
            load_text += ": above the CPU count other jobs competed for the cores, which slows 2-thread builds most."
        else:
            load_text += " (not above the CPU count)."
    md.append("Source: `%s`. Machine: %s CPUs (see [Machine](#machine)); the times are wall clock and depend on "
              "what else the machine runs.%s" % (suite.source or "bench/bench_svo.cpp", context.get("num_cpus", "?"),
                                                   load_text))
    md.append("")
    if suite.about:
        md.append(suite.about)
        md.append("")
    # Thesis anchors and the goals.
    t11 = svo_time(data, SVO_ONE_K, 11, 2)
    r11 = data.any_row(SVO_ONE_K, 11)
    ours = ""
    if t11 is not None and r11 is not None:
        ours = (" The ~1k-triangle mesh here (%s) at depth 11: %s on 2 threads, %s MB structure + colour "
                "(%s MB with normals and materials)." % (
                    SVO_ONE_K, fmt_seconds(t11), fmt_mb(r11.get("bytes_struct") + r11.get("bytes_color")),
                    fmt_mb(r11.get("bytes_total"))))
    md.append("Anchors: Gritzner, *3D graphics rendering using a polygon-voxel-hybrid approach*, builds a 1,027-triangle "
              "mesh at depth 11 in %.1f s into a %.0f MB file (its format: 4 + 8 (1 + 8 N) bytes for N non-leaf "
              "nodes); Laine and Karras's efficient sparse voxel octrees (ESVO) need about 1 byte of structure per "
              "voxel.%s Goals derived from them:" % (SVO_THESIS_S, SVO_THESIS_MB, ours))
    md.append("")
    md.extend(svo_goals(data))
    md.append("")
    if data.rows:
        md.append("### Build time and bytes per voxel vs depth")
        md.append("")
        if png:
            md.append("![octree build time and bytes per voxel vs depth](img/%s)" % SVO_PNG)
        else:
            md.append("_(plot not drawn: gnuplot was not available when this report was generated)_")
        md.append("")
    for mesh in data.meshes:
        md.append("### " + md_escape(data.mesh_title(mesh)))
        md.append("")
        md.append("| depth | voxels | time 1T | time 2T | speed-up (paired) | Mvoxels/s (2T) | B/voxel structure "
                  "| B/voxel colour | B/voxel all attr. | total MB | thesis MB | vs thesis | peak MB est. / builder / RSS |")
        md.append("|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
        notes = []
        for d in data.depths(mesh):
            r = data.any_row(mesh, d)
            r2 = data.find(mesh, d, 2)
            for t in (1, 2):
                why = data.skip_reason(mesh, d, t)
                if why:
                    notes.append("depth %d, %d thread%s: %s" % (d, t, "" if t == 1 else "s", why))
            if r is None:
                md.append("| %d | — | — | — | — | — | — | — | — | — | — | — | (skipped) |" % d)
                continue
            pr = r2 or r
            speed = r2.get("speedup_paired") if r2 is not None else None
            t2 = svo_time(data, mesh, d, 2)
            vps = r.get("voxels") / t2 if (t2 and r.get("voxels")) else None
            md.append("| %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s / %s |" % (
                d, fmt_count(r.get("voxels")), fmt_seconds(svo_time(data, mesh, d, 1)),
                fmt_seconds(svo_time(data, mesh, d, 2)),
                "%.2f (%d pair%s)" % (speed, r2.get("pairs"), "" if r2.get("pairs") == 1 else "s") if speed else "—",
                fmt_f(vps / 1e6 if vps else None), fmt_f(r.get("B_struct_per_voxel"), 3),
                fmt_f(r.get("B_color_per_voxel")), fmt_f(r.get("B_attr_per_voxel")), fmt_mb(r.get("bytes_total")),
                fmt_mb(r.get("bytes_thesis")), fmt_f(r.get("thesis_ratio"), 3),
                fmt_mb(pr.get("est_peak_bytes")), fmt_mb(pr.get("peak_bytes")), fmt_mb(pr.get("rss_peak_bytes"))))
        md.append("")
        if notes:
            md.append("Skipped: " + "; ".join(md_escape(n) for n in notes) + ".")
            md.append("")
    return md


# ------------------------------------------------------------------------------------------------
# Markdown


def paragraph(text):
    """A family title's details as a sentence: capitalised, with a full stop."""
    text = text.strip()
    if not text:
        return ""
    return text[0].upper() + text[1:] + ("" if text.endswith(".") else ".")


def interior_summary(out_dir, page="benchmarks_interior.md", heading=True):
    """The interior-mapping frame-time summary, quoted from benchmarks_interior.md (written by
    scripts/bench_interior.sh), so that this page shows the ratios without a second source; with
    page="benchmarks_interior_gpu.md", the same from a GPU run (scripts/bench_gpu.sh)."""
    md = ["## Interior mapping: frame time against a plain material", ""] if heading else []
    if heading:
        md.append("Interior mapping is measured as whole frames on the GL driver, not per call "
                  "([benchmarks_interior.md](benchmarks_interior.md), `bash scripts/bench_interior.sh`: "
                  "the scene, the method, per-feature costs, the depth pre-pass, 10^3 to 4*10^6 rooms and "
                  "SPIR-V counts).")
        md.append("")
    path = os.path.join(out_dir, page)
    if not os.path.exists(path):
        md.append("(Not measured yet: run `bash scripts/bench_interior.sh`.)" if heading else
                  "(No GPU run reported yet: `bash scripts/bench_gpu.sh` on a machine with a GPU.)")
        md.append("")
        return md
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    renderer = next((l for l in lines if l.startswith("**Renderer")), None)
    if renderer:
        md.append(renderer)
        md.append("")
    start = next((i for i, l in enumerate(lines) if l.startswith("Summary (")), None)
    if start is None:
        md.append("(benchmarks_interior.md has no summary section.)")
        md.append("")
        return md
    md.append(lines[start])
    md.append("")
    i = start + 1
    while i < len(lines) and not lines[i].strip():
        i += 1
    while i < len(lines) and lines[i].strip():
        md.append(lines[i])
        i += 1
    md.append("")
    if heading:
        md.append("The same on a GPU, from [benchmarks_interior_gpu.md](benchmarks_interior_gpu.md) "
                  "(`scripts/bench_gpu.sh`, reported by `scripts/bench_interior.sh`; absolute times there):")
        md.append("")
        md.extend(interior_summary(out_dir, "benchmarks_interior_gpu.md", heading=False))
    return md


def quoted_summary(out_dir, page, heading, intro, script):
    """A driver benchmark's results quoted from its own page (written by `script`): from its
    **Renderer** line to the line before "What the data show" (or the end)."""
    md = ["## " + heading, "", intro, ""]
    path = os.path.join(out_dir, page)
    if not os.path.exists(path):
        md.append("(Not measured yet: run `bash %s`.)" % script)
        md.append("")
        return md
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    start = next((i for i, l in enumerate(lines) if l.startswith("**Renderer")), None)
    end = next((i for i, l in enumerate(lines) if l.startswith("What the data show")), len(lines))
    if start is None:
        md.append("(%s has no results.)" % page)
        md.append("")
        return md
    md.extend(lines[start:end])
    return md


def deferred_summary(out_dir):
    """Forward against deferred frame time by light count (benchmarks_deferred.md, written by
    scripts/bench_deferred.sh from samples/deferred_city --bench)."""
    return quoted_summary(
        out_dir, "benchmarks_deferred.md",
        "Deferred shading: forward against deferred by light count, G-buffer bytes per pixel",
        "Whole frames of the deferred city on the GL driver ([benchmarks_deferred.md](benchmarks_deferred.md), "
        "`bash scripts/bench_deferred.sh`; what they show: [deferred.md](deferred.md)).",
        "scripts/bench_deferred.sh")


def volumes_summary(out_dir):
    """The thesis's volume protocol (benchmarks_volumes.md, written by scripts/bench_volumes.sh from
    samples/effects --bench)."""
    return quoted_summary(
        out_dir, "benchmarks_volumes.md",
        "Volumes: billboards, slices and raytraced soft particles (the thesis's protocol)",
        "Whole frames on the GL driver as ratios to the billboard frame, next to van Dongen's figure 6.23 "
        "([benchmarks_volumes.md](benchmarks_volumes.md), `bash scripts/bench_volumes.sh`; what they show: "
        "[volume.md](volume.md)).",
        "scripts/bench_volumes.sh")

def gpu_figures_line(out_dir):
    """Which pages hold figures from a GPU (those scripts/bench_gpu.sh writes), which of them this
    page quotes, and that the function micro-benchmarks' CPU times are ratios only."""
    known = (("interior mapping's frame times", "benchmarks_interior_gpu.md", True),
             ("the octree voxel pass", "benchmarks_svo_gl_gpu.md", True),
             ("forward against deferred shading", "benchmarks_deferred_gpu.md", False),
             ("the volume techniques", "benchmarks_volumes_gpu.md", False))
    pages = [(name, page, quoted) for name, page, quoted in known if os.path.exists(os.path.join(out_dir, page))]
    if not pages:
        return "None were recorded yet on a GPU. The CPU times above are ratios only."

    def listing(items):
        return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]

    line = "Recorded on a GPU (its name heads each page): " + listing([f"{n} ([{p}]({p}))" for n, p, _ in pages])
    quoted = [n for n, _, q in pages if q]
    if quoted:
        line += "; " + listing(quoted) + (" are" if len(quoted) > 1 else " is") + " quoted in " + \
            ("their sections" if len(quoted) > 1 else "its section") + " above"
    return line + ". None yet for the per-function benchmarks on this page, whose CPU times are ratios only; what carries over to a GPU:"


def svo_gl_gpu_summary(out_dir):
    """The GPU frame times and ray rates of the voxel pass, quoted from benchmarks_svo_gl_gpu.md (a
    run of bench_svo_gl on a GPU by scripts/bench_gpu.sh, reported by scripts/bench_svo_gl.sh)."""
    path = os.path.join(out_dir, "benchmarks_svo_gl_gpu.md")
    if not os.path.exists(path):
        return ["(No GPU run reported yet: `bash scripts/bench_gpu.sh` on a machine with a GPU.)", ""]
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    renderer = next((l.split("**")[1] for l in lines if l.startswith("**") and l.count("**") >= 2), "?")
    rows = {}
    for l in lines:
        cells = [c.strip() for c in l.strip().strip("|").split("|")] if l.startswith("| ") else []
        if len(cells) >= 7 and cells[1].isdigit():
            rows[(cells[0], int(cells[1]), cells[2], cells[3])] = cells
    md = ["On a GPU (**%s**, [benchmarks_svo_gl_gpu.md](benchmarks_svo_gl_gpu.md): every depth, both sizes, "
          "LOD errors and the plot): frame milliseconds (median) of the fragment voxel pass at full detail "
          "and with 4-pixel LOD, of the same rays traced in a compute shader, and of rasterising the mesh; "
          "Mrays/s counts the rays that enter the root cube. Where the compute pass is far faster than the "
          "fragment pass, the fragment pipeline bounds the voxel pass, not the traversal (an H100 or H200 "
          "runs pixel shaders on 2 of its 66 TPCs). Gritzner's thesis: 21.6 ms at 1280x720, depth 11, "
          "on a 2013 GPU; Wilks's: about 64 Mrays/s on a GTX 670." % renderer, ""]
    md.append("| mesh | depth | size | voxel pass ms | lod4 ms | compute ms | raster ms | Mrays/s fragment | Mrays/s compute |")
    md.append("|---|---:|---|---:|---:|---:|---:|---:|---:|")
    for key in rows:
        mesh, depth, size, config = key
        if config != "voxels":
            continue
        def ms(c):
            r = rows.get((mesh, depth, size, c))
            return r[4].split(" ")[0] if r else "-"
        def rate(c):
            r = rows.get((mesh, depth, size, c))
            return r[6].split(";")[-1].strip() if r and ";" in r[6] else "-"
        md.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s |" % (mesh, depth, size, ms("voxels"), ms("lod4"),
                                                                  ms("compute"), ms("raster"), rate("voxels"), rate("compute")))
    md.append("")
    return md


def svo_trace_summary(out_dir):
    """Octree ray casting: the CPU throughput summary quoted from benchmarks_trace.md (written by
    scripts/bench_trace_report.py) and the driver frame-time page (benchmarks_svo_gl.md)."""
    md = ["## Octree ray casting: CPU throughput against Embree and OpenVDB, frame time on the driver", ""]
    md.append("`rk_svo_trace` (the C++ build of `svo_traverse.glsl`), `svo_trace_rays` (its loop on 8 AVX2 "
              "lanes, the same answers bit for bit) and `svo_trace_packets` (pixel tiles sharing one traversal: 8x4 on AVX-512, else 4x4 on AVX2) against Embree on the source triangles and "
              "OpenVDB's level-set ray intersector, 512x512 primary rays, single thread "
              "([benchmarks_trace.md](benchmarks_trace.md), `bash scripts/bench_trace.sh`; every depth 8-12, "
              "2 threads, build times, hit agreement). Embree is timed two ways: single rays (`rtcIntersect1`, "
              "the form issue 11's reference figures come from) and its coherent stream (`rtcIntersect1M` "
              "over 4x4 pixel tiles with the coherent flag: its packets, the fair peer of raykit's). Issue 11's "
              "goals: at least 5x OpenVDB and at least Embree's speed. *best* is the fastest full-detail raykit "
              "row; the LOD columns are the packets in a level-of-detail build stopping at nodes one pixel wide "
              "(a coarser answer: the hits of the tree whose voxels match the pixels) on the depth-12 tree.")
    md.append("")
    path = os.path.join(out_dir, "benchmarks_trace.md")
    if not os.path.exists(path):
        md.append("(Not measured yet: run `bash scripts/bench_trace.sh`.)")
        md.append("")
    else:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        table = ["| mesh | Embree Mrays/s | Embree coherent | OpenVDB d10 | raykit d10 | raykit SIMD d10 | raykit packets d10 | best / OpenVDB | best / Embree | best / Embree coherent | 1-px LOD d12 / Embree | 1-px LOD d12 / Embree coherent |",
                 "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        # Per mesh, the single-thread Mrays/s cell of each (row name, depth) of its table.
        meshes = []
        for l in lines:
            if l.startswith("## "):
                meshes.append((l[3:].strip(), {}))
            cells = [c.strip() for c in l.strip().strip("|").split("|")] if l.startswith("|") else []
            if meshes and len(cells) > 3:
                meshes[-1][1][(cells[0], cells[1])] = cells[2]
        for mesh, cell in meshes:
            e, ec = cell.get(("Embree", "—")), cell.get(("Embree, coherent", "—"))
            v, r = cell.get(("OpenVDB", "10")), cell.get(("raykit", "10"))
            rs, rp = cell.get(("raykit SIMD", "10")), cell.get(("raykit packets", "10"))
            rl = cell.get(("raykit packets, 1-px LOD", "12"))
            if not (e and r):
                continue
            best = max([float(r)] + [float(x) for x in (rs, rp) if x])
            rv = f"{best / float(v):.2f}" if v else "-"
            lod = f"{float(rl) / float(e):.2f}" if rl else "-"
            bc = f"{best / float(ec):.2f}" if ec else "-"
            lodc = f"{float(rl) / float(ec):.2f}" if rl and ec else "-"
            table.append(f"| {mesh} | {e} | {ec or '-'} | {v or '-'} | {r} | {rs or '-'} | {rp or '-'} | {rv} | {best / float(e):.2f} | {bc} | {lod} | {lodc} |")
        md.extend(table)
        md.append("")
        md.append("![Mrays/s by depth, single thread](img/bench_trace_mrays.png)")
        md.append("")
    md.append("Frame time of the voxel pass on the GL driver against rasterising the source mesh, by depth, "
              "resolution and level of detail, with the LOD image error: "
              "[benchmarks_svo_gl.md](benchmarks_svo_gl.md) (`bash scripts/bench_svo_gl.sh`).")
    md.append("")
    if os.path.exists(os.path.join(out_dir, "img", "bench_svo_gl_tradeoff.png")):
        md.append("![Level of detail: frame time against image error](img/bench_svo_gl_tradeoff.png)")
        md.append("")
    md.extend(svo_gl_gpu_summary(out_dir))
    return md


def agreement(rows, prev_rows):
    """How two runs' paired ratios agree: for every row with a relative cost in both, whether each
    run's median lies inside the other's range. Returns a dict (see consecutive_run_text)."""
    prev = {r.name: r for r in prev_rows if r.rel is not None}
    out = {"n": 0, "both": 0, "misses": [], "diffs": []}
    for r in rows:
        p = prev.get(r.name)
        if r.rel is None or p is None or r.rel[2] < 0.05:
            continue
        out["n"] += 1
        med, lo, hi = r.rel
        pmed, plo, phi = p.rel
        out["diffs"].append(abs(med - pmed) / pmed if pmed else 0.0)
        if plo <= med <= phi and lo <= pmed <= hi:
            out["both"] += 1
        else:
            out["misses"].append((r, p))
    return out


def range_meaning_text(k):
    """What the bracketed range promises about a rerun (scripts/rerun_stats.py)."""
    if k < 3:
        return ""
    both, one, _ = rerun_stats.agreement_probability(k, k)
    return ("When every process draws its value from one distribution, whatever it is, a rerun of %d processes "
            "puts its median inside this range with probability %.1f %%, and both runs' medians lie inside "
            "each other's ranges with probability %.1f %% (counted exactly over the orderings of the %d values, "
            "`scripts/rerun_stats.py`): about %.0f rows in a hundred fail that two-way check by chance alone." % (
                k, 100.0 * one, 100.0 * both, 2 * k, 100.0 * (1.0 - both)))


def consecutive_run_text(context, prev_context, agree):
    """The sentences of "How to read" on the run-to-run check, from the data (None: not compared)."""
    if prev_context is None:
        return ("No previous run was compared with this one (scripts/bench.sh compares with the run before "
                "it when both come from the same binary).")
    sha = context.get("raykit_binary_sha256")
    if not sha or prev_context.get("raykit_binary_sha256") != sha:
        return ("The run before this one came from another build, so it was not compared (rebuilds are not "
                "reruns, below).")
    if not agree["n"]:
        return "The run before this one had no paired rows in common with this one."
    diffs = sorted(agree["diffs"])
    text = ("Checked against the run before it (same binary, %s): in %d of %d rows each run's median lies "
            "inside the other's range; the medians differ by %.1f %% at most (median %.2f %%). %s" % (
                prev_context.get("date", "?"), agree["both"], agree["n"], 100.0 * diffs[-1],
                100.0 * statistics.median(diffs),
                rerun_stats.expectation_text(agree["n"], agree["both"], int(context.get("raykit_processes", 1)),
                                             int(prev_context.get("raykit_processes", 1)))))
    if agree["misses"]:
        worst = sorted(agree["misses"], key=lambda rp: -abs(rp[0].rel[0] - rp[1].rel[0]) / rp[1].rel[0])
        items = ["`%s` %.3f (%.3f–%.3f) against %.3f (%.3f–%.3f)" % (
            r.name, r.rel[0], r.rel[1], r.rel[2], p.rel[0], p.rel[1], p.rel[2]) for r, p in worst[:4]]
        text += " Outside: " + "; ".join(items) + ("; ..." if len(worst) > 4 else "") + "."
        wide = [r for r, p in worst if r.rel[0] > 0 and (max(r.rel[2], p.rel[2]) - min(r.rel[1], p.rel[1])) > 0.25 * r.rel[0]]
        if wide:
            text += (" %d of these %d rows span more than 25 %% of their median over the two runs' processes: "
                     "their processes fall into a fast and a slow group (where code and data land differs from one "
                     "process to the next), so the median of a run can sit in either; quote their range, not "
                     "the median." % (len(wide), len(worst)))
    return text


def goal_lines(context, suite):
    """The suite's goals (raykit_suite:<s>:goals, see SuiteInfo::goals), each said met or missed with
    its error and its paired relative cost (median and range of repetitions)."""
    spec = context.get("raykit_suite:%s:goals" % suite.name, "")
    out = []
    for item in [g for g in spec.split(";") if g.strip()]:
        name, max_err, max_rel, what = (item.split("|") + ["", "", "", ""])[:4]
        row = next((r for r in suite.rows if r.name == name), None)
        head = "- Goal: max abs error <= %s at <= %sx the baseline's cost, %s (`%s`): " % (max_err, max_rel, what, name)
        if row is None or row.rel is None or row.max_abs is None:
            out.append(head + "not measured in this run.")
            continue
        med, lo, hi = row.rel
        ok = row.max_abs <= float(max_err) and med <= float(max_rel)
        out.append(head + "**%s** (error %.2g, cost %.2fx, %.2f to %.2f over the %s)." % (
            "met" if ok else "missed", row.max_abs, med, lo, hi,
            "processes" if int(context.get("raykit_processes", 1)) > 1 else "repetitions"))
    if out:
        out.append("")
    return out


def write_markdown(context, rows, suites, out_dir, pngs, errors=(), consecutive=None):
    pngs_written = [os.path.basename(p) for p in pngs.values() if p]
    sources = [s.source for s in suites if s.source]

    md = []
    md.append("# raykit benchmarks")
    md.append("")
    md.append("<!-- Generated by scripts/bench_report.py from raykit_bench's JSON. Do not edit by hand. -->")
    md.append("")
    md.append("Reproduce with `bash scripts/bench.sh` (Release build of %s; the per-call suites run in %d "
              "separate processes, then `scripts/bench_report.py` merges them into `build/bench.json` and "
              "rewrites this file%s)." % (
                  ", ".join("`%s`" % s for s in sources) if sources else "`bench/bench_*.cpp`",
                  int(context.get("raykit_processes", 1)),
                  " and " + ", ".join("`img/%s`" % p for p in pngs_written) if pngs_written else ""))
    md.append("")
    if len(suites) > 1:
        md.append("Sections: " + ", ".join("[%s](#%s)" % (s.title.partition(":")[0].strip(), anchor(s.title))
                                           for s in suites) + ".")
        md.append("")
    md.extend(interior_summary(out_dir))
    md.extend(svo_trace_summary(out_dir))
    md.extend(deferred_summary(out_dir))
    md.extend(volumes_summary(out_dir))
    md.append("## Machine")
    md.append("")
    md.extend(machine_table(context, rows))
    md.append("")
    md.append("## How to read the tables")
    md.append("")
    md.append("- **ns/call** (ns/pixel where a call processes a pixel): CPU time per call, the median over the "
              "iterations of a pass over a pre-generated array of independent inputs, harness included; ± is the "
              "coefficient of variation over the processes. Only the *ratios* between rows mean "
              "anything; absolute CPU times are not the point (see [GPU figures](#gpu-figures)).")
    md.append("- **relative cost**: the cost of a call relative to the section's baseline (named at the top of "
              "each section) = 1.0, measured *paired*: every benchmark iteration times four passes over the same "
              "4096 inputs back to back, in rotating order: the row's function, its *harness* (the same loop "
              "returning each input unchanged), the baseline and the baseline's harness. The ratio (row − "
              "harness) / (baseline − baseline harness) is taken per iteration and its median kept, so a slow "
              "patch of the machine, which slows the four passes alike, cancels. Shown: the median over the processes (each runs every row once, in its "
              "own random order), and in brackets the range of the per-process values, the run-to-run spread. "
              + range_meaning_text(int(context.get("raykit_processes", 1))) + " "
              + (consecutive or consecutive_run_text(context, None, None)) + " Each section states its harness "
              "cost.")
    md.append("- **gross**: the same paired ratio with the harnesses left in (median of the processes). On an "
              "out-of-order CPU a function's work partly overlaps its harness's loads and stores, so the truth "
              "lies between the two columns; for the cheapest rows (a few cycles per call) they differ most.")
    md.append("- **Rebuilds are not reruns.** The bracketed ranges are the spread of runs of one build; a rebuild "
              "that only moves code (another file edited, another compiler) can shift the cheapest rows by about "
              "a cycle per call (the timed loops are aligned to 64 bytes, `-falign-loops=64`, to limit this), so "
              "compare rows of one report, not reports of different builds.")
    md.append("- **max / mean abs err**: absolute error against float64 references over a dense sweep of the "
              "input range, computed once outside the timing; each section says which references.")
    md.append("- **max ulp**: only where meaningful (exact functions whose result stays away from zero); "
              "`—` otherwise.")
    md.append("- **worst at**: the swept input where the max abs error occurs.")
    md.append("")
    for suite in suites:
        if is_octree_suite(suite):
            md.extend(svo_section(context, suite, errors, pngs.get(suite.name)))
            continue
        md.append("## " + suite.title)
        md.append("")
        intro = []
        if suite.source:
            intro.append("Source: `%s`." % suite.source)
        if suite.baseline:
            intro.append("Relative cost 1.0: `%s` (`%s`)." % (
                suite.baseline.name, suite.baseline.function.split("[")[0].strip()))
        else:
            intro.append("Relative cost: not available (baseline `%s` not in this run)." % suite.baseline_name)
        hs = [r.harness_ns for r in suite.rows if r.harness_ns]
        if hs and suite.baseline and suite.baseline.ns:
            h = statistics.median(hs)
            intro.append("Harness (loop, input load, result store): %.2f ns/%s, median over the rows (%.2f to %.2f), "
                         "%.0f %% of the baseline's time; subtracted from every relative cost." % (
                             h, suite.per(), min(hs), max(hs), 100.0 * h / suite.baseline.ns))
        md.append(" ".join(intro))
        md.append("")
        md.extend(goal_lines(context, suite))
        if suite.about:
            md.append(suite.about)
            md.append("")
        if suite.plot_families:
            md.append("### Speed vs error")
            md.append("")
            if pngs.get(suite.name):
                md.append("![speed vs error, %s](img/%s)" % (suite.name, png_name(suite.name)))
            else:
                md.append("_(plot not drawn: gnuplot was not available when this report was generated)_")
            md.append("")
        base = suite.baseline
        for fam in suite.families:
            fam_rows = suite.family_rows(fam)
            title = family_title(context, fam)
            head, _, rest = title.partition(":")
            md.append("### " + (head.strip() if rest else title))
            md.append("")
            if rest:
                md.append(paragraph(rest))
                md.append("")
            md.append("| function | benchmark | ns/%s | relative cost | gross | max abs err | mean abs err | max ulp "
                      "| worst at | error against |" % suite.per())
            md.append("|---|---|--:|--:|--:|--:|--:|--:|--:|---|")
            for r in fam_rows:
                rel = fmt_rel(r, base)
                md.append("| %s | `%s` | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                    md_escape(fmt_function(r.function)),
                    md_escape(r.variant + ("/" + r.params if r.params else "")),
                    fmt_ns(r), rel, "%.2f" % r.rel_gross[0] if r.rel_gross else "—",
                    fmt_err(r.max_abs), fmt_err(r.mean_abs),
                    "%.1f" % r.max_ulp if r.max_ulp is not None else "—",
                    fmt_worst(r),
                    md_escape(r.against)))
            md.append("")
    md.append("## GPU figures")
    md.append("")
    md.append(gpu_figures_line(out_dir))
    md.append("")
    for suite in suites:
        if suite.gpu:
            md.append("- **%s**: %s" % (suite.title.partition(":")[0].strip(), suite.gpu))
    md.append("")

    path = os.path.join(out_dir, "benchmarks.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(md))
    return path


def anchor(title):
    """GitHub's heading anchor: lower case, punctuation dropped, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--json", required=True, action="append",
                    help="Google Benchmark JSON output of raykit_bench; repeat it for separate processes")
    ap.add_argument("--out-dir", default="docs", help="where benchmarks.md and img/ go (default: docs)")
    ap.add_argument("--merged-out", help="write the merged JSON here (what --previous reads next time)")
    ap.add_argument("--previous", help="an earlier merged JSON of the same binary to compare with")
    ap.add_argument("--binary-sha256", help="SHA-256 of the raykit_bench binary that wrote the JSON")
    args = ap.parse_args(argv)

    if len(args.json) == 1 and not args.binary_sha256:
        data = read_json(args.json[0])
    else:
        data = merge_json(args.json, args.binary_sha256)
    if args.merged_out:
        with open(args.merged_out, "w", encoding="utf-8") as f:
            json.dump(data, f, indent=1)
    context, rows = load(data)
    if not rows:
        print("bench_report: no benchmarks in %s" % ", ".join(args.json), file=sys.stderr)
        return 1
    errors = load_errors(data)
    consecutive = None
    if args.previous and os.path.exists(args.previous):
        prev_context, prev_rows = load(read_json(args.previous))
        consecutive = consecutive_run_text(context, prev_context, agreement(rows, prev_rows))
        print("bench_report: " + consecutive)
    suites = make_suites(context, rows)
    os.makedirs(args.out_dir, exist_ok=True)
    pngs = {}
    for suite in suites:
        img_dir = os.path.join(args.out_dir, "img")
        if is_octree_suite(suite):
            pngs[suite.name] = write_svo_plot(SvoData(context, suite, errors), img_dir)
        else:
            pngs[suite.name] = write_plot(context, suite, img_dir)
    if not any(s.plot_families or is_octree_suite(s) for s in suites):
        print("bench_report: nothing to plot", file=sys.stderr)
    md = write_markdown(context, rows, suites, args.out_dir, pngs, errors, consecutive)
    drawn = [p for p in pngs.values() if p]
    print("bench_report: wrote %s (%d benchmarks)%s" % (md, len(rows), "".join(", %s" % p for p in drawn)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
