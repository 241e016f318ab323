#!/usr/bin/python3
"""Markdown tables of a sao-bench run, as docs/BENCHMARKS.md shows them.

usage: /usr/bin/python3 samples/bench/markdown_tables.py OUT_DIR   (the folder sao-bench wrote)
Reads results.csv and precision.csv; prints to stdout. Only the standard library.
"""
import csv
import math
import os
import sys


def f(x, digits=1):
    return "" if x in ("", None) else f"{float(x):.{digits}f}"


def g(x, digits=3):
    return "" if x in ("", None) else f"{float(x):.{digits}g}"


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def main(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "results.csv"))))
    sec = lambda name: [r for r in rows if r["section"] == name]

    print("### Presets: time and error (raw RMSE vs (a) near-field AO and (b) AlchemyAO obscurance)\n")
    print("\"off > 0.1 (b)\": the fraction of pixels with geometry whose raw output is more than 0.1 from (b).\n")
    print(table(["scene", "backend", "preset", "total ms", "ao_sample ms", "RMSE (a)", "bias (a)", "SSIM (a)",
                 "RMSE (b)", "bias (b)", "off > 0.1 (b)", "fitted RMSE (b)", "scale (b)"],
                [[r["scene"], r["backend"], r["preset"], f(r["total_ms"]), f(r["ao_sample_ms"]), g(r["ao_rmse_raw"]),
                  g(r["ao_bias_raw"], 2), g(r["ao_ssim_raw"]), g(r["obscurance_rmse_raw"]),
                  g(r["obscurance_bias_raw"], 2), g(r["obscurance_over_0_1_raw"], 2), g(r["obscurance_rmse_fitted"]),
                  g(r["obscurance_fitted_scale"])]
                 for r in sec("presets")]))

    for name, title in (("samples", "Sample count"), ("mip_blur", "z hierarchy and blur on/off")):
        print(f"\n### {title} (medium otherwise)\n")
        print(table(["scene", "backend", "variant", "total ms", "ao_sample ms", "RMSE (a)", "RMSE (b)"],
                    [[r["scene"], r["backend"], r["variant"], f(r["total_ms"]), f(r["ao_sample_ms"]),
                      g(r["ao_rmse_raw"]), g(r["obscurance_rmse_raw"])] for r in sec(name)]))

    radius = sec("radius")
    if radius:
        curves = []
        for r in radius:
            if r["variant"] not in curves:
                curves.append(r["variant"])
        radii = sorted({float(r["radius_m"]) for r in radius})
        by = {(r["variant"], float(r["radius_m"])): float(r["ao_sample_ms"]) for r in radius}
        r0 = radius[0]
        print(f"\n### Radius sweep (paper Figure 5): ao_sample ms, {r0['scene']}, {r0['backend']}, "
              f"{r0['width']}x{r0['height']}\n")
        hdr = ["radius m"] + curves + [f"{curves[-1]} / {curves[0]}"]
        print(table(hdr, [[f"{x:g}"] + [f(by.get((c, x))) for c in curves] +
                          [f(by[(curves[-1], x)] / by[(curves[0], x)], 2)] for x in radii]))
        for c in curves:
            print(f"\n{c}: time at {radii[-1]:g} m / time at {radii[0]:g} m = "
                  f"{by[(c, radii[-1])] / by[(c, radii[0])]:.2f}")

    res = sec("resolution")
    if res:
        print("\n### Resolution (paper Table 3): per-pass ms and ns per pixel, medium\n")
        print(table(["backend", "size", "linear_z", "mips", "ao_sample", "blur_h", "blur_v", "total", "ns/pixel",
                     "timing"],
                    [[r["backend"], f"{r['width']}x{r['height']}", f(r["linear_z_ms"], 2), f(r["mips_ms"], 2),
                      f(r["ao_sample_ms"]), f(r["blur_h_ms"]), f(r["blur_v_ms"]), f(r["total_ms"]),
                      f(r["ns_per_pixel"]), r["timing_method"]] for r in res]))

    two = sec("two_layer")
    if two:
        print("\n### Two depth layers (medium)\n")
        print(table(["backend", "variant", "total ms", "RMSE (a)", "bias (a)", "RMSE (b)", "bias (b)"],
                    [[r["backend"], r["variant"], f(r["total_ms"]), g(r["ao_rmse_raw"]), g(r["ao_bias_raw"], 2),
                      g(r["obscurance_rmse_raw"]), g(r["obscurance_bias_raw"], 2)] for r in two]))

    path = os.path.join(folder, "precision.csv")
    if os.path.exists(path):
        prec = list(csv.DictReader(open(path)))
        print("\n### Precision (paper Figures 3, 4): worst / 99th-percentile |z error| and face-normal error\n")
        print(table(["backend", "format", "far m", "convention", "clip", "bin m", "z worst m", "z p99 m",
                     "normal worst °", "normal p99 °", "pixels"],
                    [[r["backend"], r["format"], r["far_m"] if r["far_m"] == "inf" else f(r["far_m"], 0),
                      r["convention"], r["clip"], r["distance_bin_m"], g(r["z_worst_m"], 2), g(r["z_p99_m"], 2),
                      g(r["normal_worst_deg"], 2), g(r["normal_p99_deg"], 2), r["pixels"]] for r in prec]))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
