"""Markdown pieces the summary tables share: cells, numbers, tables, and a
reader for tests and scripts."""
import math

import numpy as np


def fmt(value, bound=""):
    """A number to 3 significant digits, '—' for NaN or None; bound ('≤') in front."""
    if value is None or not math.isfinite(value):
        return "—"
    return f"{bound} {value:.3g}".strip()


def cell(text):
    # a message may hold '|' or a line break; either would break the table
    return str(text).replace("|", "\\|").replace("\n", " ").strip()


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return lines


def parse_table(markdown, heading):
    """Rows (lists of cells) of the table under a heading line ([] if none before the next heading)."""
    lines = markdown.splitlines()
    try:
        start = lines.index(heading)
    except ValueError:
        return None
    rows = []
    for line in lines[start + 1:]:
        if line.startswith("#"):
            break
        if line.startswith("|"):
            rows.append([c.strip() for c in line.strip().strip("|").split(" | ")])
        elif rows:
            break
    return rows[2:] if len(rows) >= 2 else []


def as_number(text):
    """The number in a cost cell ('≤ 1.2e-3' -> 1.2e-3), NaN for '—'."""
    text = text.replace("≤", "").strip()
    try:
        return float(text)
    except ValueError:
        return np.nan
