#!/usr/bin/python3
"""Markdown tables of sao-bench runs, as docs/BENCHMARKS.md shows them.

usage: /usr/bin/python3 samples/bench/markdown_tables.py OUT_DIR   (the folder sao-bench wrote; prints the tables)
       /usr/bin/python3 samples/bench/markdown_tables.py --write   (regenerate the committed pages, below)
       /usr/bin/python3 samples/bench/markdown_tables.py --check   (exit 1 if any of them is stale)
The committed runs are docs/generated/bench-data/<run>/ (results.csv, precision.csv when the run has one,
and run.txt: "key: value" lines saying how it was made); --write turns each into
docs/generated/benchmarks-<run>.md and rewrites the key-figures block of docs/BENCHMARKS.md from them.
Reads results.csv, precision.csv and per_tap.csv. Only the standard library.
"""
import csv
import math
import os
import sys


def f(x, digits=None):
    """Fixed-point with `digits` decimals; by default one, or three significant digits below 1 (a GPU's
    milliseconds)."""
    if x in ("", None):
        return ""
    v = float(x)
    if digits is None:
        return f"{v:.1f}" if abs(v) >= 1 or v == 0 or math.isnan(v) else f"{v:.3g}"
    return f"{v:.{digits}f}"


def f2(x):
    """f() with two decimals from 1 ms up."""
    return f(x, 2) if x not in ("", None) and abs(float(x)) >= 1 else f(x)


def g(x, digits=3):
    return "" if x in ("", None) else f"{float(x):.{digits}g}"


def gn(x, digits=3):
    """g() that passes "n/a" (a metric undefined for the images at hand) through."""
    return x if x == "n/a" else g(x, digits)


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def tables(folder):
    """Every table of one sao-bench output folder, as one markdown text."""
    out = []
    print = lambda text="": out.append(text)  # the sections below print; collect instead
    with open(os.path.join(folder, "results.csv"), newline="") as fh:
        rows = list(csv.DictReader(fh))
    sec = lambda name: [r for r in rows if r["section"] == name]

    timed_only = [r for r in sec("presets") if r["ao_rmse_raw"] == ""]  # sao-bench --time-only
    if timed_only:
        blur = "blur_ms" if "blur_ms" in timed_only[0] else "blur_h_ms"
        print("### Presets: time per pass (--time-only: no references, no errors)\n")
        print(table(["scene", "backend", "preset", "size", "total ms", "linear_z ms", "ao_sample ms", f"{blur[:-3]} ms",
                     "upsample ms", "output ms", "timing"],
                    [[r["scene"], r["backend"], r["preset"], f"{r['width']}x{r['height']}", f(r["total_ms"]),
                      f(r["linear_z_ms"]), f(r["ao_sample_ms"]), f(r[blur]), f(r.get("upsample_ms", "")),
                      f(r.get("output_ms", "")), r["timing_method"]] for r in timed_only]))
    elif sec("presets"):
        print("### Presets: time and error (raw RMSE vs (a) near-field AO and (b) AlchemyAO obscurance)\n")
        print("\"off > 0.1 (b)\": the fraction of pixels with geometry whose raw output is more than 0.1 from (b).\n")
        print(table(["scene", "backend", "preset", "total ms", "ao_sample ms", "RMSE (a)", "bias (a)", "SSIM (a)",
                     "RMSE (b)", "bias (b)", "off > 0.1 (b)", "fitted RMSE (b)", "scale (b)"],
                    [[r["scene"], r["backend"], r["preset"], f(r["total_ms"]), f(r["ao_sample_ms"]), g(r["ao_rmse_raw"]),
                      g(r["ao_bias_raw"], 2), g(r["ao_ssim_raw"]), g(r["obscurance_rmse_raw"]),
                      g(r["obscurance_bias_raw"], 2), g(r["obscurance_over_0_1_raw"], 2), g(r["obscurance_rmse_fitted"]),
                      g(r["obscurance_fitted_scale"])]
                     for r in sec("presets")]))
        converged = [r for r in sec("presets") if r.get("converged_rmse_raw", "") not in ("", "n/a")]
        if converged:
            print("\n### Presets against (c), the converged estimator: sampling and reconstruction error\n")
            print("Blotch: RMSE of the error vs (c) low-passed (Gaussian, sigma 8 px); silhouette: within 3 px of a "
                  "depth edge; FLIP: mean FLIP vs (c) (0 = no visible difference); model: RMSE of (c) itself vs (a), "
                  "and its share of the preset's RMSE vs (a), what no preset can change.\n")
            print(table(["scene", "backend", "preset", "total ms", "RMSE (c)", "blotch (c)", "high-freq (c)",
                         "silhouette (c)", "SSIM (c)", "FLIP (c)", "FLIP (a)", "model (c vs a)", "model share of (a)"],
                        [[r["scene"], r["backend"], r["preset"], f(r["total_ms"]), gn(r["converged_rmse_raw"]),
                          gn(r.get("converged_blotch_rmse", "")), gn(r.get("converged_highfreq_rmse", "")),
                          gn(r.get("converged_silhouette_rmse", "")), gn(r.get("converged_ssim_raw", "")),
                          gn(r.get("converged_flip_raw", "")), gn(r.get("ao_flip_raw", "")),
                          gn(r.get("model_rmse_vs_ao", "")),
                          f(100 * float(r["model_rmse_vs_ao"]) / float(r["ao_rmse_raw"]), 0) + " %"
                          if r.get("model_rmse_vs_ao") and r.get("ao_rmse_raw") else ""]
                         for r in converged]))

    for name, title in (("samples", "Sample count"), ("mip_blur", "z hierarchy and blur on/off")):
        if not sec(name):
            continue
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
        if "mips_ms" in res[0]:  # runs before the z chain moved into linear_z (and blur_v_low into upsample)
            low = "upsample_ms" in res[0]  # blur_v_low and upsample at reduced resolution
            print(table(["backend", "size", "linear_z", "mips", "ao_sample", "blur_h", "blur_v"] +
                        (["blur_v_low", "upsample"] if low else []) + ["total", "ns/pixel", "timing"],
                        [[r["backend"], f"{r['width']}x{r['height']}", f2(r["linear_z_ms"]), f2(r["mips_ms"]),
                          f(r["ao_sample_ms"]), f(r["blur_h_ms"]), f(r["blur_v_ms"])] +
                         ([f(r["blur_v_low_ms"]), f(r["upsample_ms"])] if low else []) +
                         [f(r["total_ms"]), f(r["ns_per_pixel"]), r["timing_method"]] for r in res]))
        elif "blur_ms" in res[0]:  # one blur pass, and the upsample at every divisor
            print(table(["backend", "size", "linear_z + chain", "ao_sample", "blur", "output", "upsample", "total",
                         "ns/pixel", "timing"],
                        [[r["backend"], f"{r['width']}x{r['height']}", f2(r["linear_z_ms"]),
                          f(r["ao_sample_ms"]), f(r["blur_ms"]), f(r.get("output_ms", "")), f(r["upsample_ms"]),
                          f(r["total_ms"]), f(r["ns_per_pixel"]), r["timing_method"]] for r in res]))
        else:  # linear_z writes the whole chain; blur_v at full resolution, blur_v_low and upsample at reduced
            print(table(["backend", "size", "linear_z + chain", "ao_sample", "blur_h", "blur_v", "blur_v_low",
                         "upsample", "total", "ns/pixel", "timing"],
                        [[r["backend"], f"{r['width']}x{r['height']}", f2(r["linear_z_ms"]),
                          f(r["ao_sample_ms"]), f(r["blur_h_ms"]), f(r["blur_v_ms"]), f(r["blur_v_low_ms"]),
                          f(r["upsample_ms"]), f(r["total_ms"]), f(r["ns_per_pixel"]), r["timing_method"]]
                         for r in res]))

    div = [r for r in sec("divisor") if r["converged_rmse_raw"] != ""]  # none with --time-only
    if div:
        err = {(r["scene"], r["preset"], r["resolution_divisor"]): r for r in div}
        divisors = sorted({r["resolution_divisor"] for r in div}, key=int)
        scenes = list(dict.fromkeys(r["scene"] for r in div))
        names = list(dict.fromkeys(r["preset"] for r in div))
        r0 = div[0]
        print(f"\n### Resolution divisor: error vs (c) per preset at divisors {', '.join(divisors)} "
              f"({r0['backend']}, {r0['width']}x{r0['height']})\n")
        print("Each preset as it is, only resolution_divisor changed. +: the RMSE over the same preset at full "
              "resolution; silhouette: the error within 3 px of a depth edge, over full resolution's.\n")
        hdr = ["scene", "preset", "RMSE (c) 1/1"]
        for d in divisors[1:]:
            hdr += [f"+ at 1/{d}", f"silhouette 1/{d}"]
        out_rows = []
        for sc in scenes:
            for p in names:
                full = err.get((sc, p, "1"))
                if not full:
                    continue
                row = [sc, p, gn(full["converged_rmse_raw"], 4)]
                for d in divisors[1:]:
                    r = err.get((sc, p, d))
                    if not r:
                        row += ["", ""]
                        continue
                    row.append(f"{float(r['converged_rmse_raw']) - float(full['converged_rmse_raw']):+.4f}")
                    sil, sil1 = r["converged_silhouette_rmse"], full["converged_silhouette_rmse"]
                    row.append(f"{float(sil) / float(sil1):.2f}×" if sil not in ("", "n/a") and sil1 not in ("", "n/a")
                               and float(sil1) > 0 else "n/a")
                out_rows.append(row)
        print(table(hdr, out_rows))
    times = sec("divisor_time")
    if times:
        t = {(r["backend"], r["preset"], r["resolution_divisor"]): r for r in times}
        divisors = sorted({r["resolution_divisor"] for r in times}, key=int)
        r0 = times[0]
        print(f"\n### Resolution divisor: time per preset ({r0['scene']}, {r0['width']}x{r0['height']}, median ms; "
              "a preset's divisors measured one after another)\n")
        hdr = ["backend", "preset"] + [f"total 1/{d}" for d in divisors] + [f"1/{d} ÷ 1/1" for d in divisors[1:]] + \
              [f"upsample 1/{d}" for d in divisors[1:]]
        out_rows = []
        for (b, p) in dict.fromkeys((r["backend"], r["preset"]) for r in times):
            full = float(t[(b, p, "1")]["total_ms"])
            out_rows.append([b, p] + [f(t[(b, p, d)]["total_ms"]) for d in divisors] +
                            [f"{float(t[(b, p, d)]['total_ms']) / full:.2f}" for d in divisors[1:]] +
                            [f(t[(b, p, d)]["upsample_ms"]) for d in divisors[1:]])
        print(table(hdr, out_rows))

    inter = [r for r in sec("intermediates") if r["converged_rmse_raw"] != ""]  # none with --time-only
    if inter:
        err = {(r["scene"], r["preset"], r["variant"]): r for r in inter}
        r0 = inter[0]
        print(f"\n### Intermediates: error vs (c) with rg32f and rg16f (A, key) images ({r0['backend']}, "
              f"{r0['width']}x{r0['height']})\n")
        print("Each preset as it is, only half_intermediates changed. Δ: rg16f's RMSE vs (c) minus rg32f's; "
              "silhouette: the RMSE within 3 px of a depth edge.\n")
        out_rows = []
        for (sc, p) in dict.fromkeys((r["scene"], r["preset"]) for r in inter):
            a, b = err.get((sc, p, "rg32f")), err.get((sc, p, "rg16f"))
            if not a or not b:
                continue
            ra, rb = a["converged_rmse_raw"], b["converged_rmse_raw"]
            delta = "n/a" if "n/a" in (ra, rb) else f"{float(rb) - float(ra):+.5f}"
            out_rows.append([sc, p, gn(ra, 4), gn(rb, 4), delta, gn(a["converged_silhouette_rmse"], 4),
                             gn(b["converged_silhouette_rmse"], 4)])
        print(table(["scene", "preset", "RMSE (c) rg32f", "RMSE (c) rg16f", "Δ", "silhouette rg32f",
                     "silhouette rg16f"], out_rows))
    times = sec("intermediates_time")
    if times:
        t = {(r["backend"], r["preset"], r["variant"]): r for r in times}
        blur = "blur_ms" if "blur_ms" in times[0] else "blur_h_ms"  # the one blur pass, or its first half
        r0 = times[0]
        print(f"\n### Intermediates: time per preset ({r0['scene']}, {r0['width']}x{r0['height']}, median ms; "
              "a preset's two formats measured one after another)\n")
        out_rows = []
        for (b, p) in dict.fromkeys((r["backend"], r["preset"]) for r in times):
            a, h = t.get((b, p, "rg32f")), t.get((b, p, "rg16f"))
            if not a or not h:
                continue
            out_rows.append([b, p, f(a["total_ms"]), f(h["total_ms"]),
                             f"{float(h['total_ms']) / float(a['total_ms']):.2f}", f(a["ao_sample_ms"]),
                             f(h["ao_sample_ms"]), f(a[blur]), f(h[blur])])
        print(table(["backend", "preset", "total rg32f", "total rg16f", "rg16f ÷ rg32f", "ao_sample rg32f",
                     "ao_sample rg16f", f"{blur[:-3]} rg32f", f"{blur[:-3]} rg16f"], out_rows))

    two = sec("two_layer")
    if two:
        print("\n### Two depth layers (medium)\n")
        print(table(["backend", "variant", "total ms", "RMSE (a)", "bias (a)", "RMSE (b)", "bias (b)"],
                    [[r["backend"], r["variant"], f(r["total_ms"]), g(r["ao_rmse_raw"]), g(r["ao_bias_raw"], 2),
                      g(r["obscurance_rmse_raw"]), g(r["obscurance_bias_raw"], 2)] for r in two]))

    path = os.path.join(folder, "precision.csv")
    if os.path.exists(path):
        with open(path, newline="") as fh:
            prec = list(csv.DictReader(fh))
        print("\n### Precision (paper Figures 3, 4): worst / 99th-percentile |z error| and face-normal error\n")
        print(table(["backend", "format", "far m", "convention", "clip", "bin m", "z worst m", "z p99 m",
                     "normal worst °", "normal p99 °", "pixels"],
                    [[r["backend"], r["format"], r["far_m"] if r["far_m"] == "inf" else f(r["far_m"], 0),
                      r["convention"], r["clip"], r["distance_bin_m"], g(r["z_worst_m"], 2), g(r["z_p99_m"], 2),
                      g(r["normal_worst_deg"], 2), g(r["normal_p99_deg"], 2), r["pixels"]] for r in prec]))
    per_tap = read_csv(os.path.join(folder, "per_tap.csv"))
    if per_tap:
        timing = ", ".join(dict.fromkeys(r["timing_method"] for r in per_tap if r.get("timing_method")))
        print(f"\n### Per-tap cost: ao_sample beside minimal passes of our own ({per_tap[0]['width']}x"
              f"{per_tap[0]['height']}, median ms of {per_tap[0]['runs']} runs"
              f"{'; ' + timing if timing else ''})\n")
        print("ns/px/tap: the least-squares slope of the median time against s, per pixel; fixed: its intercept; "
              "× (a): the slope over the fragment baseline's.\n")
        counts = sorted({int(r["samples"]) for r in per_tap})
        series = {}
        for r in per_tap:
            series.setdefault(r["variant"], (r["label"], {}))[1][int(r["samples"])] = float(r["median_ms"])
        pixels = float(per_tap[0]["width"]) * float(per_tap[0]["height"])

        def slope_intercept(at):
            xs = sorted(at)
            mx, my = sum(xs) / len(xs), sum(at[x] for x in xs) / len(xs)
            k = sum((x - mx) * (at[x] - my) for x in xs) / sum((x - mx) ** 2 for x in xs)
            return k, my - k * mx

        base = slope_intercept(series["a_fragment"][1])[0] if "a_fragment" in series else float("nan")
        rows_out = []
        for variant, (label, at) in series.items():
            k, c = slope_intercept(at)
            rows_out.append([label, f"{k * 1e6 / pixels:.2f}", f"{c:.1f}", f"{k / base:.2f}"] +
                            [f(at.get(n, "")) for n in counts])
        print(table(["variant", "ns/px/tap", "fixed ms", "× (a)"] + [f"s={n} ms" for n in counts], rows_out))
    return "\n".join(out).lstrip("\n") + "\n"


# ---- the committed runs: generated pages and the key figures of docs/BENCHMARKS.md
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = "docs/generated/bench-data"
DOC = "docs/BENCHMARKS.md"
BEGIN = "<!-- markdown_tables.py: begin (generated; /usr/bin/python3 samples/bench/markdown_tables.py --write) -->"
END = "<!-- markdown_tables.py: end -->"
REFRESH = "/usr/bin/python3 samples/bench/markdown_tables.py --write"


def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def run_info(folder):
    info = {}
    with open(os.path.join(folder, "run.txt")) as fh:
        for line in fh:
            if line.strip():
                key, _, value = line.partition(":")
                info[key.strip()] = value.strip()
    return info


def page(name, folder):
    info = run_info(folder)
    lines = [f"<!-- Generated by samples/bench/markdown_tables.py from {DATA}/{name}/: do not edit.",
             f"     Refresh with {REFRESH} (ctest: docs.benchmark_tables). -->",
             f"# sao-bench run `{name}`", "",
             f"The tables of one run of [docs/BENCHMARKS.md](../BENCHMARKS.md) (how to read them: that page); "
             f"raw data: [`bench-data/{name}/`](bench-data/{name}/).", ""]
    lines += [f"* {k}: {v}" for k, v in info.items()]
    return "\n".join(lines) + "\n\n" + tables(folder)


def median(values):
    v = sorted(values)
    return v[len(v) // 2] if len(v) % 2 else (v[len(v) // 2 - 1] + v[len(v) // 2]) / 2


def key_figures(runs):
    """The key-figures table: radius ratios per run, preset errors and precision of the main run."""
    curves = ("SAO (z hierarchy)", "SAO (no hierarchy)", "AlchemyAO-style")
    sweeps = []  # (backend, size, {(curve, radius): ms}) in run order
    for name, folder in runs:
        if name.startswith("gpu-"):  # another machine: its backends' names would mix with this one's
            continue
        rad = [r for r in read_csv(os.path.join(folder, "results.csv")) if r["section"] == "radius"]
        if rad:
            sweeps.append((rad[0]["backend"], f"{rad[0]['width']}×{rad[0]['height']}",
                           {(r["variant"], float(r["radius_m"])): float(r["ao_sample_ms"]) for r in rad}))

    def per_backend(ratio, bold=False):
        parts = []
        for backend in dict.fromkeys(b for b, _, _ in sweeps):
            values = [ratio(by) for b, _, by in sweeps if b == backend]
            text = f"{backend} " + ", ".join(f"{x:.2f}" for x in values)
            if len(values) > 1:
                m = f"median {median(values):.2f}"
                text += f" ({'**' + m + '**' if bold else m})"
            parts.append(text)
        return "; ".join(parts)

    rows = []
    if sweeps:
        size = sweeps[0][1]
        alch, sao, noh = curves[2], curves[0], curves[1]
        rows += [
            [f"AlchemyAO-style baseline ÷ SAO, ao_sample time, r = 1.5 m, {size}",
             per_backend(lambda by: by[(alch, 1.5)] / by[(sao, 1.5)], True), "7×"],
            ["the same at r = 4 m", per_backend(lambda by: by[(alch, 4.0)] / by[(sao, 4.0)]), "grows with r"],
            ["SAO time at r = 4 m ÷ time at r = 0.1 m (ao_sample, z hierarchy)",
             per_backend(lambda by: by[(sao, 4.0)] / by[(sao, 0.1)], True), "flat"],
            ["the same without the hierarchy", per_backend(lambda by: by[(noh, 4.0)] / by[(noh, 0.1)]), "grows"],
            ["the same, AlchemyAO-style", per_backend(lambda by: by[(alch, 4.0)] / by[(alch, 0.1)]), "grows"],
        ]

    full = [folder for name, folder in runs if name.startswith("full-")]
    main = full[-1] if full else runs[0][1]  # the latest full run (names end in their date)
    presets = [r for r in read_csv(os.path.join(main, "results.csv")) if r["section"] == "presets"]
    if presets:
        scene = presets[0]["scene"]
        backends = list(dict.fromkeys(r["backend"] for r in presets))
        cell = lambda r: f"{r['preset']} {g(r['ao_rmse_raw'])} / {g(r['obscurance_rmse_raw'])}"
        by_backend = {b: [cell(r) for r in presets if r["scene"] == scene and r["backend"] == b] for b in backends}
        same = all(v == by_backend[backends[0]] for v in by_backend.values())
        rows.append([f"RMSE vs (a) / (b), raw, default scene ({scene})" +
                     (f", identical on {', '.join(backends[:-1])} and {backends[-1]}" if same and len(backends) > 1 else ""),
                     ", ".join(by_backend[backends[0]]) if same else
                     "; ".join(f"{b}: " + ", ".join(v) for b, v in by_backend.items()), "—"])
        medium = [r for r in presets if r["preset"] == "medium" and r["backend"] == backends[0]]
        rows.append([f"fitted scale vs (b), medium ({backends[0]}; > 1: the effect is too light)",
                     ", ".join(f"{r['scene']} {g(r['obscurance_fitted_scale'])}" for r in medium), "—"])

    prec = read_csv(os.path.join(main, "precision.csv"))

    def precision(fmt, far, convention, clip, columns):
        picked = [r for r in prec if (r["format"], r["far_m"], r["convention"]) == (fmt, far, convention)
                  and (clip is None or r["clip"] == clip)]
        backends = list(dict.fromkeys(r["backend"] for r in picked))
        text = lambda b: ", ".join(" / ".join(g(r[c], 2) for c in columns) + f" at {r['distance_bin_m']} m"
                                   for r in picked if r["backend"] == b)
        if not picked:
            return None
        if all(text(b) == text(backends[0]) for b in backends):
            return f"{text(backends[0])} ({' and '.join(backends)})"
        return "; ".join(f"{b}: {text(b)}" for b in backends)

    for label, args, paper in (
            ("camera-space z, worst case m, D32F reversed-Z infinite far", ("D32F", "inf", "reversed", None, ["z_worst_m"]),
             "~2 mm worst case"),
            ("camera-space z, worst case m, D24 standard [-1,1] infinite far", ("D24", "inf", "standard", "-1..1", ["z_worst_m"]), ""),
            ("face-normal error within faces, 99th percentile / worst °, D32F reversed-Z infinite far",
             ("D32F", "inf", "reversed", None, ["normal_p99_deg", "normal_worst_deg"]), "≤ 0.2°"),
            ("face-normal error, 99th percentile / worst °, D24 standard [-1,1] infinite far",
             ("D24", "inf", "standard", "-1..1", ["normal_p99_deg", "normal_worst_deg"]), ""),
            ("face-normal error, 99th percentile / worst °, D16 reversed-Z infinite far",
             ("D16", "inf", "reversed", None, ["normal_p99_deg", "normal_worst_deg"]), "")):
        value = precision(*args)
        if value:
            rows.append([label, value, paper])
    return table(["figure", "measured here", "paper"], rows)


def generated():
    folder = os.path.join(ROOT, DATA)
    names = sorted(n for n in os.listdir(folder) if os.path.isfile(os.path.join(folder, n, "results.csv")))
    if not names:
        raise ValueError(f"no run under {DATA}/ (each needs a results.csv)")
    runs = [(n, os.path.join(folder, n)) for n in names]
    outputs = {f"docs/generated/benchmarks-{n}.md": page(n, d) for n, d in runs}
    with open(os.path.join(ROOT, DOC)) as fh:
        doc = fh.read()
    if doc.count(BEGIN) != 1 or doc.count(END) != 1:
        raise ValueError(f"{DOC} must hold the markers once each:\n  {BEGIN}\n  {END}")
    head, rest = doc.split(BEGIN)
    outputs[DOC] = f"{head}{BEGIN}\n{key_figures(runs)}\n{END}{rest.split(END)[1]}"
    return outputs


def write_or_check(check):
    import difflib
    try:
        outputs = generated()
    except (OSError, ValueError, KeyError, ZeroDivisionError) as e:
        sys.exit(f"markdown_tables.py: {type(e).__name__}: {e}")
    stale = []
    for rel, text in outputs.items():
        path = os.path.join(ROOT, rel)
        old = open(path).read() if os.path.exists(path) else ""
        if old == text:
            continue
        if check:
            stale.append(rel)
            diff = list(difflib.unified_diff(old.splitlines(), text.splitlines(), rel, "generated", lineterm=""))
            print("\n".join(diff[:40] + (["..."] if len(diff) > 40 else [])))
        else:
            with open(path, "w") as fh:
                fh.write(text)
            print(f"wrote {rel}")
    orphans = [n for n in os.listdir(os.path.join(ROOT, "docs/generated"))
               if n.startswith("benchmarks-") and f"docs/generated/{n}" not in outputs]
    if orphans:
        sys.exit(f"markdown_tables.py: docs/generated/{', '.join(orphans)} has no run in {DATA}/: remove it")
    if stale:
        sys.exit(f"stale: {', '.join(stale)} differ from what {DATA}/ gives; refresh with: {REFRESH}")
    if check:
        print(f"the benchmark pages and the key figures of {DOC} match {DATA}/")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    if sys.argv[1] in ("--write", "--check"):
        write_or_check(sys.argv[1] == "--check")
    elif sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    else:
        sys.stdout.write(tables(sys.argv[1]))
