/* common.c - the helpers shared by the test files (see common.h). */
#include "common.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------
   Precision and small numerics
   ------------------------------------------------------------------------ */
int real_is_float(void) { return sizeof(hrm_real) == sizeof(float); }

double real_eps(void) { return real_is_float() ? (double)FLT_EPSILON : DBL_EPSILON; }

void spectrum_one(void *user, hrm_real t, hrm_real out[NCH])
{
    int c;
    (void)user;
    (void)t;
    for (c = 0; c < NCH; ++c) out[c] = 1;
}

double fp_floor(long n, double tau) { return real_eps() * (double)(n + 16) * (1.0 + tau); }

int verbose(void)
{
    const char *v = getenv("HRM_TEST_VERBOSE");
    return v && v[0] && v[0] != '0';
}

int finite_d(double x) { return x == x && x - x == 0.0; }

double ls_slope(const double *x, const double *y, int n)
{
    double mx = 0, my = 0, sxx = 0, sxy = 0;
    int i;
    for (i = 0; i < n; ++i) { mx += x[i]; my += y[i]; }
    mx /= n; my /= n;
    for (i = 0; i < n; ++i) {
        sxx += (x[i] - mx) * (x[i] - mx);
        sxy += (x[i] - mx) * (y[i] - my);
    }
    return sxx > 0 ? sxy / sxx : 0.0;
}

/* ------------------------------------------------------------------------
   Gauss-Legendre
   ------------------------------------------------------------------------ */
void gl_rule(int n, double x[], double w[])
{
    int i, it, j;
    for (i = 0; i < n; ++i) {
        double z = cos(PI * (i + 0.75) / (n + 0.5)), dp = 1;
        for (it = 0; it < 100; ++it) {
            double p0 = 1, p1 = z, z1;
            for (j = 2; j <= n; ++j) {
                double p2 = ((2.0 * j - 1) * z * p1 - (j - 1.0) * p0) / j;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1);
            z1 = z;
            z = z1 - p1 / dp;
            if (fabs(z - z1) < 1e-16) break;
        }
        x[i] = z;
        w[i] = 2 / ((1 - z * z) * dp * dp);
    }
}

double gl_integrate(real_fn f, const void *ctx, double a, double b, int panels, int n,
                    int square, double centre)
{
    double x[GL_MAX], wt[GL_MAX], h = (b - a) / panels, sum = 0;
    int i, j;
    gl_rule(n, x, wt);
    for (i = 0; i < panels; ++i) {
        double mid = a + (i + 0.5) * h;
        for (j = 0; j < n; ++j) {
            double v = f(ctx, mid + 0.5 * h * x[j]);
            sum += wt[j] * (square ? (v - centre) * (v - centre) : v);
        }
    }
    return sum * 0.5 * h;
}

/* ------------------------------------------------------------------------
   The scene
   ------------------------------------------------------------------------ */
double channel_frac(int c) { return (double)c / NCH; }

void scene_set_sine(scene *sc, double a0, double a1)
{
    int c;
    sc->profile = PROFILE_SINE;
    for (c = 0; c < NCH; ++c) {
        sc->a[c] = a0 + a1 * channel_frac(c);
        sc->b[c] = 0.5 * sc->a[c];
    }
}

void scene_reset_counts(scene *sc)
{
    sc->n_sa = sc->n_ss = sc->n_st = sc->n_le = sc->n_li = sc->n_tr = sc->n_one = 0;
    sc->n_never = 0;
    sc->tmin = 1e300;
    sc->tmax = -1e300;
    sc->tr_amin = 1e300;
    sc->tr_bmax = -1e300;
    sc->tr_reversed = 0;
    sc->li_where_ss0 = sc->le_where_sa0 = 0;
    sc->log_n = sc->log_li_n = 0;
    sc->shadow_bad_status = 0;
}

void scene_init(scene *sc)
{
    int c;
    memset(sc, 0, sizeof *sc);
    for (c = 0; c < NCH; ++c) {
        double f = channel_frac(c);
        sc->sig_a[c] = 0.2 + 0.3 * f;
        sc->sig_s[c] = 0.3 + 0.45 * f;
        sc->pa[c] = 0.3 + 0.6 * f;
        sc->qc[c] = 0.1 + 0.1 * f;
        sc->le[c] = 1.0 + 1.5 * f;
        sc->E[c] = 2.0 - 0.9 * f;
        sc->I[c] = 1.0 + f;
    }
    scene_set_sine(sc, 0.6, 0.9);
    sc->w = 2.0;
    sc->q0 = 0.0;
    sc->d0 = 0.5;
    sc->k = 0.5;
    sc->cexp = 0.5;
    sc->lo = 2.3137;
    sc->hi = 3.7071;
    sc->delta = 3.0;
    sc->D = 1.0;
    scene_reset_counts(sc);
}

void touch(scene *sc, hrm_real t)
{
    double td = (double)t;
    if (td < sc->tmin || td != td) sc->tmin = td;
    if (td > sc->tmax || td != td) sc->tmax = td;
}

double sig_t_hom(const scene *sc, int c) { return sc->sig_a[c] + sc->sig_s[c]; }

double sig_t_het(const scene *sc, int c, double s)
{
    if (sc->profile == PROFILE_QUAD) return sc->qc[c] * (s - sc->q0) * (s - sc->q0);
    return sc->a[c] + sc->b[c] * sin(sc->w * s);
}

double tau_abs(const scene *sc, int c, double s)
{
    if (sc->profile == PROFILE_QUAD) {
        double d = s - sc->q0;
        return sc->qc[c] / 3 * (d * d * d + sc->q0 * sc->q0 * sc->q0);
    }
    return sc->a[c] * s + sc->b[c] * (1.0 - cos(sc->w * s)) / sc->w;
}

/* Without cancellation: for the sine, cos x - cos y = 2 sin((x + y)/2)
   sin((y - x)/2), so that tau stays positive (>= (a - b)(tb - ta)) however
   short the interval; a transmittance above 1 would be a bad value. */
double tau_het(const scene *sc, int c, double ta, double tb)
{
    if (sc->profile == PROFILE_QUAD) {
        double da = ta - sc->q0, db = tb - sc->q0;
        return sc->qc[c] / 3 * (db * db * db - da * da * da);
    }
    return sc->a[c] * (tb - ta) +
           2 * sc->b[c] / sc->w * sin(0.5 * sc->w * (ta + tb)) * sin(0.5 * sc->w * (tb - ta));
}

double light_value(const scene *sc, int light, int c, double s)
{
    switch (light) {
    case LIGHT_DIR: return sc->E[c] * exp(-sig_t_hom(sc, c) * (sc->d0 + sc->k * s));
    case LIGHT_TAU: return sc->E[c] * exp(sc->cexp * tau_abs(sc, c, s));
    case LIGHT_CONST: return sc->E[c];
    case LIGHT_SHADOW: return s >= sc->lo && s < sc->hi ? 0.0 : sc->E[c];
    case LIGHT_POINT: {
        double x = s - sc->delta;
        return sc->I[c] / (sc->D * sc->D + x * x);
    }
    default: return 0.0;
    }
}

static void poison_out(const scene *sc, int which, hrm_real out[NCH])
{
    if (sc->poison == which) out[NCH - 1] = (hrm_real)sc->poison_value;
}

/* The heterogeneous coefficients: frac(c) sigma_t_het, counted in *count,
   poisoned where the scene says so. */
static void het_out(scene *sc, hrm_real t, hrm_real out[NCH], long *count, int which, int part)
{
    int c;
    (*count)++;
    touch(sc, t);
    for (c = 0; c < NCH; ++c) {
        double f = part == 0 ? sc->pa[c] : part == 1 ? 1.0 - sc->pa[c] : 1.0;
        out[c] = (hrm_real)(f * sig_t_het(sc, c, (double)t));
    }
    poison_out(sc, which, out);
}

void het_sigma_a(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    het_out(sc, t, out, &sc->n_sa, POISON_SA, 0);
}

void het_sigma_s(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    het_out(sc, t, out, &sc->n_ss, POISON_SS, 1);
}

void het_sigma_t(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    het_out(sc, t, out, &sc->n_st, POISON_ST, 2);
}

void het_absorber(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    het_out(sc, t, out, &sc->n_sa, POISON_SA, 2);
}

void het_sigma(void *user, hrm_real t, hrm_real sa[NCH], hrm_real ss[NCH])
{
    scene *sc = (scene *)user;
    long unused = 0;
    sc->n_one++;
    het_out(sc, t, sa, &unused, POISON_SA, 0);
    het_out(sc, t, ss, &unused, POISON_SS, 1);
}

void het_transmittance(void *user, hrm_real ta, hrm_real tb, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_tr++;
    if ((double)ta < sc->tr_amin || ta != ta) sc->tr_amin = (double)ta;
    if ((double)tb > sc->tr_bmax || tb != tb) sc->tr_bmax = (double)tb;
    if (ta > tb) sc->tr_reversed++;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)exp(-tau_het(sc, c, (double)ta, (double)tb));
    poison_out(sc, POISON_TR, out);
}

void const_Le(void *user, hrm_real t, hrm_real out[NCH])
{
    scene *sc = (scene *)user;
    int c;
    sc->n_le++;
    touch(sc, t);
    if (sc->log_n < LOG_CAP) sc->log_le[sc->log_n++] = (double)t;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)sc->le[c];
    poison_out(sc, POISON_LE, out);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

long log_repeats(const double *log, int n)
{
    static const int cap = LOG_CAP;
    double sorted[LOG_CAP];
    long k, rep = 0;
    if (n > cap) n = cap;
    memcpy(sorted, log, sizeof(double) * (size_t)n);
    qsort(sorted, (size_t)n, sizeof(double), cmp_double);
    for (k = 1; k < n; ++k) rep += sorted[k] == sorted[k - 1];
    return rep;
}

static void light_eval(void *user, hrm_real t, hrm_real out[NCH], int light)
{
    scene *sc = (scene *)user;
    int c;
    sc->n_li++;
    touch(sc, t);
    if (sc->log_li_n < LOG_CAP) sc->log_li[sc->log_li_n++] = (double)t;
    for (c = 0; c < NCH; ++c) out[c] = (hrm_real)light_value(sc, light, c, (double)t);
    poison_out(sc, POISON_LI, out);
}

static void li_dir(void *user, hrm_real t, hrm_real out[NCH]) { light_eval(user, t, out, LIGHT_DIR); }
static void li_tau(void *user, hrm_real t, hrm_real out[NCH]) { light_eval(user, t, out, LIGHT_TAU); }
static void li_const(void *user, hrm_real t, hrm_real out[NCH]) { light_eval(user, t, out, LIGHT_CONST); }
static void li_shadow(void *user, hrm_real t, hrm_real out[NCH]) { light_eval(user, t, out, LIGHT_SHADOW); }
static void li_point(void *user, hrm_real t, hrm_real out[NCH]) { light_eval(user, t, out, LIGHT_POINT); }

hrm_spectrum_fn light_Li(int light)
{
    switch (light) {
    case LIGHT_DIR: return li_dir;
    case LIGHT_TAU: return li_tau;
    case LIGHT_CONST: return li_const;
    case LIGHT_SHADOW: return li_shadow;
    case LIGHT_POINT: return li_point;
    default: return NULL;
    }
}

/* ------------------------------------------------------------------------
   Problems
   ------------------------------------------------------------------------ */
problem make_problem(scene *sc, int kind, int le, int light)
{
    problem p;
    p.sc = sc;
    p.kind = kind;
    p.le = le;
    p.light = light;
    p.tr = 0;
    p.sigmas = SIGMA_AS;
    p.flags = 0;
    return p;
}

hrm_medium zero_medium(void)
{
    hrm_medium m;
    memset(&m, 0, sizeof m);
    return m;
}

hrm_medium problem_medium(const problem *p)
{
    hrm_medium m = zero_medium();
    int c;
    m.user = p->sc;
    m.flags = p->flags;
    if (p->le) m.Le = const_Le;
    m.Li = light_Li(p->light);
    if (p->kind == P_HOM) {
        m.flags |= HRM_MEDIUM_HOMOGENEOUS;
        for (c = 0; c < NCH; ++c) {
            m.const_sigma_a[c] = (hrm_real)p->sc->sig_a[c];
            m.const_sigma_s[c] = (hrm_real)p->sc->sig_s[c];
        }
        return m;
    }
    if (p->sigmas == SIGMA_A) {
        m.sigma_a = het_absorber;
    } else if (p->sigmas == SIGMA_ONE) {
        m.sigma = het_sigma;
    } else if (p->sigmas == SIGMA_TS) {
        m.sigma_t = het_sigma_t;
        m.sigma_s = het_sigma_s;
    } else {
        m.sigma_a = het_sigma_a;
        m.sigma_s = het_sigma_s;
    }
    if (p->tr) m.transmittance = het_transmittance;
    return m;
}

double exact_tau(const problem *p, int c, double t0, double t1)
{
    if (p->kind == P_HOM) return sig_t_hom(p->sc, c) * (t1 - t0);
    return tau_het(p->sc, c, t0, t1);
}

double exact_tr(const problem *p, int c, double t0, double s)
{
    if (p->kind == P_HOM) return exp(-sig_t_hom(p->sc, c) * (s - t0));
    return exp(-tau_het(p->sc, c, t0, s));
}

/* sigma_a of a heterogeneous medium as a fraction of sigma_t */
static double het_pa(const problem *p, int c)
{
    return p->sigmas == SIGMA_A ? 1.0 : p->sc->pa[c];
}

double exact_S(const problem *p, int c, double s)
{
    const scene *sc = p->sc;
    double S = 0;
    int per_length = (p->flags & HRM_EMISSION_PER_LENGTH) != 0;
    if (p->kind == P_HOM) {
        if (p->le) S += (per_length ? 1.0 : sc->sig_a[c]) * sc->le[c];
        if (p->light) S += sc->sig_s[c] * light_value(sc, p->light, c, s);
    } else {
        double pa = het_pa(p, c), st = sig_t_het(sc, c, s);
        if (p->le) S += (per_length ? 1.0 : pa * st) * sc->le[c];
        if (p->light && p->sigmas != SIGMA_A) S += (1.0 - pa) * st * light_value(sc, p->light, c, s);
    }
    return S;
}

double exact_f(const problem *p, int c, double t0, double s)
{
    return exact_tr(p, c, t0, s) * exact_S(p, c, s);
}

/* Per channel, sigma_t = sigma_a + sigma_s, T = t1 - t0:
   homogeneous, Le:  Le sigma_a/sigma_t (1 - e^{-sigma_t T})
                     (Le/sigma_t (...) with HRM_EMISSION_PER_LENGTH)
     LIGHT_DIR:      sigma_s E e^{-sigma_t (d0 + k t0)} (1 - e^{-lam T}) / lam,
                     lam = sigma_t (1 + k)
     LIGHT_CONST:    sigma_s E / sigma_t (1 - e^{-sigma_t T})
     LIGHT_SHADOW:   sigma_s E / sigma_t (1 - e^{-sigma_t (lo - t0)}
                     + e^{-sigma_t (hi - t0)} - e^{-sigma_t T})
   heterogeneous, tau = tau_het(t0, t1), Tr = e^{-tau}:
     Le:             pa Le (1 - Tr)  (sigma_a Le Tr = -pa Le d/ds Tr)
     LIGHT_TAU:      (1 - pa) E e^{c tau_abs(t0)} (1 - Tr^{1-c}) / (1 - c)
   T = +inf is allowed (e^{-inf} = 0). */
double exact_L(const problem *p, int c, double t0, double t1)
{
    const scene *sc = p->sc;
    double L = 0, T = t1 - t0;
    int per_length = (p->flags & HRM_EMISSION_PER_LENGTH) != 0;
    if (p->kind == P_HOM) {
        double st = sig_t_hom(sc, c);
        if (p->le) L += (per_length ? 1.0 : sc->sig_a[c]) * sc->le[c] * -expm1(-st * T) / st;
        switch (p->light) {
        case LIGHT_NONE: break;
        case LIGHT_DIR: {
            double lam = st * (1.0 + sc->k);
            L += sc->sig_s[c] * sc->E[c] * exp(-st * (sc->d0 + sc->k * t0)) * -expm1(-lam * T) / lam;
            break;
        }
        case LIGHT_CONST: L += sc->sig_s[c] * sc->E[c] / st * -expm1(-st * T); break;
        case LIGHT_SHADOW:
            L += sc->sig_s[c] * sc->E[c] / st *
                 (-expm1(-st * (sc->lo - t0)) + exp(-st * (sc->hi - t0)) - exp(-st * T));
            break;
        default: return (double)NAN; /* no closed form used */
        }
    } else {
        double tau = tau_het(sc, c, t0, t1), pa = het_pa(p, c);
        if (per_length || sc->profile != PROFILE_SINE) return (double)NAN;
        if (p->le) L += pa * sc->le[c] * -expm1(-tau);
        if (p->light != LIGHT_NONE && p->sigmas != SIGMA_A) {
            double cc = sc->cexp;
            if (p->light != LIGHT_TAU) return (double)NAN;
            L += (1.0 - pa) * sc->E[c] * exp(cc * tau_abs(sc, c, t0)) * -expm1(-(1.0 - cc) * tau) /
                 (1.0 - cc);
        }
    }
    return L;
}

double max_tau(const problem *p, double t0, double t1)
{
    double m = 0;
    int c;
    for (c = 0; c < NCH; ++c) {
        double tau = exact_tau(p, c, t0, t1);
        if (tau > m) m = tau;
    }
    return m;
}

double rel_err_L(const problem *p, double t0, double t1, const hrm_result *r)
{
    double e = 0;
    int c;
    for (c = 0; c < NCH; ++c) {
        double x = exact_L(p, c, t0, t1);
        double d = fabs((double)r->L[c] - x) / fabs(x);
        if (!(d <= e)) e = d; /* NaN propagates */
    }
    return e;
}

typedef struct exact_f_ctx {
    const problem *p;
    int c;
    double t0;
} exact_f_ctx;

static double exact_f_of(const void *ctx, double s)
{
    const exact_f_ctx *x = (const exact_f_ctx *)ctx;
    return exact_f(x->p, x->c, x->t0, s);
}

double gl_exact_f(const problem *p, int c, double t0, double a, double b, int panels)
{
    exact_f_ctx x;
    x.p = p;
    x.c = c;
    x.t0 = t0;
    return gl_integrate(exact_f_of, &x, a, b, panels, 10, 0, 0);
}

double rel_err_Tr(const problem *p, double t0, double t1, const hrm_real *Tr)
{
    double e = 0;
    int c;
    for (c = 0; c < NCH; ++c) {
        double x = exact_tr(p, c, t0, t1);
        double d = fabs((double)Tr[c] - x) / x;
        if (!(d <= e)) e = d;
    }
    return e;
}

/* ------------------------------------------------------------------------
   Methods, options, solving, results
   ------------------------------------------------------------------------ */
const hrm_method every_method[N_METHODS_ALL] = {
    HRM_RECTANGLE, HRM_SIMPSON, HRM_MONTE_CARLO, HRM_EULER, HRM_RK4, HRM_ADAMS_BASHFORTH,
    HRM_NESTED_SIMPSON, HRM_GAUSS_KRONROD, HRM_BOGACKI_SHAMPINE, HRM_DORMAND_PRINCE,
    HRM_FEHLBERG, HRM_CASH_KARP, HRM_VERNER, HRM_ANALYTIC_MARCH };

/* every_method lists every method of hrm.h: fails to compile otherwise */
typedef char every_method_is_complete[N_METHODS_ALL == (int)HRM_METHOD_COUNT - 1 ? 1 : -1];

int is_ivp(hrm_method m) { return m == HRM_EULER || m == HRM_RK4 || m == HRM_ADAMS_BASHFORTH; }

int is_adaptive(hrm_method m) { return m >= HRM_NESTED_SIMPSON && m <= HRM_VERNER; }

int is_pair(hrm_method m) { return m >= HRM_BOGACKI_SHAMPINE && m <= HRM_VERNER; }

const char *form_name(hrm_form f) { return f == HRM_FORM_RTE ? "rte" : "optical-depth"; }

hrm_options make_options(hrm_method m, int steps, hrm_form form)
{
    hrm_options o = hrm_default_options(m);
    o.steps = steps;
    o.form = form;
    return o;
}

hrm_options warp_options(hrm_method m, double rtol, int w, double delta, double D)
{
    hrm_options o = hrm_default_options(m);
    o.rtol = (hrm_real)rtol;
    if (w == 1) o.warp.kind = HRM_WARP_DISTANCE;
    if (w == 2) {
        o.warp.kind = HRM_WARP_EQUIANGULAR;
        o.warp.delta = (hrm_real)delta;
        o.warp.D = (hrm_real)D;
    }
    return o;
}

hrm_status solve_opt(const problem *p, double t0, double t1, const hrm_options *o, hrm_result *r)
{
    hrm_medium m = problem_medium(p);
    return hrm_solve(&m, (hrm_real)t0, (hrm_real)t1, o, r);
}

hrm_status solve(const problem *p, double t0, double t1, hrm_method m, int n, hrm_form form,
                 hrm_result *r)
{
    hrm_options o = make_options(m, n, form);
    return solve_opt(p, t0, t1, &o, r);
}

int result_finite(const hrm_result *r)
{
    int c, ok = 1;
    for (c = 0; c < NCH; ++c) ok &= finite_d((double)r->L[c]) && finite_d((double)r->Tr[c]);
    return ok;
}

int is_error_result(const hrm_result *r)
{
    int c, ok = 1;
    for (c = 0; c < NCH; ++c) ok &= r->L[c] == 0 && r->Tr[c] == 1;
    return ok;
}

int same_solve(const hrm_result *a, const hrm_result *b)
{
    int c, ok = a->stats.evals == b->stats.evals && a->stats.steps == b->stats.steps;
    for (c = 0; c < NCH; ++c) ok &= a->L[c] == b->L[c] && a->Tr[c] == b->Tr[c];
    return ok;
}

int same_result(const hrm_result *a, const hrm_result *b)
{
    return same_solve(a, b) && a->stats.medium_evals == b->stats.medium_evals;
}

void fog_sigma(void *user, hrm_real t, hrm_real sa[HRM_CHANNELS], hrm_real ss[HRM_CHANNELS])
{
    const test_fog *f = (const test_fog *)user;
    int c;
    (void)t;
    for (c = 0; c < HRM_CHANNELS; ++c) {
        sa[c] = (hrm_real)(f->st - f->ss);
        ss[c] = (hrm_real)f->ss;
    }
}

hrm_medium fog_medium(void *user, hrm_spectrum_fn li, int cb)
{
    const test_fog *f = (const test_fog *)user;
    hrm_medium m;
    int c;
    memset(&m, 0, sizeof m);
    m.user = user;
    m.Li = li;
    if (cb) {
        m.sigma = fog_sigma;
    } else {
        m.flags = HRM_MEDIUM_HOMOGENEOUS;
        for (c = 0; c < HRM_CHANNELS; ++c) {
            m.const_sigma_a[c] = (hrm_real)(f->st - f->ss);
            m.const_sigma_s[c] = (hrm_real)f->ss;
        }
    }
    return m;
}
