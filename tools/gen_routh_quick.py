#!/usr/bin/python3
"""gen_routh_quick.py: writes src/numerics/routh_quick.inc, the straight-line quick
stage of the Routh-Hurwitz sign test (issue 7), one function per degree.

    /usr/bin/python3 tools/gen_routh_quick.py > src/numerics/routh_quick.inc

The output is committed; rerun this script after editing it.  Included by
src/numerics/sign_tests.c (autobal_poly_hurwitz, autobal_poly_hurwitz_err) and
src/analysis/pendulum_verdict.c (autobal_pendulum_verdict).  For degree n (3..12):

    static AUTOBAL_RQ_INLINE int autobal_routh_quick_<n>(
        const double *c, const double *ce, const double *mu0, double rtol,
        double eps0, int rel, int *changes)

c[0..n]: the coefficients (any values).  The bounds of the full test are
ce[j] (rel == 0) or rtol |c[j]| (rel != 0; ce is not read).  The
magnitudes of the coefficients (mu0, below) are taken from mu0[0..n] when
mu0 != NULL (the caller guarantees mu0[j] >= |c[j]|, mu0[j] >= (ce[j] +
u |c[j]|) / eps0, ce[j] >= 0, and a non-finite mu0[j] whenever c[j] or
ce[j] is not finite), else |c[j]| (rel: eps0 >= u + rtol), else
max(|c[j]|, (ce[j] + u |c[j]|) / eps0) (any eps0 > 0).

Returns 1 when it certifies the verdict of the full test (routh_err_core in
src/numerics/sign_tests.c: the Routh array with one running error bound per entry): every
first-column entry of the full test is decided, and *changes is its number
of sign changes.  Else 0 (*changes unspecified): the caller runs the full
test, which also reports bad input.  See the comment "Quick stage" in
src/numerics/sign_tests.c for the bound and why it is sound.

Straight-line code: one scalar variable per entry, no arrays, no early exit
(all conditions are combined at the end).  Per entry the value r (the full
test's operations; the array of c[n] < 0 is the exact negative of the
normalised one) and a magnitude mu (mu' = mu_x + |q| mu_y >= |r'|); per row
t one relative bound eps_t (e_{t,j} <= eps_t mu_{t,j}):
    eps_0 = eps_1 = eps0,  P_t = eps_t mu_{t,0} / |r_{t,0}|,
    eps_{t+1} = eps_t + P_t + P_{t-1} + 3u;
pass: sum_{t<n} P_t < 1/2 (row n - 1 as eps_{n-1} mu_{n-1,0} < (1/2 - S)
|r_{n-1,0}|, without the division q_{n-1}, which only copies c[0] into row
n), |r_{n,0}| > the full test's own bound of the copied c[0] (the same
operations), every mu in [2^-300, 2^300] (mu0 is raised to 2^-300, a valid
magnitude; the upper end is checked on the first column, which bounds every
mu), and the bounds of the input >= 0.  1/|r_{t,0}| is formed as |q_t| /
|r_{t-1,0}|: one division per row (q).
"""
import sys

DEGREES = range(3, 13)  # degrees 1 and 2: the full test is as cheap
# Program order: the values (the chain of divisions, the critical path) run
# LEAD rows ahead of the bounds; 2 measured best on the benchmark (bench/perf
# roots: autobal_poly_hurwitz, autobal_pendulum_verdict), GCC 12, AMD EPYC.
LEAD = 2

PRELUDE = """
/* the sign bit of x, as 0 or 1 */
static AUTOBAL_RQ_INLINE uint64_t rq_sign(double x) {
  uint64_t b;
  memcpy(&b, &x, sizeof b);
  return b >> 63;
}
"""


def tree(op, items):
    items = list(items)
    while len(items) > 1:
        nxt = [op(items[i], items[i + 1]) for i in range(0, len(items) - 1, 2)]
        if len(items) % 2:
            nxt.append(items[-1])
        items = nxt
    return items[0]


def gen(n):
    """The function for degree n: first the values (the chain of divisions,
    the critical path, early in program order), then magnitudes and bounds."""
    L, V, Bd = [], [[]], [[]]
    w = L.append

    def v(x):
        V[-1].append(x)

    def bd(x):
        Bd[-1].append(x)

    def seg():  # a new segment (rows), for the interleaved order
        V.append([])
        Bd.append([])

    def ln(t):  # entries of row t
        return (n - t) // 2 + 1

    w("static AUTOBAL_RQ_INLINE int autobal_routh_quick_%d(const double *c, const double *ce," % n)
    w("                                                  const double *mu0, double rtol,")
    w("                                                  double eps0, int rel, int *changes) {")
    w("  const double u = DBL_EPSILON, u3 = 3.0 * DBL_EPSILON, is = 1.0 / eps0;")
    w("  const double lo = 0x1p-300, hi = 0x1p300;")
    w("  double S, M;")
    w("  int ok;")
    w("  uint64_t cs, ng;")
    v("  /* the values: the full test's operations */")
    bd("  /* magnitudes and bounds */")
    # rows 0 and 1: values r and magnitudes m (NaN propagates through the
    # selections: the comparisons are false for NaN and pick the NaN operand)
    for t in (0, 1):
        for j in range(ln(t)):
            k = n - 2 * j - t
            v("  const double r%d_%d = c[%d];" % (t, j, k))
            bd("  const double a%d_%d = fabs(c[%d]);" % (t, j, k))
            bd("  const double b%d_%d = mu0 || rel ? 0.0 : (ce[%d] + u * a%d_%d) * is;" % (t, j, k, t, j))
            bd("  const double n%d_%d = mu0 ? mu0[%d] : rel || a%d_%d > b%d_%d ? a%d_%d : b%d_%d;"
               % ((t, j, k) + (t, j) * 4))
            bd("  const double m%d_%d = lo > n%d_%d ? lo : n%d_%d;" % ((t, j) * 3))
    # the copied c[0]: its bound in the full test, bitwise (rows n % 2 + 2, ..., n)
    bd("  double ez = (rel ? rtol * fabs(c[0]) : ce[0]) + u * fabs(c[0]);")
    for _ in range(n % 2 + 2, n + 1, 2):
        bd("  ez = ez + u * fabs(c[0]);")
    c0name = "m%d_%d" % (n % 2, (n - n % 2) // 2)
    bd("  cs = mu0 || rel ? 0 : %s;"
       % tree(lambda a, b: "(%s | %s)" % (a, b), ["rq_sign(ce[%d])" % k for k in range(n + 1)]))
    bd("  const double ia0 = 1.0 / fabs(r0_0);")
    bd("  const double P0 = eps0 * (m0_0 * ia0);")
    bd("  const double e1 = eps0;")
    bd("  S = P0;")
    bd("  M = m0_0 + %s;" % c0name)
    bd("  ng = 0;")
    for t in range(1, n - 1):
        seg()
        v("  /* row %d from rows %d and %d */" % (t + 1, t - 1, t))
        v("  const double q%d = r%d_0 / r%d_0;" % (t, t - 1, t))
        bd("  /* row %d */" % t)
        bd("  const double fq%d = fabs(q%d);" % (t, t))
        # 1/|a_t| = |q_t| / |a_{t-1}|: a product instead of a division
        bd("  const double ia%d = fq%d * ia%d;" % (t, t, t - 1))
        bd("  const double P%d = (e%d * m%d_0) * ia%d;" % (t, t, t, t))
        bd("  M = M + m%d_0;" % t)
        bd("  ng = ng + rq_sign(q%d);" % t)
        if t < n - 2:
            bd("  S = S + P%d;" % t)
            bd("  const double e%d = (e%d + u3) + (P%d + P%d);" % (t + 1, t, t, t - 1))
        else:
            # e_{n-1} = E + P_{n-2}, E = e_{n-2} + u3 + P_{n-3}: see the final check
            bd("  const double E%d = (e%d + u3) + P%d;" % (t + 1, t, t - 1))
        len1, len2 = ln(t), ln(t + 1)
        for j in range(len2):
            x, mx = "r%d_%d" % (t - 1, j + 1), "m%d_%d" % (t - 1, j + 1)
            if j + 1 < len1:
                v("  const double r%d_%d = %s - q%d * r%d_%d;" % (t + 1, j, x, t, t, j + 1))
                bd("  const double m%d_%d = %s + fq%d * m%d_%d;" % (t + 1, j, mx, t, t, j + 1))
            else:
                # structural zero y: the full test computes x - q*0.0, which
                # equals x (up to the sign of a zero) whenever q is finite
                v("  const double r%d_%d = %s;" % (t + 1, j, x))
                bd("  const double m%d_%d = %s;" % (t + 1, j, mx))
    # row n - 1 (a single entry): its check P_{n-1} < 1/2 - S without the
    # division q_{n-1} (which only copies c[0] into row n: the range guard
    # keeps it and its bound finite), so that the chain of divisions is one
    # shorter: e_{n-1} mu_{n-1,0} < (1/2 - S_{n-2}) |r_{n-1,0}|, written with
    # e_{n-1} = E + P_{n-2} and S_{n-2} = S + P_{n-2} (S up to P_{n-3}) as
    #   E mu + P_{n-2} (mu + |r_{n-1,0}|) < (1/2 - S) |r_{n-1,0}|
    # (fewer operations after the last division)
    seg()
    v("  /* row %d: c[0] copied from row %d */" % (n, n - 2))
    v("  const double r%d_0 = r%d_1;" % (n, n - 2))
    bd("  M = M + m%d_0;" % (n - 1))
    bd("  ng = ng + (rq_sign(r%d_0) ^ rq_sign(r%d_0)) + (rq_sign(r%d_0) ^ rq_sign(r%d_0));"
       % (n - 2, n - 1, n - 1, n))
    bd("  const double al = fabs(r%d_0);" % (n - 1))
    bd("  ok = (E%d * m%d_0 + P%d * (m%d_0 + al) < (0.5 - S) * al) & (fabs(r%d_0) > ez) &"
       % (n - 1, n - 1, n - 2, n - 1, n))
    bd("       (M <= hi) & (cs == 0);")
    # program order: the values run LEAD segments (rows) ahead of the bounds
    for i in range(len(V) + LEAD):
        if i < len(V):
            L.extend(V[i])
        if 0 <= i - LEAD < len(Bd):
            L.extend(Bd[i - LEAD])
    w("  *changes = (int)ng;")
    w("  return ok;")
    w("}")
    return "\n".join(L)


def main():
    out = sys.stdout
    out.write("/* routh_quick.inc: GENERATED by tools/gen_routh_quick.py, do not edit.\n"
              " * The quick stage of the Routh-Hurwitz sign test for degrees %d..%d,\n"
              " * straight-line code; see tools/gen_routh_quick.py and the comment\n"
              " * \"Quick stage\" in src/numerics/sign_tests.c.  The includer provides <float.h>,\n"
              " * <math.h>, <stdint.h>, <string.h> and AUTOBAL_RQ_INLINE. */\n"
              % (min(DEGREES), max(DEGREES)))
    out.write(PRELUDE)
    for n in DEGREES:
        out.write("\n" + gen(n) + "\n")


if __name__ == "__main__":
    main()
