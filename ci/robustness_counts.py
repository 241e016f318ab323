#!/usr/bin/python3
"""The bad-input case tables of docs/ROBUSTNESS.md section 4, generated, so that no count is kept by hand.

Source: tests/docs/robustness_cases.md (hand-written: one "## 4.N" heading per sub-section, tables whose
first column "#" is that row's count of distinct inputs: 3, 5+5, 11×2×2, "15 kinds", or "every" for a
sweep over a set outside the tree, which is not summed). Anywhere in the source, {files:GLOB} becomes
the number of files of the tree matching GLOB (relative to the repository root).
Outputs: docs/generated/robustness-cases.md (the tables, a count per sub-section and in all, the fuzz
corpus) and the counts block of docs/ROBUSTNESS.md between its "robustness_counts.py" markers.
Every test a table names (`Suite.Name`, ctest names) must occur under tests/, or nothing is written.

usage: /usr/bin/python3 ci/robustness_counts.py [--write | --check]
  (no option: print the counts)  --write: rewrite the outputs  --check: exit 1 if they are stale
Only the standard library.
"""
import difflib
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCE = "tests/docs/robustness_cases.md"
GENERATED = "docs/generated/robustness-cases.md"
DOC = "docs/ROBUSTNESS.md"
BEGIN = "<!-- robustness_counts.py: begin (generated; /usr/bin/python3 ci/robustness_counts.py --write) -->"
END = "<!-- robustness_counts.py: end -->"
REFRESH = "/usr/bin/python3 ci/robustness_counts.py --write"


class Problem(Exception):
    pass


def expand_tokens(text):
    def files(m):
        matches = [p for p in ROOT.glob(m.group(1)) if p.is_file() and not p.name.startswith(".")]
        if not matches:
            raise Problem(f"{SOURCE}: {{files:{m.group(1)}}} matches no file of the tree")
        return str(len(matches))
    return re.sub(r"\{files:([^}]+)\}", files, text)


def row_count(cell, where):
    """The number a "#" cell stands for; None for "every" (not summed)."""
    cell = cell.strip()
    if cell == "every":
        return None
    m = re.fullmatch(r"([0-9+×]+)(?: kinds)?", cell)
    if not m or any(t == "" for t in re.split(r"[+×]", m.group(1))):
        raise Problem(f"{where}: the \"#\" cell '{cell}' is not N, N+M, N×M, 'N kinds' or 'every'")
    total = 0
    for term in m.group(1).split("+"):
        product = 1
        for factor in term.split("×"):
            product *= int(factor)
        total += product
    return total


def cells(line):
    # Split a table row on "|" outside backticks (a case may quote `a|b`).
    out, cur, tick = [], "", False
    for ch in line.strip().strip("|"):
        if ch == "`":
            tick = not tick
        if ch == "|" and not tick:
            out.append(cur.strip())
            cur = ""
        else:
            cur += ch
    out.append(cur.strip())
    return out


def identifiers_under_tests():
    words = set()
    for path in (ROOT / "tests").rglob("*"):
        if path.is_file() and "docs" not in path.relative_to(ROOT / "tests").parts[:1]:
            try:
                words.update(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", path.read_text(errors="replace")))
            except OSError:
                pass
    return words


def named_test(token):
    """The most specific identifier of a test name as a table writes it, or None (a path, a glob)."""
    parts = [p for p in re.split(r"[./*]", token.split("{")[0]) if p]
    names = [p for p in parts if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]{3,}", p)]
    return names[-1] if names and not token.startswith(("ci/", "build")) else None


def parse(source_text):
    """Sub-sections with their counts, and the tests the tables name."""
    sections, tests, current, test_column = {}, [], None, None
    lines = source_text.splitlines()
    for n, line in enumerate(lines, 1):
        heading = re.match(r"^## (4\.\d+) (.*)", line)
        if heading:
            current = f"{heading.group(1)} {heading.group(2)}"
            sections[current] = 0
            continue
        if not line.startswith("|"):
            test_column = None
            continue
        row = cells(line)
        if row[0] == "#":
            test_column = next((i for i, c in enumerate(row) if c.startswith("test")), None)
            continue
        if set(line) <= set("|-: "):
            continue
        if current is None:
            raise Problem(f"{SOURCE}:{n}: a table row before the first '## 4.N' heading")
        count = row_count(row[0], f"{SOURCE}:{n}")
        sections[current] += count or 0
        if test_column is not None and test_column < len(row):
            tests += [(n, t) for t in re.findall(r"`([^`]+)`", row[test_column])]
    return sections, tests


def counts_table(sections):
    out = ["| section | cases |", "|---|---|"]
    out += [f"| {name} | {n} |" for name, n in sections.items()]
    out.append(f"| **total** | **{sum(sections.values())}** |")
    return "\n".join(out)


def fuzz_table():
    runs = dict(re.findall(r"\[(\w+)\]=(\d+)", next(
        (l for l in (ROOT / "ci/fuzz.sh").read_text().splitlines() if l.startswith("declare -A runs=")), "")))
    targets = sorted(p.name for p in (ROOT / "tests/fuzz/corpus").iterdir() if p.is_dir())
    out = ["| target | seed files (`tests/fuzz/corpus/`) | regressions (`tests/fuzz/regressions/`) | "
           "inputs per CI run (`ci/fuzz.sh`) |", "|---|---|---|---|"]
    for t in targets:
        count = lambda d: sum(1 for p in (ROOT / d / t).glob("*") if p.is_file() and not p.name.startswith("."))
        inputs = f"{int(runs[t]):,}" if t in runs else "(not in ci/fuzz.sh)"
        out.append(f"| `fuzz_{t}` | {count('tests/fuzz/corpus')} | {count('tests/fuzz/regressions')} | {inputs} |")
    return "\n".join(out)


def generate():
    raw = (ROOT / SOURCE).read_text()
    body = expand_tokens(re.sub(r"\A<!--.*?-->\n*", "", raw, flags=re.S))
    sections, tests = parse(body)
    known = identifiers_under_tests()
    def exists(token):
        name = named_test(token)
        if name is None or name in known:
            return True
        return name + "*" in token and any(w.startswith(name) for w in known)  # `Suite.Prefix*`
    missing = [f"{SOURCE}:{n}: `{t}`" for n, t in tests if not exists(t)]
    if missing:
        raise Problem("these tables name tests that no file under tests/ mentions (renamed or removed?):\n  "
                      + "\n  ".join(missing))
    table = counts_table(sections)
    generated = f"""<!-- Generated by ci/robustness_counts.py from {SOURCE} and the tree: do not edit.
     Change the source, then run {REFRESH} (ctest: docs.robustness_cases). -->
# Bad-input cases

The case tables of [docs/ROBUSTNESS.md](../ROBUSTNESS.md) section 4 ("Bad input"), which says what
every case must hold (a clear `Status`, nothing changed, the context, device and effect still
usable). Column "#": the row's count of distinct inputs, per backend; a seeded corruption loop
counts once; "every" rows sweep a set outside the tree (Debian's assimp-testmodels), whose test
prints how many files it tried, and are not summed.

{table}

{body.rstrip()}

## Fuzz corpus

The libFuzzer targets of docs/ROBUSTNESS.md section 5: files of the committed seed corpus and
regressions, and the fixed number of inputs each target runs in CI's deterministic fuzz stage.

{fuzz_table()}
"""
    doc = (ROOT / DOC).read_text()
    if doc.count(BEGIN) != 1 or doc.count(END) != 1:
        raise Problem(f"{DOC} must hold the markers once each:\n  {BEGIN}\n  {END}")
    head, rest = doc.split(BEGIN)
    _, tail = rest.split(END)
    new_doc = f"{head}{BEGIN}\n{table}\n{END}{tail}"
    return sections, {GENERATED: generated, DOC: new_doc}


def main(argv):
    mode = argv[1] if len(argv) > 1 else None
    if mode not in (None, "--write", "--check") or len(argv) > 2:
        sys.exit(__doc__)
    try:
        sections, outputs = generate()
    except (Problem, OSError) as e:
        sys.exit(f"robustness_counts.py: {e}")
    if mode is None:
        width = max(map(len, sections))
        for name, n in sections.items():
            print(f"{name:<{width}}  {n:5d}")
        print(f"{'total':<{width}}  {sum(sections.values()):5d}")
    elif mode == "--write":
        for rel, text in outputs.items():
            (ROOT / rel).parent.mkdir(parents=True, exist_ok=True)
            if not (ROOT / rel).exists() or (ROOT / rel).read_text() != text:
                (ROOT / rel).write_text(text)
                print(f"wrote {rel}")
    else:
        stale = []
        for rel, text in outputs.items():
            old = (ROOT / rel).read_text() if (ROOT / rel).exists() else ""
            if old != text:
                stale.append(rel)
                diff = list(difflib.unified_diff(old.splitlines(), text.splitlines(), rel, "generated", lineterm=""))
                print("\n".join(diff[:40] + (["..."] if len(diff) > 40 else [])))
        if stale:
            sys.exit(f"stale: {', '.join(stale)} differ from what {SOURCE} and the tree give; refresh with: {REFRESH}")
        print(f"{GENERATED} and the counts in {DOC} are up to date ({sum(sections.values())} cases)")


if __name__ == "__main__":
    main(sys.argv)
