#!/usr/bin/python3
"""The fair silhouette measurement's arithmetic (scripts/silhouette_fair.py) on cases with known
answers: the contour distance of a line and its shifted copy, coverage masks from runs, the
crossing of an error curve in log-log and popping interpolated at a triangle budget."""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import silhouette_fair as fair  # noqa: E402

failures = []


def check(what, ok):
    print(f"{'ok  ' if ok else 'FAIL'} {what}")
    if not ok:
        failures.append(what)


# A horizontal line of contour points and the same line one pixel lower: every point is exactly one
# pixel from the other line, both ways; adding a far outlier moves the maximum, not the 95th
# percentile.
line = np.array([[x, 10.0] for x in range(200)])
mean, p95, worst = fair.contour_distance(line, line + [0.0, 1.0])
check("a line against itself one pixel lower: mean, 95th percentile and maximum 1", (mean, p95, worst) == (1.0, 1.0, 1.0))
mean, p95, worst = fair.contour_distance(line, np.vstack([line, [[100.0, 40.0]]]))
check("one outlier 30 px away: maximum 30, mean 30/401, 95th percentile 0",
      worst == 30.0 and math.isclose(mean, 30.0 / 401) and p95 == 0.0)
check("an empty contour is infinitely far", fair.contour_distance(line, np.empty((0, 2)))[0] == math.inf)

# Coverage runs (y, x_begin, x_end exclusive) at the measurement's sample grid.
runs = np.array([0, 2, 5, 3, 0, 1, 3, 7, 9])
mask = fair.coverage_mask(runs)
w, h = fair.SIZE[0] * fair.SAMPLES, fair.SIZE[1] * fair.SAMPLES
check("coverage mask: the grid's shape", mask.shape == (h, w))
check("coverage mask: exactly the runs' samples", mask.sum() == 3 + 1 + 2 and mask[0, 2:5].all() and mask[3, 0]
      and mask[3, 7:9].all() and not mask[3, 1:7].any() and not mask[1].any())
check("coverage mask: a run to the right edge", fair.coverage_mask(np.array([5, w - 3, w])).sum() == 3)

# The crossing of a curve falling as 1/triangles, straight in log-log: exact between two points.
curve = [(1000.0, 0.1), (2000.0, 0.05), (4000.0, 0.025)]
check("crossing between points (1/t curve: 0.04 at 2500)", math.isclose(fair.crossing(curve, 0.04), 2500.0))
check("crossing at a measured point", math.isclose(fair.crossing(curve, 0.05), 2000.0))
check("a curve already below the target crosses at its first point", fair.crossing(curve, 0.2) == 1000.0)
check("a curve that never reaches the target has no crossing", fair.crossing(curve, 0.01) is None)
check("popping interpolated in log(triangles)", math.isclose(fair.at_budget([(1000.0, 0.0), (4000.0, 1.0)], 2000.0), 0.5))
check("outside the measured triangles: no value", fair.at_budget([(1000.0, 0.0), (4000.0, 1.0)], 5000.0) is None)

sys.exit(1 if failures else 0)
