#!/usr/bin/env python3
"""bench/speed_targets.py DIR: the "Speed targets" section of BENCHMARKS.md.

bench/run leaves each soiq-bench section's markdown in DIR (dispatch.md, table5.md, floor.md,
features.md, codec.md, query.md, replicas.md); this reads the figures the speed targets name out
of those tables, by their column headers and row labels, and prints one table: each figure now,
its target, and its value before the speed work (as measured on this machine when the work was
planned; empty where nothing was measured then).

A figure that cannot be found prints as "not measured" rather than failing the whole report: the
sections themselves are in BENCHMARKS.md below it.
"""
import os
import re
import sys


def tables(path):
    """Every markdown table of a file, as lists of rows (the header first), cells stripped."""
    out, rows = [], []
    try:
        lines = open(path, encoding="utf-8").read().splitlines()
    except OSError:
        return out
    for line in lines + [""]:
        if line.startswith("|"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not all(re.fullmatch(r":?-+:?", c) for c in cells):
                rows.append(cells)
        elif rows:
            out.append(rows)
            rows = []
    return out


def cell(path, column, row_prefix):
    """The cell of the first table holding `column` whose row's first cell starts with row_prefix."""
    for t in tables(path):
        header = t[0]
        if column not in header:
            continue
        i = header.index(column)
        for r in t[1:]:
            if r[0].startswith(row_prefix) and i < len(r):
                return r[i]
    return None


def number(text):
    m = re.search(r"-?[0-9]+(?:\.[0-9]+)?", text or "")
    return float(m.group(0)) if m else None


def main():
    d = sys.argv[1]
    f = lambda name: os.path.join(d, name)
    rows = []  # (figure, now, target, met, before)

    def add(figure, now, target, ok, before):
        shown = now if now is not None else "not measured"
        met = "" if now is None or ok is None else ("met" if ok(number(now)) else "**not met**")
        rows.append((figure, shown, target, met, before))

    before_dispatch = {"SM1": "1.18x", "SM6": "1.20x", "SM11": "1.24x"}
    for m in ("SM1", "SM6", "SM11"):
        add(f"{m}: portable / tuned build, 1D conversion", cell(f("dispatch.md"), "portable / tuned", m),
            "<= 1.05x", lambda v: v <= 1.05, before_dispatch[m])
    before_itk = {"SM1": "11.5x", "SM6": "10.5x", "SM11": "9.1x"}
    before_vtk = {"SM1": "69x", "SM6": "71x", "SM11": "85x"}
    before_floor = {"SM1": "3.45x", "SM6": "", "SM11": "2.7x"}
    for m in ("SM1", "SM6", "SM11"):
        add(f"{m}: ITK / 1D, one thread", cell(f("table5.md"), "itk / 1d", m), ">= 25x", lambda v: v >= 25,
            before_itk[m])
        add(f"{m}: VTK stencil / 1D, one thread", cell(f("table5.md"), "vtk / 1d", m), ">= 150x",
            lambda v: v >= 150, before_vtk[m])
        add(f"{m}: 1D / scanline floor, one thread", cell(f("floor.md"), "1d / floor", m), "<= 1.5x",
            lambda v: v <= 1.5, before_floor[m])
    add("SM11: 1D on 2 threads, speed-up over 1", cell(f("table5.md"), "1d x2 speed-up", "SM11"), ">= 1.8x",
        lambda v: v >= 1.8, "")
    add("cold query / its conversions alone on the same workers",
        cell(f("query.md"), "value", "cold query / the same"), "<= 1.5x", lambda v: v <= 1.5, "3.6-4.1x")
    add("warm query: server total / its stage 1", cell(f("query.md"), "value", "warm query's server total_ms"),
        "<= 1.5x", lambda v: v <= 1.5, "1.8-2.7x")
    add("8 clients' warm throughput / 1 client's", cell(f("query.md"), "value", "8 clients' queries/s"),
        ">= 1.9x", lambda v: v >= 1.9, "1.47-1.52x")
    add("query after precompute / query of stored values only",
        cell(f("query.md"), "value", "benchmark query after precompute"), "<= 2x", lambda v: v <= 2, "")
    add("PostgreSQL / SQLite: cold query", cell(f("replicas.md"), "PostgreSQL / SQLite", "cold query"),
        "<= 1.3x", lambda v: v <= 1.3, "2.3x")
    add("PostgreSQL / SQLite: warm throughput, 8 clients",
        cell(f("replicas.md"), "PostgreSQL / SQLite", "warm query, 8 clients"), ">= 0.8x", lambda v: v >= 0.8,
        "0.41x")
    scale = None
    try:
        m = re.search(r"PostgreSQL ([0-9.]+) / ([0-9.]+)\.", open(f("replicas.md"), encoding="utf-8").read().split(
            "Stage 1 at scale", 1)[1])
        scale = f"{m.group(1)} ms (best)" if m else None
    except (OSError, IndexError):
        pass
    add("stage 1 over 10^6 structures on PostgreSQL, through soiqd", scale, "measured", None, "")
    add("smoothed STS tumour (>= 100k triangles): all features / its conversion",
        cell(f("features.md"), "features / conversion", "STS_002 tumour, smoothed"), "<= 4x", lambda v: v <= 4,
        "10.8x")
    add("surface decode, 100k triangles / memcpy of its decoded bytes (medians)",
        cell(f("codec.md"), "decode / memcpy", "uv sphere, 100k"), "<= 2.5x", lambda v: v <= 2.5, "")

    print("| figure | now | target | | before |")
    print("|---|---:|---|---|---:|")
    for figure, now, target, met, before in rows:
        print(f"| {figure} | {now} | {target} | {met} | {before} |")


if __name__ == "__main__":
    main()
