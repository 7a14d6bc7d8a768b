#!/usr/bin/python3
"""gen_ellint_coeffs.py - generate libicshadow/src/ellint_data.{c,h} (tables for ellint.c).

Parameter convention: m = k^2, x = m1 = 1 - m (complementary parameter).

Three tables, all built at 256-bit precision with mpmath:

1. LOG region, 0 < x < X0 (DLMF 19.12.1, 19.12.2 with L = ln(16/x)):
       K(1-x) = (L/2) A(x) + B(x),            A(x) = 1 + x Pa(x),  B(x) = x Pb(x)
       E(1-x) = 1 + x ((L/2) C(x) + D(x)),    C(x) = 1/2 + x Pc(x), D(x) = -1/4 + x Pd(x)
   so that E(1-x) = 1 + x ((L - 1)/4 + x ((L/2) Pc(x) + Pd(x))).
   A, B, C, D are the power series with EXACT rational coefficients
       A = sum a_n x^n,           a_n = ((1/2)_n / n!)^2
       B = sum a_n (d_n - d_0) x^n,   d_n - d_0 = H_n - sum_{j<n} 2/(2j+1)   (psi differences)
       C = sum c_n x^n,           c_n = (1/2) (1/2)_n (3/2)_n / ((2)_n n!)
       D = sum c_n (d_n - d_0 - 1/((2n+1)(2n+2))) x^n
   (summed with exact fractions, 400 terms).  The formulas are first checked against
   mpmath.ellipk / mpmath.ellipe at many points (an independent algorithm); then Pa, Pb, Pc, Pd
   are replaced by their Chebyshev interpolants on [0, X0] (near-minimax, lower degree than the
   truncated Taylor series), written in the monomial basis and rounded to double.  They are
   stored as Pa, 2 Pb, 2 Pc, 4 Pd (exact scalings) for the form ellint.c evaluates,
       K = (1/2) [L + x (L Pa + 2Pb)],   E = 1 + (x/4) [L - 1 + x (L 2Pc + 4Pd)].

2. PIECES, X0 <= x <= 1: each binade [2^-j, 2^(1-j)) is cut into 2^S equal pieces of half-width
   h around a dyadic centre c.  On each piece
       K(1-x) = k0_hi + (k0_lo + t Pk(t)),   t = x - c,   k0_hi + k0_lo = K(1-c) (double-double)
   and the same for E; Pk, Pe are Chebyshev interpolants of (K(1-c-t) - K(1-c))/t on [-h, h].

3. LOGARITHM: ellint.c computes L = ln(16/x) (and ln(16 m1) for m < 0) inline as H + T with H
   exact: x = 2^k z, z in [sqrt(1/2), sqrt(2)), 2^LOG_B intervals of z with centre c (a double),
   1/c rounded, ln c = lhi + llo with lhi a multiple of 2^-32 (like n * LN2_HI, so their sum is
   exact), and log1p(r) = r + r^2 P(r) with P the Chebyshev interpolant of (log1p(r) - r)/r^2
   on the range of r.  Each ln c is checked against a logarithm that shares no code with mpmath
   (Python's decimal module, Decimal.ln at 70 significant digits; c and lhi + llo converted
   exactly), and the C evaluation of L is emulated here in doubles (Python floats are IEEE
   doubles with the same rounding) at thousands of points, interval ends and subnormals
   included, against mpmath.log: ln(16/x) for the log series, and ln(16 m1) for m < 0 from
   m1 = m1h + m1l (two-sum of 1 - m) with the low part entering as rel = m1l/m1h, as in
   ellint.c's ln16_times.

For the K/E tables the maximum approximation error (double coefficients evaluated exactly,
against mpmath.ellipk/ellipe at dense points) is measured, written into the output, and
asserted to be below the target.  The error is in units of the last place of the result (ulp of
K or E).  For the logarithm the emulated absolute error of L is asserted below 2^LN_TARGET_LOG2
(L/2 is the leading term of K, so 2^-58 costs at most 0.004 ulp of K).

Usage: /usr/bin/python3 scripts/gen_ellint_coeffs.py [OUTDIR]   (default libicshadow/src)
Running it again must reproduce the checked-in files byte for byte.
"""
import os
import struct
import sys
from fractions import Fraction

import mpmath
from mpmath import mp, mpf

mp.prec = 256

X0_LOG2 = -7          # log region is 0 < x < X0 = 2^-7 = 1/128
X0 = mpf(2) ** X0_LOG2
S = 3                 # 2^S pieces per binade
NLOGK = 5             # degree of Pa, Pb (K)
NLOGE = 5             # degree of Pc, Pd (E)
NK = 10               # degree of Pk (pieces)
NE = 9                # degree of Pe (pieces)
TARGET_ULP = 0.02     # approximation error target per table (ulp of the result)
NSERIES = 400
LOG_B = 7             # inline logarithm: 2^LOG_B intervals of f in [sqrt(1/2), sqrt(2))
NLOG1P = 4            # degree of P in log1p(r) = r + r^2 P(r)
LOG_OFF = 0x3fe6a09e667f3bcd   # bits of the double nearest sqrt(1/2)
LN_TARGET_LOG2 = -58  # asserted bound on the absolute error of the inline L = H + T


def ulp_of(v):
    """ulp of the double nearest to v (v > 0 normal)."""
    e = mpmath.floor(mpmath.log(abs(v), 2))
    return mpf(2) ** (int(e) - 52)


def d(v):
    """nearest double"""
    return float(v)


# ---------------------------------------------------------------- exact series coefficients
def series_coeffs(n_terms):
    a, b, c, dd = [], [], [], []
    an = Fraction(1)          # ((1/2)_n/n!)^2
    poch_half = Fraction(1)   # (1/2)_n
    poch_3half = Fraction(1)  # (3/2)_n
    poch_2 = Fraction(1)      # (2)_n
    fact = Fraction(1)        # n!
    dn = Fraction(0)          # d_n - d_0
    for n in range(n_terms):
        if n > 0:
            poch_half *= Fraction(2 * n - 1, 2)
            poch_3half *= Fraction(2 * n + 1, 2)
            poch_2 *= n + 1
            fact *= n
            dn += Fraction(1, n) - Fraction(2, 2 * n - 1)
        an = (poch_half / fact) ** 2
        cn = Fraction(1, 2) * poch_half * poch_3half / (poch_2 * fact)
        a.append(an)
        b.append(an * dn)
        c.append(cn)
        dd.append(cn * (dn - Fraction(1, (2 * n + 1) * (2 * n + 2))))
    return a, b, c, dd


A_Q, B_Q, C_Q, D_Q = series_coeffs(NSERIES)
A_M = [mpf(q.numerator) / q.denominator for q in A_Q]
B_M = [mpf(q.numerator) / q.denominator for q in B_Q]
C_M = [mpf(q.numerator) / q.denominator for q in C_Q]
D_M = [mpf(q.numerator) / q.denominator for q in D_Q]


def pser(coeffs, x):
    s = mpf(0)
    for q in reversed(coeffs):
        s = s * x + q
    return s


def fPa(x):
    return pser(A_M[1:], x)


def fPb(x):
    return pser(B_M[1:], x)


def fPc(x):
    return pser(C_M[1:], x)


def fPd(x):
    return pser(D_M[1:], x)


def _extra(x):
    """working precision that keeps m = 1 - x exact for x >= 2^-1074"""
    x = mpf(x)
    return mp.prec + max(0, -int(mpmath.floor(mpmath.log(x, 2)))) + 16


def Kx(x):
    with mpmath.workprec(_extra(x)):
        r = mpmath.ellipk(1 - mpf(x))
    return +r


def Ex(x):
    with mpmath.workprec(_extra(x)):
        r = mpmath.ellipe(1 - mpf(x))
    return +r


def check_series():
    """The series formulas against mpmath's own K and E (independent algorithm)."""
    worst = mpf(0)
    for i in range(1, 41):
        x = X0 * mpf(i) / 40 * mpf(0.999)
        if i % 4 == 0:
            x = mpf(2) ** (-7 * i)
        L = mpmath.log(16 / x)
        k = L / 2 * (1 + x * fPa(x)) + x * fPb(x)
        e = 1 + x * ((L - 1) / 4 + x * (L / 2 * fPc(x) + fPd(x)))
        rk = abs(k / Kx(x) - 1)
        re = abs(e / Ex(x) - 1)
        worst = max(worst, rk, re)
    assert worst < mpf(2) ** -200, "series does not reproduce mpmath ellipk/ellipe: %s" % worst
    return worst


# ---------------------------------------------------------------- Chebyshev interpolation
def cheb_fit(f, lo, hi, n):
    """monomial coefficients (in the variable itself, not scaled) of the degree-n polynomial
    interpolating f at the n+1 Chebyshev nodes of [lo, hi]"""
    mid = (lo + hi) / 2
    hw = (hi - lo) / 2
    nodes = [mid + hw * mpmath.cospi((j + mpf(0.5)) / (n + 1)) for j in range(n + 1)]
    V = mpmath.matrix(n + 1, n + 1)
    y = mpmath.matrix(n + 1, 1)
    for i, z in enumerate(nodes):
        for j in range(n + 1):
            V[i, j] = z ** j
        y[i] = f(z)
    sol = mpmath.lu_solve(V, y)
    return [sol[j] for j in range(n + 1)]


def peval(coeffs, x):
    s = mpf(0)
    for q in reversed(coeffs):
        s = s * x + q
    return s


# ---------------------------------------------------------------- log region
def log_tables():
    pa = [d(v) for v in cheb_fit(fPa, mpf(0), X0, NLOGK)]
    pb = [d(v) for v in cheb_fit(fPb, mpf(0), X0, NLOGK)]
    pc = [d(v) for v in cheb_fit(fPc, mpf(0), X0, NLOGE)]
    pd = [d(v) for v in cheb_fit(fPd, mpf(0), X0, NLOGE)]
    errk = mpf(0)
    erre = mpf(0)
    npts = 400
    for i in range(npts + 1):
        x = X0 * mpf(i) / npts
        if i == 0:
            x = mpf(2) ** -1074
        if i % 10 == 5:
            x = X0 * mpf(2) ** (-i // 8)
        L = mpmath.log(16 / x)
        kt, et = Kx(x), Ex(x)
        k = L / 2 * (1 + x * peval(pa, x)) + x * peval(pb, x)
        e = 1 + x * ((L - 1) / 4 + x * (L / 2 * peval(pc, x) + peval(pd, x)))
        errk = max(errk, abs(k - kt) / ulp_of(kt))
        erre = max(erre, abs(e - et) / ulp_of(et))
    assert errk < TARGET_ULP and erre < TARGET_ULP, (errk, erre)
    return pa, pb, pc, pd, float(errk), float(erre)


# ---------------------------------------------------------------- pieces
def pieces():
    out = []
    errk_all = mpf(0)
    erre_all = mpf(0)
    for j in range(-X0_LOG2, 0, -1):          # binades [2^-j, 2^(1-j)), j = 4, 3, 2, 1
        a = mpf(2) ** -j
        w = a / 2 ** S
        for s in range(2 ** S):
            lo = a + s * w
            hi = lo + w
            c = (lo + hi) / 2
            h = w / 2
            kc, ec = Kx(c), Ex(c)
            m = 1 - c
            # derivatives in x (= -d/dm): dK/dm = (E - x K)/(2 m x), dE/dm = (E - K)/(2 m)
            dk = -(ec - c * kc) / (2 * m * c)
            de = -(ec - kc) / (2 * m)

            def hk(t):
                return dk if t == 0 else (Kx(c + t) - kc) / t

            def he(t):
                return de if t == 0 else (Ex(c + t) - ec) / t

            pk = [d(v) for v in cheb_fit(hk, -h, h, NK)]
            pe = [d(v) for v in cheb_fit(he, -h, h, NE)]
            k0h = d(kc)
            k0l = d(kc - mpf(k0h))
            e0h = d(ec)
            e0l = d(ec - mpf(e0h))
            errk = mpf(0)
            erre = mpf(0)
            npts = 64
            for i in range(npts + 1):
                t = -h + 2 * h * mpf(i) / npts
                kt, et = Kx(c + t), Ex(c + t)
                k = mpf(k0h) + (mpf(k0l) + t * peval(pk, t))
                e = mpf(e0h) + (mpf(e0l) + t * peval(pe, t))
                errk = max(errk, abs(k - kt) / ulp_of(kt))
                erre = max(erre, abs(e - et) / ulp_of(et))
            errk_all = max(errk_all, errk)
            erre_all = max(erre_all, erre)
            out.append((d(c), k0h, k0l, pk, e0h, e0l, pe))
    assert errk_all < TARGET_ULP and erre_all < TARGET_ULP, (errk_all, erre_all)
    return out, float(errk_all), float(erre_all)



# ---------------------------------------------------------------- inline logarithm
# ellint.c needs L = ln(16/x) (m >= 0) and L = ln(16 m1) (m < 0) as H + T with H exact and
# |T| < 2^-7 small.  x = 2^k z, z in [sqrt(1/2), sqrt(2)) from the bits; the top LOG_B mantissa
# bits of (bits(x) - LOG_OFF) select an interval i of z with centre c_i (a double), and
#     ln z = ln c_i + log1p(r),  r = (z - c_i) * invc_i   (z - c_i is exact: Sterbenz)
# ln c_i = lhi_i + llo_i with lhi_i a multiple of 2^-32, so that n LN2_HI -+ lhi_i is exact
# (LN2_HI has 32 significant bits, the last at 2^-32).  log1p(r) = r + r^2 P(r), P the
# Chebyshev interpolant of (log1p(r) - r)/r^2 on the range of r.
def as_u64(v):
    return struct.unpack("<Q", struct.pack("<d", v))[0]


def as_f64(u):
    return struct.unpack("<d", struct.pack("<Q", u & 0xFFFFFFFFFFFFFFFF))[0]


LN2_HI = float(mpmath.floor(mpmath.log(2) * 2 ** 32)) / 2 ** 32
LN2_LO = d(mpmath.log(2) - mpf(LN2_HI))


def ln_indep_err(v, approx):
    """|approx - ln v| for doubles v > 0 and approx = (hi, lo), by Python's decimal module
    (Decimal.ln, 70 significant digits), which shares no code with mpmath (mpmath's atanh, the
    check used before, is computed through its own log).  Returns a float."""
    import decimal
    ctx = decimal.Context(prec=70)
    lnv = ctx.ln(decimal.Decimal(v))           # Decimal(float) is exact
    s = ctx.add(decimal.Decimal(approx[0]), decimal.Decimal(approx[1]))  # exact at 70 digits
    return abs(float(ctx.subtract(s, lnv)))


def lnc_table():
    n = 1 << LOG_B
    tab = []
    rmin = rmax = mpf(0)
    for i in range(n):
        zlo = as_f64(LOG_OFF + (i << (52 - LOG_B)))
        zhi = as_f64(LOG_OFF + ((i + 1) << (52 - LOG_B)) - 1)
        c = d((mpf(zlo) + mpf(zhi)) / 2)
        invc = d(1 / mpf(c))
        lnc = mpmath.log(mpf(c))
        lhi = float(mpmath.nint(lnc * 2 ** 32)) / 2 ** 32
        llo = d(lnc - mpf(lhi))
        # checks against an independent logarithm (decimal) and the exactness conditions
        assert zlo <= c <= zhi
        assert lhi * 2 ** 32 == int(lhi * 2 ** 32) and abs(mpf(lhi) - lnc) <= mpf(2) ** -33
        assert ln_indep_err(c, (lhi, llo)) < 2.0 ** -86, i
        assert abs(mpf(invc) * c - 1) <= mpf(2) ** -53
        rmin = min(rmin, (mpf(zlo) - c) / c)
        rmax = max(rmax, (mpf(zhi) - c) / c)
        tab.append((c, invc, lhi, llo))
    rlo, rhi = rmin * (1 + mpf(2) ** -20), rmax * (1 + mpf(2) ** -20)

    def g(r):
        return mpf(-0.5) if r == 0 else (mpmath.log1p(r) - r) / r ** 2
    p = [d(v) for v in cheb_fit(g, rlo, rhi, NLOG1P)]
    # the polynomial (double coefficients, exact arithmetic) against mpmath.log1p
    perr = mpf(0)
    for j in range(401):
        r = rlo + (rhi - rlo) * j / 400
        perr = max(perr, abs(r + r * r * peval(p, r) - mpmath.log1p(r)))
    assert perr < mpf(2) ** (LN_TARGET_LOG2 - 4), perr
    return tab, p, rlo, rhi


def log_parts_emul(tab, x):
    """ellint.c log_parts() in doubles: returns (k, i, r) with x = 2^k z"""
    u = as_u64(x)
    kadj = 0
    if u < 0x0010000000000000:
        u = as_u64(float(u))
        kadj = -1074
    tmp = (u - LOG_OFF) & 0xFFFFFFFFFFFFFFFF
    i = (tmp >> (52 - LOG_B)) & ((1 << LOG_B) - 1)
    k = tmp >> 52
    if k >= 2048:
        k -= 4096
    z = as_f64(u - (tmp & 0xFFF0000000000000))
    c, invc, lhi, llo = tab[i]
    r = (z - c) * invc
    return float(k + kadj), i, r


def log1p_tail_emul(p, r):
    """r^2 P(r) exactly as ellint.c evaluates it (Estrin, degree 4)"""
    r2 = r * r
    return r2 * ((p[0] + p[1] * r) + r2 * ((p[2] + p[3] * r) + r2 * p[4]))


def ln16_emul(tab, p, x, sign, rel=0.0):
    """sign = -1: ln(16/x) (ln16_over);  sign = +1: ln(16 x (1 + rel)) (ln16_times), as (H, T)
    in doubles, like ellint.c"""
    k, i, r = log_parts_emul(tab, x)
    c, invc, lhi, llo = tab[i]
    if sign < 0:
        n = 4.0 - k
        h = n * LN2_HI - lhi
        t = ((n * LN2_LO - llo) - r) - log1p_tail_emul(p, r)
    else:
        n = 4.0 + k
        h = n * LN2_HI + lhi
        t = ((n * LN2_LO + llo) + (r + rel)) + log1p_tail_emul(p, r)
    return h, t


def neg_m1_parts(m):
    """ellint.c for m < 0: m1h + m1l = 1 - m (two-sum, exact), and rel = mls q as ln16_times
    gets it (q = 1/ms, ms = m1h sc, mls = m1l sc, sc = 2^-600 above m1h = 2^512)"""
    m1h = 1.0 - m
    m1l = float(mpf(1) - mpf(m) - mpf(m1h))  # exact (two-sum)
    sc = 2.0 ** -600 if m1h > 2.0 ** 512 else 1.0
    q = 1.0 / (m1h * sc)
    return m1h, m1l, (m1l * sc) * q


def check_ln(tab, p):
    """max |H + T - L| of the emulated C code, L = ln(16/x) (log series, x < X0) over interval
    ends, random points, subnormals; and L = ln(16 m1), m1 = m1h + m1l > 1/X0 (m < 0: the m1
    entry with m1l = 0 at interval ends, and the m entry, whose two-sum low part m1l enters
    through rel = m1l/m1h).  Returns (log2 of the max, number of points, number with m1l != 0)."""
    import random
    rnd = random.Random(12345)
    ends = []
    for i in range(1 << LOG_B):
        for off in (0, 1, 2, (1 << (52 - LOG_B)) // 2, (1 << (52 - LOG_B)) - 2, (1 << (52 - LOG_B)) - 1):
            ends.append(as_f64(LOG_OFF + (i << (52 - LOG_B)) + off))
    xs = []
    for z in ends:
        for e in (-1070, -1030, -1022, -300, -60, -8):
            xs.append(z * 2.0 ** e if e >= -1022 else mpmath.ldexp(z, e))
    for _ in range(4000):
        xs.append(float(mpmath.ldexp(1 + rnd.random(), rnd.randint(-1074, X0_LOG2 - 1))))
    xs = [float(v) for v in xs if 0 < float(v) < 2.0 ** X0_LOG2]
    ms = []  # m < 0 with 1 - m > 1/X0
    for z in ends:
        for e in (-X0_LOG2, -X0_LOG2 + 1, 60, 511, 512, 513, 1000, 1023):
            y = z * 2.0 ** e
            if y > 2.0 ** -X0_LOG2 and y < float("inf"):
                ms.append(1.0 - y)   # m entry, mostly m1l = 0
    for _ in range(4000):
        e = rnd.randint(-X0_LOG2, 1023)
        m = -float(mpmath.ldexp(1 + rnd.random(), e))
        if rnd.random() < 0.5 and e < 1023:  # just below a binade: 1 - m crosses it, m1l != 0
            m = -float(mpmath.ldexp(2 - rnd.random() * 2.0 ** -40, e))
        if 1.0 - m > 2.0 ** -X0_LOG2 and m > -float("inf"):
            ms.append(m)
    worst = mpf(0)
    for x in xs:
        h, t = ln16_emul(tab, p, x, -1)
        assert h == float(mpf(h))
        worst = max(worst, abs(mpf(h) + mpf(t) - mpmath.log(16 / mpf(x))))
    nrel = 0
    for m in ms:
        m1h, m1l, rel = neg_m1_parts(m)
        nrel += m1l != 0
        for mm in ((m1h, 0.0, 0.0), (m1h, m1l, rel)):  # m1 entry (m1l = 0), m entry
            h, t = ln16_emul(tab, p, mm[0], +1, mm[2])
            assert h == float(mpf(h))
            worst = max(worst, abs(mpf(h) + mpf(t) - mpmath.log(16 * (mpf(mm[0]) + mpf(mm[1])))))
    assert nrel > 1000, nrel
    assert worst < mpf(2) ** LN_TARGET_LOG2, worst
    return float(mpmath.log(worst, 2)), len(xs) + 2 * len(ms), nrel


def hexs(v):
    return float(v).hex()


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "libicshadow", "src")
    serr = check_series()
    pa, pb, pc, pd, lek, lee = log_tables()
    pcs, pek, pee = pieces()
    lntab, l1p, rlo, rhi = lnc_table()
    lnerr, lnn, lnrel = check_ln(lntab, l1p)
    npieces = len(pcs)
    cmd = "/usr/bin/python3 scripts/gen_ellint_coeffs.py"
    stamp = ("generated by scripts/gen_ellint_coeffs.py - do not edit.\n"
             " * Command: %s   (mpmath %s, %d-bit arithmetic)" % (cmd, mpmath.__version__, mp.prec))

    h = []
    h.append("/* ellint_data.h - coefficient tables for ellint.c: %s */" % stamp)
    h.append("#ifndef ICS_ELLINT_DATA_H")
    h.append("#define ICS_ELLINT_DATA_H")
    h.append("")
    h.append("#define ICS_ELLINT_X0 0x1p%d /* log series below x = m1 = X0 */" % X0_LOG2)
    h.append("#define ICS_ELLINT_X0_LOG2 (%d)" % X0_LOG2)
    h.append("#define ICS_ELLINT_S %d /* 2^S pieces per binade of x in [X0, 1] */" % S)
    h.append("#define ICS_ELLINT_NPIECES %d" % npieces)
    h.append("#define ICS_ELLINT_NLOGK %d /* degree of Pa, Pb */" % NLOGK)
    h.append("#define ICS_ELLINT_NLOGE %d /* degree of Pc, Pd */" % NLOGE)
    h.append("#define ICS_ELLINT_NK %d /* degree of the K piece polynomials */" % NK)
    h.append("#define ICS_ELLINT_NE %d /* degree of the E piece polynomials */" % NE)
    h.append("")
    h.append("/* Log region 0 < x < X0, L = ln(16/x):")
    h.append(" *   K = (L/2)(1 + x Pa(x)) + x Pb(x),   E = 1 + x ((L - 1)/4 + x ((L/2) Pc(x) + Pd(x))),")
    h.append(" * stored as pa = Pa, pb2 = 2 Pb, pc2 = 2 Pc, pd4 = 4 Pd (exact scalings) for the form")
    h.append(" *   K = (1/2) [L + x (L Pa + 2 Pb)],   E = 1 + (x/4) [L - 1 + x (L 2Pc + 4Pd)].")
    h.append(" * Coefficients in increasing degree. */")
    h.append("struct ics_ellint_log_table {")
    h.append("  double pa[ICS_ELLINT_NLOGK + 1], pb2[ICS_ELLINT_NLOGK + 1];")
    h.append("  double pc2[ICS_ELLINT_NLOGE + 1], pd4[ICS_ELLINT_NLOGE + 1];")
    h.append("};")
    h.append("")
    h.append("/* Piece i covers x in [c - w/2, c + w/2]; t = x - c:")
    h.append(" *   K = k0h + (k0l + t Pk(t)),   E = e0h + (e0l + t Pe(t)). */")
    h.append("struct ics_ellint_piece {")
    h.append("  double c, k0h, k0l, e0h, e0l;")
    h.append("  double pk[ICS_ELLINT_NK + 1];")
    h.append("  double pe[ICS_ELLINT_NE + 1];")
    h.append("};")
    h.append("struct ics_ellint_piece_table {")
    h.append("  struct ics_ellint_piece p[ICS_ELLINT_NPIECES];")
    h.append("};")
    h.append("")
    h.append("/* Inline logarithm: x = 2^k z, z in [sqrt(1/2), sqrt(2)) (bits(x) - LOG_OFF), interval")
    h.append(" * i = top LOG_B mantissa bits of bits(x) - LOG_OFF;  ln z = (lhi + llo) + log1p(r),")
    h.append(" * r = (z - c) invc,  log1p(r) = r + r^2 P(r).  lhi is a multiple of 2^-32 like")
    h.append(" * n LN2_HI (|n| < 2^21), so n LN2_HI -+ lhi is exact. */")
    h.append("#define ICS_ELLINT_LOG_B %d" % LOG_B)
    h.append("#define ICS_ELLINT_LOG_N %d" % (1 << LOG_B))
    h.append("#define ICS_ELLINT_LOG_OFF 0x%xULL /* bits of sqrt(1/2) */" % LOG_OFF)
    h.append("#define ICS_ELLINT_NLOG1P %d /* degree of P */" % NLOG1P)
    h.append("#define ICS_ELLINT_LN2_HI %s /* ln 2 to 32 bits */" % hexs(LN2_HI))
    h.append("#define ICS_ELLINT_LN2_LO %s" % hexs(LN2_LO))
    h.append("struct ics_ellint_lnc {")
    h.append("  double c, invc, lhi, llo;")
    h.append("};")
    h.append("")
    h.append("extern const struct ics_ellint_log_table ics_ellint_log;")
    h.append("extern const struct ics_ellint_lnc ics_ellint_lnc[ICS_ELLINT_LOG_N];")
    h.append("extern const double ics_ellint_log1p[ICS_ELLINT_NLOG1P + 1];")
    h.append("extern const struct ics_ellint_piece_table ics_ellint_pieces;")
    h.append("")
    h.append("#endif")
    htext = "\n".join(h) + "\n"

    c = []
    c.append("/* ellint_data.c - coefficient tables for ellint.c: %s" % stamp)
    c.append(" * Maximum approximation error (double coefficients evaluated exactly, against mpmath")
    c.append(" * ellipk/ellipe at dense points), in ulps of the result; the rounding errors of the")
    c.append(" * double evaluation come on top and are measured by tests/test_ellint.c:")
    c.append(" *   ics_ellint_log    (x in (0, 2^%d], degree %d/%d):  K %.4f ulp, E %.4f ulp"
             % (X0_LOG2, NLOGK, NLOGE, lek, lee))
    c.append(" *   ics_ellint_pieces (x in [2^%d, 1], %d pieces, degree %d/%d):  K %.4f ulp, E %.4f ulp"
             % (X0_LOG2, npieces, NK, NE, pek, pee))
    c.append(" * Series check (DLMF 19.12.1/2 vs mpmath ellipk/ellipe, 40 points): rel. diff %.2e"
             % float(serr))
    c.append(" *   inline logarithm (%d intervals, log1p degree %d, r in [%.3g, %.3g]): the C evaluation"
             % (1 << LOG_B, NLOG1P + 2, float(rlo), float(rhi)))
    c.append(" *   of L = ln(16/x), ln(16 m1) emulated in doubles at %d points (%d with a two-sum low part"
             % (lnn, lnrel))
    c.append(" *   of m1 = 1 - m): max |H + T - L| = 2^%.2f (asserted < 2^%d); each ln c checked against"
             % (lnerr, LN_TARGET_LOG2))
    c.append(" *   Python decimal's ln (70 digits): |lhi + llo - ln c| < 2^-86")
    c.append(" */")
    c.append('#include "ellint_data.h"')
    c.append("")
    c.append("const struct ics_ellint_log_table ics_ellint_log = {")
    for name, arr in (("pa", pa), ("pb2", [2 * v for v in pb]), ("pc2", [2 * v for v in pc]),
                      ("pd4", [4 * v for v in pd])):
        c.append("  .%s = {" % name)
        for v in arr:
            c.append("    %s," % hexs(v))
        c.append("  },")
    c.append("};")
    c.append("")
    c.append("const struct ics_ellint_lnc ics_ellint_lnc[ICS_ELLINT_LOG_N] = {")
    for (cc, invc, lhi, llo) in lntab:
        c.append("  {%s, %s, %s, %s}," % (hexs(cc), hexs(invc), hexs(lhi), hexs(llo)))
    c.append("};")
    c.append("")
    c.append("const double ics_ellint_log1p[ICS_ELLINT_NLOG1P + 1] = {%s};" % ", ".join(hexs(v) for v in l1p))
    c.append("")
    c.append("const struct ics_ellint_piece_table ics_ellint_pieces = {.p = {")
    for (cc, k0h, k0l, pk, e0h, e0l, pe) in pcs:
        c.append("  {.c = %s, /* %.17g */" % (hexs(cc), cc))
        c.append("   .k0h = %s, .k0l = %s," % (hexs(k0h), hexs(k0l)))
        c.append("   .e0h = %s, .e0l = %s," % (hexs(e0h), hexs(e0l)))
        c.append("   .pk = {%s}," % ", ".join(hexs(v) for v in pk))
        c.append("   .pe = {%s}}," % ", ".join(hexs(v) for v in pe))
    c.append("}};")
    ctext = "\n".join(c) + "\n"

    with open(os.path.join(outdir, "ellint_data.h"), "w") as f:
        f.write(htext)
    with open(os.path.join(outdir, "ellint_data.c"), "w") as f:
        f.write(ctext)
    print("log table: K %.4f ulp, E %.4f ulp; pieces: K %.4f ulp, E %.4f ulp; inline log 2^%.2f"
          % (lek, lee, pek, pee, lnerr))


if __name__ == "__main__":
    main()
