#!/usr/bin/python3
# sao-render --help (docs/ROBUSTNESS.md) lists every setting of the generated metadata with its
# range, unit ("unitless" when it has none) and default, names every backend (cpu-double too) and
# every sao.* attribute that sao/io.h documents for a depth EXR's camera.
#
#   render_help.py SAO_RENDER GENERATED_SAO_EFFECT_H IO_H
import re
import subprocess
import sys

render, effect_h, io_h = sys.argv[1:4]
run = subprocess.run([render, "--help"], capture_output=True, text=True)
help_text = run.stdout
problems = []
if run.returncode != 0 or run.stderr:
    problems.append(f"--help: exit {run.returncode}, stderr {run.stderr!r}")


def number(text):  # as the help prints it: 9 significant digits, like the range errors
    return format(float(text), ".9g")


settings = re.findall(r'\{"(\w+)", SettingType::(\w+), ([^,]+), ([^,]+), ([^,]+), "([^"]*)", "', open(effect_h).read())
if len(settings) < 10:
    problems.append(f"found only {len(settings)} settings in {effect_h}")
for name, kind, default, lo, hi, unit in settings:
    span = "0 | 1" if kind == "Bool" else f"[{number(lo)}, {number(hi)}]"
    if kind == "Int":
        span = "whole number in " + span
    allowed = re.search(rf"kAllowed_{name}\[\] = \{{([^}}]*)\}}", open(effect_h).read())
    if allowed:  # values=[...]: those alone
        span = "one of " + " | ".join(number(v) for v in allowed.group(1).split(","))
    want = f"{span}, {unit or 'unitless'}, default {number(default)}"
    line = re.search(rf"^  {name} +(.*)$", help_text, re.M)
    if not line or line.group(1) != want:
        problems.append(f"setting {name}: help says {line.group(1) if line else None!r}, metadata {want!r}")

for backend in ("gl", "vulkan", "cpu", "cpu-double", "auto"):
    if not re.search(rf"(^|[ |(]){re.escape(backend)}( |$)", help_text.split("--scene")[0].split("--backend")[1], re.M):
        problems.append(f"--backend does not name {backend}")

attributes = re.findall(r"^//\s+(sao\.\w+)\s", open(io_h).read(), re.M)
if len(attributes) < 10:
    problems.append(f"found only {len(attributes)} sao.* attributes in {io_h}")
for attribute in attributes:
    if attribute not in help_text:
        problems.append(f"the help does not name the depth EXR attribute {attribute}")
for option in ("--runs N", "--progress S", "sao-render-outputs.txt"):
    if option not in help_text:
        problems.append(f"the help does not mention {option}")

print("\n".join(problems) or f"{len(settings)} settings, {len(attributes)} attributes listed")
sys.exit(1 if problems else 0)
