#!/usr/bin/python3
"""Bjøntegaard delta-rate and size ratios between two rate-distortion curves.

Bjøntegaard, "Calculation of average PSNR differences between RD-curves" (VCEG-M33, 2001):
fit log(rate) as a cubic polynomial of PSNR for each curve, integrate both fits over the
PSNR interval that both curves cover, and report exp(mean difference) - 1 as a percentage.
Departures: with fewer than four points the polynomial degree drops to (points - 1); the
fit is done by least squares (normal equations, pure Python) so more than four points are
allowed. The size ratio at a given PSNR interpolates log(rate) piecewise-linearly in PSNR
on each curve's Pareto front (no extrapolation) instead of using the cubic fit, because
the cubic can swing outside the measured points near the ends of the range.

A curve is a list of (rate, psnr_db) pairs; rate is any size measure (bytes, bpv) > 0.
"""
import math


class BDError(ValueError):
    """The two curves cannot be compared (too few points or no common PSNR range)."""


def pareto_front(points):
    """Points not dominated by another (smaller-or-equal rate and higher-or-equal PSNR),
    sorted by rate. Use it to merge several settings of one codec into its best curve."""
    pts = sorted((float(r), float(p)) for r, p in points
                 if r is not None and p is not None and r > 0 and math.isfinite(p))
    front = []
    for r, p in pts:
        if front and p <= front[-1][1]:
            continue  # a cheaper point already reaches this PSNR
        if front and r == front[-1][0]:
            front[-1] = (r, p)
        else:
            front.append((r, p))
    return front


def _solve(a, b):
    """Solves a x = b by Gaussian elimination with partial pivoting (small dense a)."""
    n = len(b)
    m = [list(row) + [bi] for row, bi in zip(a, b)]
    for col in range(n):
        piv = max(range(col, n), key=lambda r: abs(m[r][col]))
        if abs(m[piv][col]) < 1e-300:
            raise BDError("singular fit (repeated PSNR values?)")
        m[col], m[piv] = m[piv], m[col]
        for r in range(col + 1, n):
            f = m[r][col] / m[col][col]
            for c in range(col, n + 1):
                m[r][c] -= f * m[col][c]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (m[r][n] - sum(m[r][c] * x[c] for c in range(r + 1, n))) / m[r][r]
    return x


def polyfit(xs, ys, degree):
    """Least-squares polynomial coefficients c[0] + c[1] x + ... (x centred for conditioning
    by the caller)."""
    k = degree + 1
    ata = [[sum(x ** (i + j) for x in xs) for j in range(k)] for i in range(k)]
    aty = [sum(y * x ** i for x, y in zip(xs, ys)) for i in range(k)]
    return _solve(ata, aty)


def _poly_integral(c, lo, hi):
    return sum(ci * (hi ** (i + 1) - lo ** (i + 1)) / (i + 1) for i, ci in enumerate(c))


def _clean(curve):
    pts = [(float(r), float(p)) for r, p in curve
           if r is not None and p is not None and r > 0 and math.isfinite(p)]
    if len({p for _, p in pts}) < 2:
        raise BDError("a curve needs at least two points with distinct PSNR")
    return pts


def bd_rate(anchor, test):
    """Average rate difference of `test` against `anchor` in percent over the PSNR range
    both cover: -50 means test needs half the rate of anchor at equal PSNR.
    Returns (percent, psnr_lo, psnr_hi)."""
    a, t = _clean(anchor), _clean(test)
    lo = max(min(p for _, p in a), min(p for _, p in t))
    hi = min(max(p for _, p in a), max(p for _, p in t))
    if hi <= lo:
        raise BDError("the curves cover no common PSNR range "
                      "(anchor %.2f-%.2f dB, test %.2f-%.2f dB)"
                      % (min(p for _, p in a), max(p for _, p in a),
                         min(p for _, p in t), max(p for _, p in t)))
    centre = 0.5 * (lo + hi)
    integrals = []
    for pts in (a, t):
        xs = [p - centre for _, p in pts]
        ys = [math.log(r) for r, _ in pts]
        degree = min(3, len({round(x, 12) for x in xs}) - 1)
        c = polyfit(xs, ys, degree)
        integrals.append(_poly_integral(c, lo - centre, hi - centre) / (hi - lo))
    return (math.exp(integrals[1] - integrals[0]) - 1.0) * 100.0, lo, hi


def rate_at_psnr(curve, psnr):
    """Rate at `psnr` interpolated (log rate, linear in PSNR) on the curve's Pareto front;
    None when the curve does not reach that PSNR or starts above it."""
    front = pareto_front(curve)
    if not front or psnr < front[0][1] or psnr > front[-1][1]:
        return None
    for (r0, p0), (r1, p1) in zip(front, front[1:]):
        if p0 <= psnr <= p1:
            if p1 == p0:
                return r0
            f = (psnr - p0) / (p1 - p0)
            return math.exp(math.log(r0) + f * (math.log(r1) - math.log(r0)))
    return front[-1][0] if psnr == front[-1][1] else None


def psnr_at_rate(curve, rate):
    """PSNR at `rate` interpolated linearly in log(rate) on the Pareto front; None outside."""
    front = pareto_front(curve)
    if not front or rate < front[0][0] or rate > front[-1][0]:
        return None
    for (r0, p0), (r1, p1) in zip(front, front[1:]):
        if r0 <= rate <= r1:
            f = (math.log(rate) - math.log(r0)) / (math.log(r1) - math.log(r0))
            return p0 + f * (p1 - p0)
    return front[-1][1]


def size_ratio(other, ours, psnr):
    """rate(other) / rate(ours) at `psnr` (each interpolated on its own curve); None when
    either curve does not reach it."""
    ro, ru = rate_at_psnr(other, psnr), rate_at_psnr(ours, psnr)
    if ro is None or ru is None:
        return None
    return ro / ru


if __name__ == "__main__":
    import argparse
    import csv
    ap = argparse.ArgumentParser(description="BD-rate of TEST against ANCHOR from two CSV files "
                                             "with columns rate,psnr (header optional)")
    ap.add_argument("anchor")
    ap.add_argument("test")
    args = ap.parse_args()

    def load(path):
        out = []
        with open(path, newline="") as f:
            for row in csv.reader(f):
                try:
                    out.append((float(row[0]), float(row[1])))
                except (ValueError, IndexError):
                    continue
        return out

    pct, lo, hi = bd_rate(load(args.anchor), load(args.test))
    print("BD-rate %.2f %% over %.2f-%.2f dB" % (pct, lo, hi))
