"""Why are the anisotropic AREA columns of Tables 1-2 not reproduced?  (investigation)

Each hypothesis is a small function T -> (A/A0, W/A0) over the printed separations of one
table, with a one-line rationale.  Everything else (loads, Hertz numerics) is the paper's
numerics (hertz="paper": e1 from (33) clipped, K, E from (36)-(39)) unless the hypothesis
says otherwise.  No factor is fitted.  Run:

    .venv/bin/python investigations/area_columns.py

Findings: docs/investigations/area_columns.md.
"""
from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
from numpy.polynomial.legendre import leggauss

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _infra import (  # noqa: E402
    E_STAR, ElasticPrefactors, PolarGeometry, ellipse, load_tables, polar_integral_g,
    theta_rule_on,
)

TABLES = load_tables()
HYPOTHESES = []


def hyp(name, why):
    def deco(f):
        HYPOTHESES.append((name, why, f))
        return f
    return deco


# ------------------------------------------------------------------------------------------
# polar building blocks (docs/derivation.md), θ over (a, b) with |cs|; signed curvatures
# ------------------------------------------------------------------------------------------
def nodes(S, a=0.0, b=0.5 * math.pi, level=4):
    s40, s04 = math.sqrt(S.m40), math.sqrt(S.m04)
    k = s40 / s04
    br = []
    for lam in (1.0, ellipse.PAPER_LAMBDA_CLIP):
        for rho in (lam**2, 1 / lam**2):
            t0 = math.atan(k / rho)
            br += [t0, math.pi - t0, -t0]
    th, w = theta_rule_on(a, b, br, level)
    x4, x6 = s40 * np.cos(th), s04 * np.sin(th)  # |ξ4|, |ξ6| per unit r/√μ (signed off-quadrant)
    rho = np.abs(x4) / np.abs(x6)
    lam = np.sqrt(np.minimum(rho, 1 / rho))
    return dict(
        th=th, w=w, cs=np.abs(np.cos(th) * np.sin(th)), x4=x4, x6=x6, lam=lam, rho=rho,
        c=0.5 * (np.abs(x4) + np.abs(x6)),
        g=(math.sqrt(S.beta1) * np.cos(th) + math.sqrt(S.beta2) * np.sin(th)) / math.sqrt(S.mu),
        hp=ellipse.hertz_factors(lam, "paper"), hx=ellipse.hertz_factors(lam, "exact"),
    )


def area_int(T, N, F, l=None, r_pow=2.0, nu=1.0):
    """π D √(m00 μ) Σ w |cs| F ∫ r^{r_pow} e^{-r²/2} J_ν(r g − l); F is f1/c-like."""
    S = T["S"]
    l = S.l_from_s(T["s"]) if l is None else l
    return ElasticPrefactors.of(S).area * polar_integral_g(N["g"], N["w"] * N["cs"] * F, l, r_pow, nu)


def load_int(T, N, F, l=None):
    """(4/3) D E* (m00 μ)^{3/4} Σ w |cs| F ∫ r^{5/2} e^{-r²/2} J_{3/2}(r g − l); F is f2/√c-like."""
    S = T["S"]
    l = S.l_from_s(T["s"]) if l is None else l
    return E_STAR * ElasticPrefactors.of(S).load * polar_integral_g(N["g"], N["w"] * N["cs"] * F, l, 2.5, 1.5)


def std_load(T, N):
    return load_int(T, N, N["hp"].f2 / np.sqrt(N["c"]))


def KE_paper(N):
    return N["hp"].K, N["hp"].E, N["hp"].e1


# ------------------------------------------------------------------------------------------
# hypotheses
# ------------------------------------------------------------------------------------------
@hyp("H00 baseline (paper numerics)", "(52)/(53) with (33) clipped + (36)-(39): the current reading")
def h00(T):
    N = nodes(T["S"])
    return area_int(T, N, N["hp"].f1 / N["c"]), std_load(T, N)


@hyp("H01 exact Hertz (area+load)", "exact (27) inversion and exact K, E in both integrals")
def h01(T):
    N = nodes(T["S"])
    return area_int(T, N, N["hx"].f1 / N["c"]), load_int(T, N, N["hx"].f2 / np.sqrt(N["c"]))


@hyp("H02 area uses f2", "copy-paste of the load's deviation factor into (52)")
def h02(T):
    N = nodes(T["S"])
    return area_int(T, N, N["hp"].f2 / N["c"]), std_load(T, N)


@hyp("H03 f1 = E/(K e1^2)", "power slip on (1-e^2)^{1/2} in (46)")
def h03(T):
    N = nodes(T["S"]); K, E, e1 = KE_paper(N)
    return area_int(T, N, E / (K * e1**2) / N["c"]), std_load(T, N)


@hyp("H04 f1 = sqrt(E/K)/e1", "power slip: f2-like square root on E/K")
def h04(T):
    N = nodes(T["S"]); K, E, e1 = KE_paper(N)
    return area_int(T, N, np.sqrt(E / K) / e1 / N["c"]), std_load(T, N)


@hyp("H05 f1 = E/(K sqrt(e1))", "power slip: (1-e^2)^{1/4}")
def h05(T):
    N = nodes(T["S"]); K, E, e1 = KE_paper(N)
    return area_int(T, N, E / (K * np.sqrt(e1)) / N["c"]), std_load(T, N)


@hyp("H06 f1 = 2E/(K e1^2) (Fortran **1/2)", "(1.-E**2)**1/2 parses as (1-e^2)/2 in Fortran")
def h06(T):
    N = nodes(T["S"]); K, E, e1 = KE_paper(N)
    return area_int(T, N, 2 * E / (K * e1**2) / N["c"]), std_load(T, N)


@hyp("H07 f1 = 1/(K e1) (E dropped)", "E(e) omitted from the area factor")
def h07(T):
    N = nodes(T["S"]); K, E, e1 = KE_paper(N)
    return area_int(T, N, 1 / (K * e1) / N["c"]), std_load(T, N)


@hyp("H08 f1: e1 (33) but exact K,E", "area factor computed with exact K, E, load with polynomials")
def h08(T):
    N = nodes(T["S"]); e1 = N["hp"].e1
    return area_int(T, N, ellipse.f1(e1, "exact") / N["c"]), std_load(T, N)


@hyp("H09 f1: e1 exact, K,E polynomial", "exact λ→e1 inversion in the area, (33) in the load")
def h09(T):
    N = nodes(T["S"]); e1 = N["hx"].e1
    return area_int(T, N, ellipse.f1(e1, "paper") / N["c"]), std_load(T, N)


@hyp("H10 f1 at e1:=λ (no inversion)", "λ passed where e1 is expected in the area factor")
def h10(T):
    N = nodes(T["S"])
    return area_int(T, N, ellipse.f1(np.minimum(N["lam"], 1.0), "paper") / N["c"]), std_load(T, N)


@hyp("H11 f1 at e1 from (33)(λ²)", "the code's 'lambda' holds b²/a² = λ² in (33), area only")
def h11(T):
    N = nodes(T["S"])
    e1 = ellipse.e1_from_lambda(N["lam"] ** 2, "paper")
    return area_int(T, N, ellipse.f1(e1, "paper") / N["c"]), std_load(T, N)


def kappa_from44(N, lam2):
    """(44): κ_m/r = ½ |ξ6| (1 + λ²) per unit r, with the larger curvature as |ξ6| (turned)."""
    big = np.maximum(np.abs(N["x4"]), np.abs(N["x6"]))
    return 0.5 * big * (1 + lam2)


@hyp("H12 κm (44) with λ not λ² (area)", "(44) coded with (1+λ) in the area integral only")
def h12(T):
    N = nodes(T["S"])
    return area_int(T, N, N["hp"].f1 / kappa_from44(N, N["lam"])), std_load(T, N)


@hyp("H13 κm (44) with λ not λ² (both)", "(44) coded with (1+λ) in both integrals")
def h13(T):
    N = nodes(T["S"]); k = kappa_from44(N, N["lam"])
    return area_int(T, N, N["hp"].f1 / k), load_int(T, N, N["hp"].f2 / np.sqrt(k))


@hyp("H14 κm (44), λ² from (32)(e1 of 33), area", "'λ from (32)' below (43): λ² = e1²[ln(4/e1)-1]")
def h14(T):
    N = nodes(T["S"]); e1 = N["hp"].e1
    lam2 = ellipse.lambda_squared_small_e1(e1)
    return area_int(T, N, N["hp"].f1 / kappa_from44(N, lam2)), std_load(T, N)


@hyp("H15 κm (44), λ² from (32)(e1 of 33), both", "as H14 in both integrals")
def h15(T):
    N = nodes(T["S"]); e1 = N["hp"].e1
    k = kappa_from44(N, ellipse.lambda_squared_small_e1(e1))
    return area_int(T, N, N["hp"].f1 / k), load_int(T, N, N["hp"].f2 / np.sqrt(k))


@hyp("H16 κm = |ξ6|/2 (no 1+λ²), area", "highly-eccentric limit of (44) used in the area")
def h16(T):
    N = nodes(T["S"])
    return area_int(T, N, N["hp"].f1 / kappa_from44(N, 0.0)), std_load(T, N)


@hyp("H17 κm (44) unturned for λ>1, both", "(44) with ω6 always (no turn): κ = ½|ξ6|(1+λ²), λ² = min ratio")
def h17(T):
    N = nodes(T["S"])
    k = 0.5 * np.abs(N["x6"]) * (1 + np.minimum(N["rho"], 1 / N["rho"]))
    return area_int(T, N, N["hp"].f1 / k), load_int(T, N, N["hp"].f2 / np.sqrt(k))


@hyp("H18 κm = mean κ̄m (70), area", "a single mean summit curvature (70) in the area")
def h18(T):
    S = T["S"]; N = nodes(S)
    kbar = S.mean_summit_curvature / math.sqrt(S.mu)  # per-r units: c r ↔ κ/√μ
    return area_int(T, N, N["hp"].f1 / kbar, r_pow=3.0), std_load(T, N)


def piAB(N, e1, swap=False):
    """π A B / (π ω) per unit r (area-integrand form ~ F/c): (21), (34), (35).
    a² = 2ω/|ξ_small| (semi-major), λ² = b²/a²; πAB = π a² λ² e1/(λ²+e1²).
    swap: a taken as the semi-MINOR axis as the text of section 3 says (a² = 2ω/|ξ_big|,
    λ² = b²/a² = 1/λ_true² ≥ 1)."""
    small = np.minimum(np.abs(N["x4"]), np.abs(N["x6"]))
    big = np.maximum(np.abs(N["x4"]), np.abs(N["x6"]))
    lam2 = N["lam"] ** 2
    if not swap:
        return 2 * lam2 * e1 / (small * (lam2 + e1**2))
    L2 = 1 / lam2
    return 2 * L2 * e1 / (big * (L2 + e1**2))


@hyp("H19 area = πAB, (21),(34),(35), e1 (33)", "the Remark after (47): A_i = πAB")
def h19(T):
    N = nodes(T["S"])
    return area_int(T, N, piAB(N, N["hp"].e1)), std_load(T, N)


@hyp("H20 area = πAB, a semi-minor (text)", "section 3 text: a semi-minor, b semi-major")
def h20(T):
    N = nodes(T["S"])
    return area_int(T, N, piAB(N, N["hp"].e1, swap=True)), std_load(T, N)


@hyp("H21 area prefactor √m00 (not √(m00μ))", "μ dropped in (52)'s prefactor only: ×1/√μ")
def h21(T):
    A, W = h00(T)
    return A / math.sqrt(T["S"].mu), W


@hyp("H22 area: (ω1 - s) over ω1 > l", "s in the interference, l in the limit (area only)")
def h22(T):
    S = T["S"]; N = nodes(S); l = S.l_from_s(T["s"]); s = T["s"]
    # t' = ω1 - s = t + (l - s):  ∫ (t + d) φ = J1 + d J0
    F = N["hp"].f1 / N["c"]
    A1 = area_int(T, N, F)
    A0 = np.array([area_int(T, N, F, l=np.array([li]), nu=0.0)[0] for li in l])
    return A1 + (l - s) * A0, std_load(T, N)


@hyp("H23 area with l = s (load with l)", "the area integral run with l = s, the load with s/√μ")
def h23(T):
    N = nodes(T["S"])
    return area_int(T, N, N["hp"].f1 / N["c"], l=T["s"]), std_load(T, N)


@hyp("H24 ω4, ω6 ∈ ℝ (printed (16)), ÷D_sum", "printed limits of (16): saddles counted, |ω4ω6|")
def h24(T):
    S = T["S"]; A = 0; W = 0
    for a, b in ((0, math.pi / 2), (math.pi / 2, math.pi), (-math.pi / 2, 0)):
        N = nodes(S, a, b)
        A = A + area_int(T, N, N["hp"].f1 / N["c"]); W = W + std_load(T, N)
    return A, W


@hyp("H25 ω4, ω6 ∈ ℝ, ÷ numerical (16) = 2 D_sum", "as H24, p_sum normalised by its printed-limit integral")
def h25(T):
    A, W = h24(T)
    return A / 2, W / 2


# --- Cartesian Gauss-Legendre 50-point product rule on truncated boxes --------------------
def gl_box(T, L1, L4, L6, n=50, absolute_top=None):
    S = T["S"]; mu = S.mu; D = S.summit_density
    x, wx = leggauss(n)
    def rule(a, b):
        return 0.5 * (b - a) * x + 0.5 * (b + a), 0.5 * (b - a) * wx
    w4, ww4 = rule(0.0, L4); w6, ww6 = rule(0.0, L6)
    W4, W6 = np.meshgrid(w4, w6, indexing="ij")
    k4, k6 = W4 * math.sqrt(S.m40 * mu), W6 * math.sqrt(S.m04 * mu)  # |ξ4|, |ξ6|
    rho = k4 / k6
    lam = np.sqrt(np.minimum(rho, 1 / rho))
    hf = ellipse.hertz_factors(lam, "paper")
    kap = 0.5 * (k4 + k6)
    mean = math.sqrt(S.beta1) * W4 + math.sqrt(S.beta2) * W6
    base = mu**2 / math.sqrt(2 * math.pi) * W4 * W6 * np.exp(-0.5 * mu * (W4**2 + W6**2))
    base = base * np.outer(ww4, ww6)
    pa = math.pi * D * math.sqrt(S.m00 * mu)
    pw = 4 / 3 * D * E_STAR * (S.m00 * mu) ** 0.75
    A, W = [], []
    for l in S.l_from_s(T["s"]):
        top = l + L1 if absolute_top is None else absolute_top
        w1, ww1 = rule(l, top)
        t = w1 - l
        G = np.exp(-0.5 * (w1[:, None, None] - mean[None]) ** 2) * ww1[:, None, None]
        A.append(pa * np.einsum("i,ijk,jk->", t, G, base * hf.f1 / kap))
        W.append(pw * np.einsum("i,ijk,jk->", t**1.5, G, base * hf.f2 / np.sqrt(kap)))
    return np.array(A), np.array(W)


for _L in (5.0, 6.0, 10.0, 20.0):
    hyp(f"H26 GL50 box ω1∈[l,l+{_L:g}], ω4,ω6∈[0,{_L:g}]", "the paper's 50-point Gauss-Legendre on a truncated box")(
        lambda T, L=_L: gl_box(T, L, L, L))
hyp("H27 GL50 box ω1∈[l,10], ω4,ω6∈[0,10]", "fixed absolute upper limit of ω1")(
    lambda T: gl_box(T, None, 10.0, 10.0, absolute_top=10.0))
hyp("H28 GL50 box ω1∈[l,l+5], ω4,ω6∈[0,10]", "short ω1 range, wide curvature box")(
    lambda T: gl_box(T, 5.0, 10.0, 10.0))


@hyp("H29 √m00 prefactor + area uses f2", "combination of two slips (H21 × H02)")
def h29(T):
    A, W = h02(T)
    return A / math.sqrt(T["S"].mu), W


@hyp("H30 √m00 prefactor + exact f1 (area)", "combination: H21 with exact Hertz in the area only")
def h30(T):
    N = nodes(T["S"])
    return area_int(T, N, N["hx"].f1 / N["c"]) / math.sqrt(T["S"].mu), std_load(T, N)


# ------------------------------------------------------------------------------------------
def evaluate():
    rows = []
    for name, why, f in HYPOTHESES:
        ra, rw = [], []
        for key in ("table1", "table2"):
            T = TABLES[key]
            A, W = f(T)
            ra.append(T["A"] / A); rw.append(T["W"] / W)
        rows.append((name, why, ra, rw))
    return rows


def main():
    rows = evaluate()
    hdr = f"{'hypothesis':44s} {'maxA-1 T1':>9s} {'T2':>8s} {'spread':>7s} {'maxW-1 T1':>9s} {'T2':>8s}"
    print("ratio = printed/computed; spread = max/min - 1 of the 12 area ratios")
    print(hdr); print("-" * len(hdr))
    for name, why, ra, rw in rows:
        allr = np.concatenate(ra)
        print(f"{name:44s} {np.max(np.abs(ra[0]-1)):9.4f} {np.max(np.abs(ra[1]-1)):8.4f} "
              f"{allr.max()/allr.min()-1:7.4f} {np.max(np.abs(rw[0]-1)):9.4f} {np.max(np.abs(rw[1]-1)):8.4f}")
    if "-v" in sys.argv:
        print()
        for name, why, ra, rw in rows:
            print(name, "--", why)
            for k, (a, w) in enumerate(zip(ra, rw)):
                print(f"   T{k+1} area", np.array2string(a, precision=4), " load", np.array2string(w, precision=4))


def diagnostics():
    """NOT hypotheses: how far the baseline area integrand must be deformed (fitted r^p, t^q,
    l-scale) to make the printed/computed ratio flat in s, and the constant that then remains."""
    for key in ("table1", "table2"):
        T = TABLES[key]; S = T["S"]; N = nodes(S); F = N["hp"].f1 / N["c"]; l = S.l_from_s(T["s"])
        print(key)
        for lab, kw in ([(f"r^{p:+.2f}", dict(r_pow=2 + p)) for p in (-0.15, -0.10)]
                        + [(f"t^{q:+.2f}", dict(nu=1 + q)) for q in (0.05, 0.10)]
                        + [(f"l*{f:.4f}", dict(l=l * f)) for f in (1.0025, 1.005)]):
            r = T["A"] / area_int(T, N, F, **kw)
            print(f"   {lab:10s}", np.array2string(r, precision=4), f"spread {r.max()/r.min()-1:.4f}")


if __name__ == "__main__":
    main()
    if "--diag" in sys.argv:
        diagnostics()
