/* bench/qag.h - a general-purpose quadrature to measure hrm against: the
   globally adaptive Gauss-Kronrod algorithm of QUADPACK's QAG (Piessens,
   de Doncker-Kapenga, Ueberhuber and Kahaner 1983) with its 15-point rule,
   the routine GSL ships as gsl_integration_qag (GSL_INTEG_GAUSS15). Written
   here from the algorithm's description, independent of hrm: it is given
   the scene's integrand Tr(t0, s) S(s) with the exact transmittance (the
   reference's, reference.h), as a host would hand a quadrature package
   its integrand, and sees nothing else (no breakpoints, no warp).

   Vector form: one evaluation gives every channel (as one of hrm's
   evaluations does); each channel keeps QUADPACK's error estimate, an
   interval is judged by its worst channel's share of that channel's
   tolerance, and the integration ends when every channel's summed error
   is within epsrel times its integral. Left out: QUADPACK's round-off
   exits and its refusal of epsrel below 50 epsilons (the bench's
   tolerances stay above). Checked once against GSL 2.7.1's
   gsl_integration_qag (GAUSS15, epsabs 0) outside the repository: the
   same evaluations and values to 2e-16 on five integrands (exp(-x),
   a Lorentzian peak, sqrt(x), two small oscillations) at epsrel 1e-2 to
   1e-13. */
#ifndef BENCH_QAG_H
#define BENCH_QAG_H

#include "reference.h"

#define QAG_LIMIT 1000 /* subintervals at most (GSL's workspace size in its examples) */

/* The integral over [a, b] of f (t0 passed through) to relative
   tolerance epsrel into out; returns the evaluations made (15 a rule),
   and sets *ok to 0 where the limit was reached first. */
long qag_integrate(ref_integrand_fn f, const void *params, double t0, double a, double b, double epsrel,
                   double out[HRM_CHANNELS], int *ok);

/* The rule's self-check: the largest error of its Kronrod and Gauss
   weights on the monomials they integrate exactly (degree 22 and 13 on
   [-1, 1]), relative to the exact value. */
double qag_rule_check(void);

#endif
