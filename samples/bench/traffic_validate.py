#!/usr/bin/env python3
"""Checks the memory-traffic model against llvmpipe: the model's bytes per pixel for this CPU
(traffic.csv from `sao-bench --sections traffic`) beside the ao_sample times of the radius sweep
in the committed runs (docs/generated/bench-data/*/results.csv, 1920x1080 rows; the median of the
runs per point). Fits time = t0 + k * bytes over every curve and radius, per cache level, and
prints the fit, its correlation, and the predicted and measured time ratios to SAO side by side.

usage: traffic_validate.py TRAFFIC_CSV [BENCH_DATA_DIR]"""
import collections
import csv
import glob
import os
import statistics
import sys

CURVES = ['SAO (z hierarchy)', 'SAO (no hierarchy)', 'AlchemyAO-style']
MACHINE = 'this CPU (llvmpipe-like)'


def fit(x, y):
    """Least squares y = a + k x; returns a, k and the correlation."""
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((a - mx) ** 2 for a in x)
    syy = sum((b - my) ** 2 for b in y)
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    if sxx == 0 or syy == 0:
        sys.exit('traffic_validate: no spread to fit')
    k = sxy / sxx
    return my - k * mx, k, sxy / (sxx * syy) ** 0.5


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    data = sys.argv[2] if len(sys.argv) == 3 else os.path.join(os.path.dirname(__file__), '../../docs/generated/bench-data')
    times = collections.defaultdict(list)
    for path in sorted(glob.glob(os.path.join(data, '*', 'results.csv'))):
        for r in csv.DictReader(open(path)):
            if r['section'] == 'radius' and r['width'] == '1920' and r['ao_sample_ms']:
                times[(r['variant'], float(r['radius_m']))].append(float(r['ao_sample_ms']))
    model = {}
    for r in csv.DictReader(open(sys.argv[1])):
        if r['section'] == 'radius' and r['machine'] == MACHINE and r['width'] == '1920':
            model[(r['variant'], float(r['radius_m']))] = (float(r['l2_bytes_per_pixel']),
                                                            float(r['memory_bytes_per_pixel']))
    radii = sorted({k[1] for k in model if all((c, k[1]) in model and (c, k[1]) in times for c in CURVES)})
    if len(radii) < 2:
        sys.exit('traffic_validate: fewer than two radii with both model rows (1920x1080, %s) and timings' % MACHINE)
    t = {(c, r): statistics.median(times[(c, r)]) for c in CURVES for r in radii}
    runs = min(len(times[(c, r)]) for c in CURVES for r in radii)
    print('%d radii, at least %d timed runs per point (median)' % (len(radii), runs))
    for level, name in ((0, 'from L2'), (1, 'from memory')):
        x = [model[(c, r)][level] for c in CURVES for r in radii]
        y = [t[(c, r)] for c in CURVES for r in radii]
        a, k, corr = fit(x, y)
        print('\nbytes %s: ao_sample ms = %.1f + %.4f * bytes/px (correlation %.3f)' % (name, a, k, corr))
        print('| r (m) | model bytes/px SAO, no hier., AlchemyAO-style | model ratio no hier. / AlchemyAO-style | '
              'predicted time ratio | measured time ratio |')
        print('|---|---|---|---|---|')
        ratios_model, ratios_time = [], []
        for r in radii:
            b = [model[(c, r)][level] for c in CURVES]
            p = [a + k * v for v in b]
            m = [t[(c, r)] for c in CURVES]
            ratios_model += [b[1] / b[0], b[2] / b[0]]
            ratios_time += [m[1] / m[0], m[2] / m[0]]
            print('| %g | %.1f, %.1f, %.1f | %.2f / %.2f | %.2f / %.2f | %.2f / %.2f |' % (
                r, b[0], b[1], b[2], b[1] / b[0], b[2] / b[0], p[1] / p[0], p[2] / p[0], m[1] / m[0], m[2] / m[0]))
        print('correlation of the byte ratios with the time ratios: %.3f' % fit(ratios_model, ratios_time)[2])


if __name__ == '__main__':
    main()
