#!/usr/bin/env python3
"""Counts the bad-input cases of docs/ROBUSTNESS.md section 4 from its tables, so that no total is
kept by hand: the first column "#" of each table row is that row's count of distinct inputs.
usage: ci/robustness_counts.py [docs/ROBUSTNESS.md]"""
import re
import sys
from pathlib import Path

doc = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent / "docs/ROBUSTNESS.md")
section, counts = None, {}
in_four = False
for line in doc.read_text().splitlines():
    heading = re.match(r"^(#{2,3}) (\d+(?:\.\d+)?)\.? (.*)", line)
    if heading:
        number = heading.group(2)
        in_four = number == "4" or number.startswith("4.")
        section = f"{number} {heading.group(3)}" if in_four else None
        continue
    if not in_four or section is None:
        continue
    row = re.match(r"^\|\s*(\d+)\s*\|", line)
    if row:
        counts[section] = counts.get(section, 0) + int(row.group(1))

width = max(len(s) for s in counts) if counts else 0
for s, n in counts.items():
    print(f"{s:<{width}}  {n:5d}")
print(f"{'total':<{width}}  {sum(counts.values()):5d}")
