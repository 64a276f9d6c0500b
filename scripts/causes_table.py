#!/usr/bin/env python3
"""One table of the 2D causes study (docs/crumple2d/causes.md) from the CSV files that
scripts/crumple_study.py writes: a row per (file, value), each observable as the mean over
the seeds ± its standard error (n = number of seeds that ran; a failed run is counted and
named, not averaged).

  /usr/bin/python3 scripts/causes_table.py "drag factor=docs/crumple2d/causes/drag_f25.csv" \
      "relative damping=docs/crumple2d/causes/relative_f25.csv" ... > table.md
"""
import csv
import math
import sys

COLUMNS = [("phi", "φ_jam", 3), ("jammed", "jammed", 2), ("ab_ratio", "A/B", 2), ("loops", "loops", 1),
           ("contacts", "contacts", 0), ("wall_contacts", "wall contacts", 1),
           ("outer_share", "outer share", 2), ("half_width", "half width", 2), ("wall_s", "wall s", 0)]


def mean_se(values, digits):
    n = len(values)
    if n == 0:
        return "–"
    m = sum(values) / n
    if n == 1:
        return f"{m:.{digits}f}"
    se = math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1) / n)
    return f"{m:.{digits}f} ± {se:.{digits}f}"


def rows_of(label, path):
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    by_value = {}
    for r in rows:
        by_value.setdefault(r["value"], []).append(r)
    out = []
    for value, group in by_value.items():
        ok = [r for r in group if r["status"] == "ok"]
        failed = len(group) - len(ok)
        cells = [mean_se([float(r[k]) for r in ok], d) for k, _, d in COLUMNS]
        name = f"{label} = {value}" if value not in ("", None) else label
        out.append(f"| {name} | {len(ok)}" + (f" ({failed} failed)" if failed else "") + " | "
                   + " | ".join(cells) + " |")
    return out


def main():
    print("| variant | seeds | " + " | ".join(h for _, h, _ in COLUMNS) + " |")
    print("|---|---|" + "---|" * len(COLUMNS))
    for arg in sys.argv[1:]:
        label, path = arg.split("=", 1)
        for line in rows_of(label, path):
            print(line)


if __name__ == "__main__":
    main()
