#!/usr/bin/python3
"""Reference solution of the planar cantilever elastica (independent of slender).

Problem: an inextensible beam of length L and bending stiffness EI is clamped
horizontally at s = 0 and carries a vertical dead load P (pointing in -y) at
its free tip s = L.  With theta(s) the tangent angle, moment balance gives

    EI theta''(s) = P cos(theta(s)),   theta(0) = 0,   theta'(L) = 0,
    x'(s) = cos(theta),   y'(s) = sin(theta).

In the dimensionless arc length u = s/L this becomes theta_uu = alpha cos(theta)
with alpha = P L^2 / EI, and (x, y)/L are integrated over u in [0, 1].

The boundary-value problem is solved by shooting on k = theta'(0) (in units of
1/L): the ODE is integrated with fixed-step RK4 and the end condition
theta'(1) = 0 is solved with a bracketed secant (Illinois) iteration on the
bracket k in [-sqrt(2 alpha), 0], which holds exactly one physical root
(theta decreasing monotonically from 0 to the tip angle in (-pi/2, 0)).

Usage:
    elastica.py --alpha 0.1 2 5      # table of tip positions
    elastica.py --selftest           # quick checks, non-zero exit on failure
    from elastica import tip; tip(2.0) -> (x_tip/L, y_tip/L)
"""

import argparse
import math
import sys

DEFAULT_STEPS = 4000
SHOOT_TOL = 1e-13


def integrate(alpha, k, steps=DEFAULT_STEPS):
    """Integrate the dimensionless elastica from u=0 to u=1 with RK4.

    State is (theta, theta', x, y); theta(0)=0, theta'(0)=k, x(0)=y(0)=0.
    Returns the final state (theta, dtheta, x, y) at u = 1 and the largest
    theta' seen at the step ends (used to classify shots, see shoot()).
    """
    h = 1.0 / steps
    th, dth, x, y = 0.0, k, 0.0, 0.0
    dth_max = -math.inf
    cos, sin = math.cos, math.sin
    for _ in range(steps):
        # f(state) = (theta', alpha cos theta, cos theta, sin theta)
        c1, s1 = cos(th), sin(th)
        k1 = (dth, alpha * c1, c1, s1)

        t2 = th + 0.5 * h * k1[0]
        c2, s2 = cos(t2), sin(t2)
        k2 = (dth + 0.5 * h * k1[1], alpha * c2, c2, s2)

        t3 = th + 0.5 * h * k2[0]
        c3, s3 = cos(t3), sin(t3)
        k3 = (dth + 0.5 * h * k2[1], alpha * c3, c3, s3)

        t4 = th + h * k3[0]
        c4, s4 = cos(t4), sin(t4)
        k4 = (dth + h * k3[1], alpha * c4, c4, s4)

        th += h / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        dth += h / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        x += h / 6.0 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])
        y += h / 6.0 * (k1[3] + 2 * k2[3] + 2 * k3[3] + k4[3])
        if dth > dth_max:
            dth_max = dth
    return th, dth, x, y, dth_max


def shoot(alpha, steps=DEFAULT_STEPS, tol=SHOOT_TOL):
    """Find k = theta'(0) such that theta'(1) = 0 (physical branch).  Returns k.

    First integral: theta'^2 = k^2 + 2 alpha sin(theta), so theta' can only
    return to zero (at the tip angle sin(theta_t) = -k^2/(2 alpha)) if
    k^2 < 2 alpha.  Let u*(k) be where theta' first reaches 0; the physical
    root has u* = 1, and u* grows monotonically from 0 (k=0) to infinity
    (k -> -sqrt(2 alpha)).  The residual r(k) = theta'(1) therefore has the
    sign of 1 - u*: negative for k in [-sqrt(2 alpha), root), positive above,
    EXCEPT that for large alpha a shot with u* << 1 can swing past pi/2 and
    bring theta'(1) back below zero.  Such shots (theta' went positive and
    ended non-positive) are given residual +1, which keeps the bracket
    [-sqrt(2 alpha), 0] valid and the root unique for any alpha > 0.
    """
    if alpha == 0.0:
        return 0.0
    if alpha < 0.0:
        raise ValueError("alpha must be >= 0 (load along -y)")

    def resid(k):
        _, dth, _, _, dth_max = integrate(alpha, k, steps)
        if dth_max > 0.0 and dth <= 0.0:   # swung back: far above the root
            return 1.0
        return dth

    a, b = 0.0, -math.sqrt(2.0 * alpha)
    fa, fb = resid(a), resid(b)
    if not (fa > 0.0 and fb < 0.0):
        raise RuntimeError("elastica: bad bracket for alpha=%g (r(0)=%g, r(-sqrt(2a))=%g)"
                           % (alpha, fa, fb))

    # Illinois (modified regula falsi): secant steps that keep the bracket.
    # Tolerance on k is absolute (tol) but scaled down with the bracket size
    # for small loads so that tiny alpha still gets full relative accuracy.
    tol_k = tol * min(1.0, -b)
    side = 0
    for _ in range(400):
        k = (a * fb - b * fa) / (fb - fa)
        if not (min(a, b) < k < max(a, b)):   # safety: fall back to bisection
            k = 0.5 * (a + b)
        fk = resid(k)
        if fk == 0.0:
            return k
        if fk > 0.0:
            a, fa = k, fk
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb = k, fk
            if side == +1:
                fa *= 0.5
            side = +1
        if abs(b - a) < tol_k or abs(fk) < 1e-15 * alpha:
            break
    else:
        raise RuntimeError("elastica: shooting did not converge for alpha=%g" % alpha)
    return k   # last secant point: within tol_k of the root


def solve(alpha, steps=DEFAULT_STEPS):
    """Full solution summary: dict with k=theta'(0), tip angle, x/L, y/L."""
    k = shoot(alpha, steps)
    th, dth, x, y, _ = integrate(alpha, k, steps)
    return {"alpha": alpha, "k0": k, "theta_tip": th, "dtheta_tip": dth,
            "x": x, "y": y}


def tip(alpha, steps=DEFAULT_STEPS):
    """Tip position (x_tip/L, y_tip/L) for alpha = P L^2 / EI (load along -y)."""
    s = solve(alpha, steps)
    return s["x"], s["y"]


def first_integral_quadrature(alpha, theta_t, n=20000):
    """Arc length, x/L, y/L from the first integral, given the tip angle.

    theta runs from 0 down to theta_t with |theta'| = sqrt(2 alpha (sin theta -
    sin theta_t)).  The inverse-square-root end singularity at theta_t is
    removed by theta = theta_t - theta_t v^2 (v in [0, 1]); midpoint rule.
    """
    length = xs = ys = 0.0
    for i in range(n):
        v = (i + 0.5) / n
        th = theta_t - theta_t * v * v
        dth = -2.0 * theta_t * v / n
        # sin(th) - sin(theta_t) written without cancellation
        den = math.sqrt(4.0 * alpha * math.cos(0.5 * (th + theta_t))
                        * math.sin(0.5 * (th - theta_t)))
        w = dth / den
        length += w
        xs += math.cos(th) * w
        ys += math.sin(th) * w
    return length, xs, ys


def selftest(verbose=True):
    """Return True if the reference passes basic checks."""
    ok = True

    def check(name, cond, detail):
        nonlocal ok
        ok &= cond
        if verbose:
            print("%-46s %s  (%s)" % (name, "ok  " if cond else "FAIL", detail))

    # 1) small load -> linear Euler-Bernoulli value y/L = -alpha/3
    a = 1e-4
    x, y = tip(a)
    rel = abs(y - (-a / 3.0)) / (a / 3.0)
    check("small load: y/L vs -alpha/3 (alpha=1e-4)", rel < 1e-6,
          "y/L=%.12e, rel.dev=%.2e" % (y, rel))

    # 2) alpha=2: classic large-deflection values (Bisshopp & Drucker 1945,
    #    elliptic integrals): vertical tip deflection ~0.4935 L, horizontal
    #    tip displacement ~0.1606 L, i.e. y/L ~ -0.4935 and x/L ~ 0.8394.
    s = solve(2.0)
    check("alpha=2: y/L close to -0.4935", abs(s["y"] + 0.4935) < 2e-3,
          "y/L=%.6f" % s["y"])
    check("alpha=2: x/L close to 0.8394", abs(s["x"] - 0.8394) < 2e-3,
          "x/L=%.6f" % s["x"])

    # 2b) independent cross-check via the first integral (no ODE shooting):
    #     theta'^2 = 2 alpha (sin theta - sin theta_t), so with the tip angle
    #     from the shot, arc length, x and y are quadratures over theta.
    for a in (0.1, 2.0, 5.0):
        sa = solve(a) if a != 2.0 else s
        length, xq, yq = first_integral_quadrature(a, sa["theta_tip"])
        d = max(abs(length - 1.0), abs(xq - sa["x"]), abs(yq - sa["y"]))
        check("alpha=%g: quadrature of first integral" % a, d < 1e-7,
              "L=%.10f x/L=%.10f y/L=%.10f, max diff %.1e" % (length, xq, yq, d))

    # 3) boundary condition theta'(1)=0 is met and the shape bends downward
    check("alpha=2: theta'(1) ~ 0", abs(s["dtheta_tip"]) < 1e-10,
          "theta'(1)=%.1e" % s["dtheta_tip"])
    check("alpha=2: tip angle in (-pi/2, 0)", -math.pi / 2 < s["theta_tip"] < 0,
          "theta_tip=%.6f rad" % s["theta_tip"])

    # 4) inextensibility: chord shorter than the arc, |tip| <= L
    check("alpha=2: |tip| < L", math.hypot(s["x"], s["y"]) < 1.0,
          "|tip|/L=%.6f" % math.hypot(s["x"], s["y"]))

    # 5) step convergence: halving the RK4 step changes the tip by < 1e-10
    x2, y2 = tip(2.0, steps=DEFAULT_STEPS // 2)
    d = max(abs(x2 - s["x"]), abs(y2 - s["y"]))
    check("alpha=2: RK4 2000 vs 4000 steps", d < 1e-10, "diff=%.1e" % d)
    return ok


def main(argv=None):
    p = argparse.ArgumentParser(
        description="Reference tip position of a 2D cantilever elastica under a "
                    "vertical tip dead load (alpha = P L^2/EI), by shooting + RK4.")
    p.add_argument("--alpha", type=float, nargs="+", default=[0.1, 1.0, 2.0, 3.0, 5.0],
                   help="load parameter(s) alpha = P L^2/EI (default: 0.1 1 2 3 5)")
    p.add_argument("--steps", type=int, default=DEFAULT_STEPS,
                   help="RK4 steps over the length (default %d)" % DEFAULT_STEPS)
    p.add_argument("--selftest", action="store_true",
                   help="run self-checks; exit status 1 on failure")
    args = p.parse_args(argv)

    if args.selftest:
        ok = selftest()
        print("selftest:", "PASSED" if ok else "FAILED")
        return 0 if ok else 1

    print("%10s %18s %18s %18s %14s" % ("alpha", "x/L", "y/L", "EB y/L=-a/3", "theta_tip"))
    for a in args.alpha:
        s = solve(a, args.steps)
        print("%10g %18.12f %18.12f %18.12f %14.10f"
              % (a, s["x"], s["y"], -a / 3.0, s["theta_tip"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
