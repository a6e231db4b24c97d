/* fuzz.c - the fuzz harness of hrm.h: bytes decoded into a medium
   (constants or callbacks, whose outputs come from the bytes too, NaN and
   infinities included), an interval, options (an opacity cut-off and the
   medium's feature among them), a warp and breakpoints; one
   hrm_solve (and, for some inputs, hrm_transmittance) checked against the
   manual's promises. A broken promise aborts, which libFuzzer reports as a
   crash with the input that caused it.

   Built two ways:
   - with FUZZ_LIBFUZZER (make fuzz): clang -fsanitize=fuzzer,address,
     undefined; libFuzzer calls LLVMFuzzerTestOneInput;
   - without it (make test): a program that replays every file named on its
     command line (the seed corpus tests/corpus/ and any crash committed
     there as a regression case) and ends with "N passed, N failed".

   The promises (hrm.h's manual): a known status; on an error status L = 0,
   Tr = 1 and nothing of the result's neighbours written; otherwise L and
   Tr finite, and in the optical-depth form (every method but an IVP
   solver in HRM_FORM_RTE) 0 <= Tr <= 1 and L >= 0 when every source is
   non-negative; every callback called at a finite t in [t0, t1]; an
   adaptive method's source evaluations within max_evals. */
#define HRM_IMPLEMENTATION
#include "hrm.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NCH HRM_CHANNELS

typedef struct fz_reader {
    const uint8_t *d;
    size_t n, i;
} fz_reader;

static unsigned fz_byte(fz_reader *r)
{
    return r->i < r->n ? r->d[r->i++] : 0u;
}

/* A number from the bytes: raw bits, a special value, or a mantissa from a
   short table times a power of ten (the extremes of the manual's grid). */
static double fz_num(fz_reader *r)
{
    static const double special[8] = {0.0, -0.0, (double)NAN, (double)INFINITY, -(double)INFINITY, DBL_MIN, 4.9e-324, DBL_MAX};
    static const double mant[8] = {1.0, 2.0, 0.5, 3.0, 1.5, 0.1, 7.0, 0.25};
    unsigned mode = fz_byte(r) % 8;
    if (mode == 0) {
        uint64_t bits = 0;
        double x;
        int k;
        for (k = 0; k < 8; ++k) bits = bits << 8 | fz_byte(r);
        memcpy(&x, &bits, sizeof x);
        return x;
    }
    if (mode == 1) return special[fz_byte(r) % 8];
    {
        unsigned m = fz_byte(r), e = fz_byte(r);
        double x = mant[m % 8] * pow(10.0, (double)((int)(e % 61) - 30) / (1 + (m >> 3) % 2));
        return (m & 0x80) ? -x : x;
    }
}

/* a mostly valid non-negative value: the bytes decide how often not */
static double fz_coef(fz_reader *r)
{
    double x = fz_num(r);
    return (fz_byte(r) % 8 == 0) ? x : fabs(x);
}

typedef struct fz_medium {
    double sa[NCH], ss[NCH], le[NCH], li[NCH];
    double lo, hi;          /* Li is zero over [lo, hi] (a shadow) */
    double delta, D2;       /* and peaked as 1 / (D2 + (t - delta)^2) if D2 > 0 */
    double t0, t1;
    long calls, outside;
    int bad_after;          /* callbacks return NaN from this call on (0: never) */
} fz_medium;

static void fz_touch(fz_medium *m, hrm_real t)
{
    double x = (double)t;
    m->calls++;
    if (!(x == x) || x < m->t0 || x > m->t1) m->outside++;
}

static hrm_real fz_out(const fz_medium *m, double v)
{
    if (m->bad_after > 0 && m->calls >= m->bad_after) return (hrm_real)(double)NAN;
    return (hrm_real)v;
}

static void fz_sa(void *u, hrm_real t, hrm_real out[NCH])
{
    fz_medium *m = (fz_medium *)u;
    int c;
    fz_touch(m, t);
    for (c = 0; c < NCH; ++c) out[c] = fz_out(m, m->sa[c]);
}

static void fz_ss(void *u, hrm_real t, hrm_real out[NCH])
{
    fz_medium *m = (fz_medium *)u;
    int c;
    fz_touch(m, t);
    for (c = 0; c < NCH; ++c) out[c] = fz_out(m, m->ss[c]);
}

static void fz_le(void *u, hrm_real t, hrm_real out[NCH])
{
    fz_medium *m = (fz_medium *)u;
    int c;
    fz_touch(m, t);
    for (c = 0; c < NCH; ++c) out[c] = fz_out(m, m->le[c]);
}

static void fz_li(void *u, hrm_real t, hrm_real out[NCH])
{
    fz_medium *m = (fz_medium *)u;
    double x = (double)t, f = 1;
    int c;
    fz_touch(m, t);
    if (x >= m->lo && x <= m->hi) f = 0;
    if (m->D2 > 0) f /= m->D2 + (x - m->delta) * (x - m->delta);
    for (c = 0; c < NCH; ++c) out[c] = fz_out(m, m->li[c] * f);
}

/* a user warp: t = t0 + s (u + u^3), s > 0, u in [0, U] */
typedef struct fz_user {
    double t0, s;
} fz_user;

static hrm_real fz_t_of_u(void *u, hrm_real v)
{
    const fz_user *w = (const fz_user *)u;
    double x = (double)v;
    return (hrm_real)(w->t0 + w->s * (x + x * x * x));
}

static hrm_real fz_dt_du(void *u, hrm_real v)
{
    const fz_user *w = (const fz_user *)u;
    double x = (double)v;
    return (hrm_real)(w->s * (1 + 3 * x * x));
}

static hrm_real fz_u_of_t(void *u, hrm_real t)
{
    /* the real root of x^3 + x - y = 0 (Cardano) */
    const fz_user *w = (const fz_user *)u;
    double y = ((double)t - w->t0) / w->s, q = sqrt(y * y / 4 + 1.0 / 27);
    return (hrm_real)(cbrt(y / 2 + q) + cbrt(y / 2 - q));
}

typedef struct fz_guarded {
    unsigned char before[64];
    hrm_result r;
    unsigned char after[64];
} fz_guarded;

/* One input: 0 if every promise held, else the first broken one (printed). */
static int fz_run(const uint8_t *data, size_t size)
{
    fz_reader rd = {data, size, 0};
    fz_medium fm;
    fz_user fu;
    hrm_medium m;
    hrm_options o;
    fz_guarded g;
    hrm_real breaks[4];
    hrm_status s;
    int c, k, rte, nonneg = 1, adaptive;
    unsigned method = fz_byte(&rd) % (unsigned)HRM_METHOD_COUNT, flags = fz_byte(&rd);
    double t0 = fz_num(&rd), T = fz_num(&rd);

    memset(&fm, 0, sizeof fm);
    memset(&m, 0, sizeof m);
    for (c = 0; c < NCH; ++c) {
        fm.sa[c] = fz_coef(&rd);
        fm.ss[c] = fz_coef(&rd);
        fm.le[c] = (flags & 1) ? fz_coef(&rd) : 0;
        fm.li[c] = fz_coef(&rd);
        nonneg &= fm.le[c] >= 0 && fm.li[c] >= 0;
    }
    fm.t0 = t0;
    fm.t1 = t0 + T;
    fm.lo = t0 + T * (fz_byte(&rd) / 255.0);
    fm.hi = fm.lo + T * (fz_byte(&rd) / 1024.0);
    if (!(flags & 2)) fm.lo = fm.hi = (double)INFINITY;
    fm.delta = t0 + T * (fz_byte(&rd) / 255.0);
    fm.D2 = (flags & 4) ? fabs(fz_num(&rd)) : 0;
    fm.bad_after = (flags & 8) ? (int)fz_byte(&rd) + 1 : 0;
    m.user = &fm;
    if (flags & 16) {
        m.flags = HRM_MEDIUM_HOMOGENEOUS;
        for (c = 0; c < NCH; ++c) {
            m.const_sigma_a[c] = (hrm_real)fm.sa[c];
            m.const_sigma_s[c] = (hrm_real)fm.ss[c];
        }
    } else {
        m.sigma_a = fz_sa;
        m.sigma_s = fz_ss;
    }
    if (flags & 1) m.Le = fz_le;
    m.Li = fz_li;

    o = hrm_default_options((hrm_method)method);
    if (fz_byte(&rd) % 2) o.method = (hrm_method)(fz_byte(&rd) % 32); /* unknown methods too */
    o.form = (hrm_form)(fz_byte(&rd) % 4);
    o.steps = fz_byte(&rd) % 4 == 0 ? (int)(signed char)fz_byte(&rd) * 1000 : (int)(fz_byte(&rd) % 64);
    o.rtol = (hrm_real)((flags & 32) ? fz_num(&rd) : pow(10.0, -1.0 - fz_byte(&rd) % 14));
    if (fz_byte(&rd) % 4 == 0) o.atol = (hrm_real)fz_num(&rd);
    if (fz_byte(&rd) % 4 == 0) o.h_min = (hrm_real)fz_num(&rd);
    if (fz_byte(&rd) % 4 == 0) o.h_max = (hrm_real)fz_num(&rd);
    o.max_evals = (long)(fz_byte(&rd) % 8 == 0 ? -1 : 20000);
    o.jitter = (int)(fz_byte(&rd) % 2);
    o.seed = fz_byte(&rd);
    o.tau_mode = (hrm_tau_mode)(fz_byte(&rd) % 4);
    o.find_jumps = (int)(fz_byte(&rd) % 4) - 1;
    o.exponential = (int)(fz_byte(&rd) % 4);
    o.gk_mode = (hrm_gk_mode)(fz_byte(&rd) % 3);
    o.gk_rule = (hrm_gk_rule)(fz_byte(&rd) % 3);
    switch (fz_byte(&rd) % 5) {
    case 1:
        o.warp.kind = HRM_WARP_DISTANCE;
        o.warp.sigma_ref = (hrm_real)fz_num(&rd);
        break;
    case 2:
        o.warp.kind = HRM_WARP_EQUIANGULAR;
        o.warp.delta = (hrm_real)fm.delta;
        o.warp.D = (hrm_real)fz_num(&rd);
        break;
    case 3:
        fu.t0 = t0;
        fu.s = fabs(T) > 0 ? fabs(T) / 2 : 1;
        o.warp.kind = HRM_WARP_USER;
        o.warp.user = &fu;
        o.warp.t_of_u = fz_t_of_u;
        o.warp.dt_du = fz_dt_du;
        o.warp.u_of_t = fz_u_of_t;
        break;
    default: break;
    }
    k = (int)(fz_byte(&rd) % 6);
    if (k > 0 && k <= 4) {
        int j;
        for (j = 0; j < k; ++j) breaks[j] = (hrm_real)(t0 + T * (fz_byte(&rd) / 255.0));
        o.breaks = breaks;
        o.nbreaks = k;
    }
    /* an opacity cut-off and the medium's feature (a byte that reads 0,
       past the input's end, leaves both unset) */
    k = (int)fz_byte(&rd);
    if (k % 4 == 1) o.cutoff = (hrm_real)(k & 4 ? fz_num(&rd) : pow(10.0, -(double)(fz_byte(&rd) % 8)));
    k = (int)fz_byte(&rd);
    if (k % 4 == 1) m.feature = (hrm_real)(k & 4 ? fz_num(&rd) : T / (1 + fz_byte(&rd) % 64));

    memset(&g, 0xA5, sizeof g);
    fm.calls = fm.outside = 0;
    s = hrm_solve(&m, (hrm_real)t0, (hrm_real)(t0 + T), &o, &g.r);

    /* the promises (on a broken one, the case is printed first) */
    if (getenv("FUZZ_VERBOSE"))
        printf("method %d form %d warp %d (sigma_ref %g D %g) t0 %g T %g flags %#x steps %d rtol %g atol %g "
               "h_min %g h_max %g tau_mode %d find_jumps %d exponential %d nbreaks %d: sa %g ss %g le %g li %g "
               "D2 %g bad_after %d cutoff %g feature %g -> status %d L %g Tr %g\n",
               (int)o.method, (int)o.form, (int)o.warp.kind, (double)o.warp.sigma_ref, (double)o.warp.D, t0, T,
               flags, o.steps, (double)o.rtol, (double)o.atol, (double)o.h_min, (double)o.h_max, (int)o.tau_mode,
               o.find_jumps, o.exponential, o.nbreaks, fm.sa[0], fm.ss[0], fm.le[0], fm.li[0], fm.D2, fm.bad_after,
               (double)o.cutoff, (double)m.feature, (int)s, (double)g.r.L[0], (double)g.r.Tr[0]);
    if (strcmp(hrm_status_string(s), "unknown status") == 0) return printf("unknown status %d\n", (int)s), 1;
    for (k = 0; k < 64; ++k)
        if (g.before[k] != 0xA5 || g.after[k] != 0xA5) return printf("wrote outside the result\n"), 2;
    if (s < 0) {
        for (c = 0; c < NCH; ++c)
            if (g.r.L[c] != 0 || g.r.Tr[c] != 1) return printf("error %d: L %g, Tr %g\n", (int)s, (double)g.r.L[c], (double)g.r.Tr[c]), 3;
        return 0;
    }
    for (c = 0; c < NCH; ++c) {
        double L = (double)g.r.L[c], Tr = (double)g.r.Tr[c];
        if (!isfinite(L) || !isfinite(Tr))
            return printf("status %d, channel %d (sa %g ss %g le %g li %g): L %g, Tr %g not finite\n", (int)s, c,
                          fm.sa[c], fm.ss[c], fm.le[c], fm.li[c], L, Tr), 4;
    }
    rte = o.form == HRM_FORM_RTE;
    for (c = 0; c < NCH; ++c) {
        double L = (double)g.r.L[c], Tr = (double)g.r.Tr[c];
        if (!rte && (Tr < 0 || Tr > 1)) return printf("Tr %g outside [0, 1]\n", Tr), 5;
        if (!rte && nonneg && L < 0) return printf("L %g < 0\n", L), 6;
    }
    if (fm.outside) return printf("%ld callbacks outside [t0, t1] or at a non-finite t\n", fm.outside), 7;
    adaptive = o.method == HRM_METHOD_DEFAULT || o.method == HRM_NESTED_SIMPSON || o.method == HRM_GAUSS_KRONROD ||
               o.method == HRM_BOGACKI_SHAMPINE || o.method == HRM_DORMAND_PRINCE ||
               o.method == HRM_FEHLBERG || o.method == HRM_CASH_KARP || o.method == HRM_VERNER;
    if (adaptive && o.max_evals > 0 && g.r.stats.evals > o.max_evals)
        return printf("%ld evaluations, budget %ld\n", (long)g.r.stats.evals, o.max_evals), 8;
    return 0;
}

#ifdef FUZZ_LIBFUZZER
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (fz_run(data, size)) abort();
    return 0;
}
#else
/* Replays the files on the command line: N passed, N failed. */
int main(int argc, char **argv)
{
    int i, pass = 0, fail = 0;
    size_t cap = (size_t)1 << 16;
    uint8_t *buf = (uint8_t *)malloc(cap);
    if (!buf) return 2;
    for (i = 1; i < argc; ++i) {
        FILE *f = fopen(argv[i], "rb");
        size_t n;
        if (!f) {
            printf("FAIL cannot read %s\n", argv[i]);
            fail++;
            continue;
        }
        n = fread(buf, 1, cap, f);
        fclose(f);
        if (fz_run(buf, n)) {
            printf("FAIL %s\n", argv[i]);
            fail++;
        } else {
            pass++;
        }
    }
    free(buf);
    printf("%d passed, %d failed\n", pass, fail);
    return fail != 0;
}
#endif
