/* bench/qag.c - QUADPACK's QAG with the 15-point Gauss-Kronrod rule, the
   general-purpose quadrature of qag.h. */
#include "qag.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

/* The 15-point Kronrod rule and its 7-point Gauss rule on [-1, 1],
   positive abscissae, outermost first: QUADPACK's qk15 table (Fullerton's
   values, as QUADPACK 1983 and GSL print them). xgk[1], xgk[3], xgk[5]
   are the Gauss nodes (weights wg[0..2]), xgk[7] = 0 is shared (wg[3]). */
static const double xgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                              0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                              0.586087235467691130294144838258730, 0.405845151377397166906606412076961,
                              0.207784955007898467600689403773245, 0.0};
static const double wgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                              0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                              0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                              0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                             0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

typedef struct qag_iv {
    double a, b;
    double r[HRM_CHANNELS], e[HRM_CHANNELS]; /* the rule's integral and error estimate */
    int sat[HRM_CHANNELS]; /* the estimate is resasc itself (saturated) */
} qag_iv;

static void qag_f(ref_integrand_fn f, const void *params, double t0, double s, double out[HRM_CHANNELS])
{
    long double v[HRM_CHANNELS];
    int c;
    f(params, (long double)t0, (long double)s, v);
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (double)v[c];
}

/* QUADPACK's qk15 on [a, b], per channel: the Kronrod value, and its error
   estimate |K - G| h made QUADPACK's way: scaled by the integral of |f -
   mean| (resasc) as resasc min(1, (200 |K - G| h / resasc)^1.5), and at
   least 50 epsilons of the integral of |f| (resabs). */
static void qag_rule(ref_integrand_fn f, const void *params, double t0, qag_iv *v)
{
    double centr = v->a / 2 + v->b / 2, hl = (v->b - v->a) / 2;
    double fc[HRM_CHANNELS], fv1[7][HRM_CHANNELS], fv2[7][HRM_CHANNELS];
    double resg[HRM_CHANNELS], resk[HRM_CHANNELS], resabs[HRM_CHANNELS], resasc[HRM_CHANNELS];
    int j, c;
    qag_f(f, params, t0, centr, fc);
    for (c = 0; c < HRM_CHANNELS; ++c) {
        resg[c] = fc[c] * wg[3];
        resk[c] = fc[c] * wgk[7];
        resabs[c] = fabs(resk[c]);
    }
    for (j = 0; j < 7; ++j) {
        double absc = hl * xgk[j];
        qag_f(f, params, t0, centr - absc, fv1[j]);
        qag_f(f, params, t0, centr + absc, fv2[j]);
        for (c = 0; c < HRM_CHANNELS; ++c) {
            double sum = fv1[j][c] + fv2[j][c];
            if (j % 2 == 1) resg[c] += wg[j / 2] * sum;
            resk[c] += wgk[j] * sum;
            resabs[c] += wgk[j] * (fabs(fv1[j][c]) + fabs(fv2[j][c]));
        }
    }
    for (c = 0; c < HRM_CHANNELS; ++c) {
        double mean = resk[c] / 2, err;
        resasc[c] = wgk[7] * fabs(fc[c] - mean);
        for (j = 0; j < 7; ++j) resasc[c] += wgk[j] * (fabs(fv1[j][c] - mean) + fabs(fv2[j][c] - mean));
        v->r[c] = resk[c] * hl;
        resabs[c] *= fabs(hl);
        resasc[c] *= fabs(hl);
        err = fabs((resk[c] - resg[c]) * hl);
        if (resasc[c] != 0 && err != 0) {
            double scale = pow(200 * err / resasc[c], 1.5);
            err = scale < 1 ? resasc[c] * scale : resasc[c];
        }
        v->sat[c] = err == resasc[c];
        if (resabs[c] > DBL_MIN / (50 * DBL_EPSILON) && err < 50 * DBL_EPSILON * resabs[c])
            err = 50 * DBL_EPSILON * resabs[c];
        v->e[c] = err;
    }
}

long qag_integrate(ref_integrand_fn f, const void *params, double t0, double a, double b, double epsrel,
                   double out[HRM_CHANNELS], int *ok)
{
    qag_iv *iv = (qag_iv *)malloc(sizeof *iv * QAG_LIMIT);
    double area[HRM_CHANNELS], err[HRM_CHANNELS];
    long evals = 0;
    int n = 1, c, i;
    *ok = 1;
    if (!iv) {
        *ok = 0;
        return 0;
    }
    iv[0].a = a;
    iv[0].b = b;
    qag_rule(f, params, t0, &iv[0]);
    evals += 15;
    for (;;) {
        int done = 1, worst = 0;
        double wscore = -1;
        for (c = 0; c < HRM_CHANNELS; ++c) {
            area[c] = err[c] = 0;
            for (i = 0; i < n; ++i) {
                area[c] += iv[i].r[c];
                err[c] += iv[i].e[c];
            }
            done &= err[c] <= epsrel * fabs(area[c]);
            /* the first rule alone is not trusted where its estimate is
               resasc itself (QUADPACK's first test: abserr != resasc, or
               abserr 0) */
            if (n == 1 && iv[0].sat[c] && iv[0].e[c] != 0) done = 0;
        }
        if (done) break;
        if (n == QAG_LIMIT) {
            *ok = 0;
            break;
        }
        /* the interval with the largest error, each channel's against its
           tolerance */
        for (i = 0; i < n; ++i)
            for (c = 0; c < HRM_CHANNELS; ++c) {
                double tol = epsrel * fabs(area[c]), s = tol > 0 ? iv[i].e[c] / tol : iv[i].e[c];
                if (s > wscore) {
                    wscore = s;
                    worst = i;
                }
            }
        {
            double mid = iv[worst].a / 2 + iv[worst].b / 2;
            if (!(mid > iv[worst].a && mid < iv[worst].b)) {
                *ok = 0; /* bisected to the resolution of s */
                break;
            }
            iv[n] = iv[worst];
            iv[worst].b = mid;
            iv[n].a = mid;
            qag_rule(f, params, t0, &iv[worst]);
            qag_rule(f, params, t0, &iv[n]);
            evals += 30;
            n++;
        }
    }
    for (c = 0; c < HRM_CHANNELS; ++c) out[c] = area[c];
    free(iv);
    return evals;
}

double qag_rule_check(void)
{
    double worst = 0;
    int k, j;
    for (k = 0; k <= 22; k += 2) {
        /* integral of x^k over [-1, 1]: 2 / (k + 1); odd degrees vanish by
           symmetry */
        double exact = 2.0 / (k + 1), K = wgk[7] * (k == 0 ? 1 : 0), G = wg[3] * (k == 0 ? 1 : 0);
        for (j = 0; j < 7; ++j) {
            double p = 2 * pow(xgk[j], k);
            K += wgk[j] * p;
            if (j % 2 == 1) G += wg[j / 2] * p;
        }
        if (fabs(K - exact) / exact > worst) worst = fabs(K - exact) / exact;
        if (k <= 13 && fabs(G - exact) / exact > worst) worst = fabs(G - exact) / exact;
    }
    return worst;
}
