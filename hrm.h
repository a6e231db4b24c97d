/* hrm.h - higher-order ray marching for the radiative transfer equation.
   Version 0.1.0. Single-file C99 library; no dependencies but libm.

   ==========================================================================
   QUICK START
   ==========================================================================
   Define HRM_IMPLEMENTATION in exactly one C or C++ file before including
   this header; every other file includes it plainly.

   ---- quick start begin ----
   #define HRM_IMPLEMENTATION
   #include "hrm.h"
   #include <math.h>
   #include <stdio.h>
   #include <string.h>

   // A point light of intensity I in homogeneous fog; the camera ray runs
   // from the origin along +z.
   typedef struct fog_scene {
       double light[3], I, sigma_t;
   } fog_scene;

   // In-scattered radiance toward the camera at distance t: the light's
   // intensity over r^2, attenuated on its way (your shadow ray goes here),
   // times an isotropic phase function.
   static void in_scatter(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]) {
       const fog_scene *s = (const fog_scene *)user;
       double dx = s->light[0], dy = s->light[1], dz = s->light[2] - (double)t;
       double r2 = dx * dx + dy * dy + dz * dz;
       double v = s->I * exp(-s->sigma_t * sqrt(r2)) / r2 / (4 * 3.14159265358979);
       int c;
       for (c = 0; c < HRM_CHANNELS; ++c) out[c] = (hrm_real)v;
   }

   int main(void) {
       fog_scene s = {{0, 0.5, 5}, 10, 0.3};
       hrm_real origin[3] = {0, 0, 0}, dir[3] = {0, 0, 1}, t0 = 0, t1 = 20;
       hrm_medium fog;
       hrm_light lamp;
       hrm_ray_plan plan;
       hrm_options opt = hrm_default_options(HRM_NESTED_SIMPSON);
       hrm_result res;
       hrm_status st;
       int c;

       memset(&fog, 0, sizeof fog);         // zero: every term absent
       fog.user = &s;
       fog.flags = HRM_MEDIUM_HOMOGENEOUS;  // constants: Tr in closed form
       for (c = 0; c < HRM_CHANNELS; ++c) {
           fog.const_sigma_a[c] = (hrm_real)0.05;
           fog.const_sigma_s[c] = (hrm_real)0.25;
       }
       fog.Li = in_scatter;

       // the light described: hrm turns it into the ray's warp (samples
       // where the light is) and breakpoints
       memset(&lamp, 0, sizeof lamp);
       lamp.kind = HRM_LIGHT_POINT;
       for (c = 0; c < 3; ++c) lamp.position[c] = (hrm_real)s.light[c];
       lamp.power = (hrm_real)s.I;
       opt.rtol = (hrm_real)1e-3;           // the relative error of L you accept
       if (hrm_light_options(&lamp, 1, NULL, 0, origin, dir, t0, t1, &plan, &opt) != HRM_OK) return 1;

       st = hrm_solve(&fog, t0, t1, &opt, &res);
       if (st < 0) return 1;
       // pixel = res.L + res.Tr * (the radiance of the surface at t1)
       for (c = 0; c < HRM_CHANNELS; ++c)
           printf("L[%d] = %.6g  Tr[%d] = %.6g\n", c, (double)res.L[c], c, (double)res.Tr[c]);
       printf("%s, %ld Li calls\n", hrm_status_string(st), res.stats.evals);
       return 0;
   }
   ---- quick start end ----

   ==========================================================================
   DEFINITIONS
   ==========================================================================
   t      distance along the ray from its origin; a call integrates from t0
          (the camera end) to t1 (a surface, or where the medium ends).
   sigma_a, sigma_s, sigma_t   absorption, scattering, extinction (1/length;
          sigma_t = sigma_a + sigma_s unless given separately).
   tau    optical depth from t0, the integral of sigma_t; Tr = exp(-tau), the
          result's Tr is Tr(t0, t1).
   Le     emitted radiance: the source is sigma_a Le (Munoz 2014 eq. 1,
          pbrt-v4), or Le with HRM_EMISSION_PER_LENGTH (pbrt-v2, Cycles).
   Li     in-scattered radiance toward the camera, phase function and the
          light's transmittance applied: the host's (shadow rays, ...).
   S      the source sigma_a Le + sigma_s Li. L = integral over [t0, t1] of
          Tr(t0, t) S(t), the medium's radiance: pixel = L + Tr L_surface.
   evaluation   one call of the source (Le and/or Li) at one abscissa, at
          most once per abscissa: the cost that matters (each Li is a
          shadow ray), hrm_stats.evals. A medium evaluation (sigma or
          transmittance callbacks): hrm_stats.medium_evals.

   ==========================================================================
   THE SCENE: hrm_medium
   ==========================================================================
   Every member is optional; an absent (NULL) term is never called:
     sigma_a, sigma_s  NULL: zero.     sigma_t  NULL: sigma_a + sigma_s.
     sigma             both coefficients from one call (one lookup);
                       with any of the three above: HRM_ERR_BAD_MEDIUM.
     Le, Li            NULL: absent; never called where sigma_a (Le, unless
                       per length) or sigma_s (Li) is 0 in every channel.
     transmittance     closed-form Tr(ta, tb) of the eye ray (no scan for
                       jumps: give sigma's as breakpoints); NULL: hrm
                       integrates sigma_t (TRANSMITTANCE).
   flags |= HRM_MEDIUM_HOMOGENEOUS with const_sigma_a / const_sigma_s: the
   callbacks above are ignored, Tr is exp(-sigma_t (tb - ta)), no medium
   evaluation. Callbacks return finite values, coefficients and sources
   >= 0, a transmittance in [0, 1] not rising with t; anything else stops
   the solve with HRM_ERR_CALLBACK_VALUE (no call after the bad value).

   ==========================================================================
   CONFIGURATION (define before including)
   ==========================================================================
   HRM_IMPLEMENTATION  compile the implementation into this file.
   HRM_STATIC          make every function static (private to one file).
   HRM_REAL            scalar type, double by default; float works too.
   HRM_CHANNELS        colour channels, 3 by default; 1 to 64.
   HRM_MAX_BREAKS      breakpoints per ray, 64 (1-1024); HRM_MAX_JUMPS jumps
                       reported, 8 (1-256); HRM_MAX_LIGHTS lights weighed
                       by hrm_light_options, 8 (1-64).
   Storage (fixed arrays, held only by the solves that use them; where
   they run out a solve finishes left to right or warns HRM_WARN_STORAGE):
   HRM_NS_INTERVALS 64 (8-4096), HRM_NS_PANELS 32 (1-HRM_NS_INTERVALS):
                       nested Simpson's intervals and initial panels.
   HRM_GK_INTERVALS 128 (8-4096), HRM_GK_INITIAL 32: global Gauss-Kronrod's.
   HRM_MAX_DEPTH 60 (8-200): the left-to-right finish's depth.
   HRM_TAU_PANELS 128 (16-65536): the layer's panel table (on the stack 32,
                       8 for the pairs, 4 for the fixed-step rules).
   HRM_SHADOW_PANELS 48 (16-4096): the shadow-ray estimator's a segment.
   A value outside its range fails to compile (a static assertion).
   HRM_ASSERT(x)       internal invariants only; assert() by default.
   HRM_SQRT, HRM_EXP, HRM_EXPM1, HRM_LOG, HRM_LOG1P, HRM_POW, HRM_FABS,
   HRM_SIN, HRM_COS, HRM_ATAN2, HRM_HYPOT: math functions; by default the
                       libm function of HRM_REAL's type (expf, exp).

   ==========================================================================
   ERRORS
   ==========================================================================
   Every call that can fail returns hrm_status: HRM_OK (0), a negative error
   (no usable answer: the result holds L = 0, Tr = 1 and the stats counted so
   far) or a positive warning (a usable estimate that missed what was asked;
   the result holds it). hrm_status_string() names each. Bad input never
   aborts, never crashes and never writes anything but the result.
   Range: R = the largest HRM_REAL / 1024 / max(1, t1 - t0) (1.7e305 in
   double on a unit ray, 3.3e35 in float). Every coefficient and source,
   also times a warp's dt/du, within R keeps every sum of every rule finite;
   beyond it, or where t1 - t0 or the RTE form's solution overflows it, the
   call returns HRM_ERR_RANGE (constants: before any evaluation;
   callbacks: at that sample) rather than inf or NaN.

   ==========================================================================
   BAD INPUT
   ==========================================================================
   Every class of bad or extreme input and what it returns; one test each
   (tests/test_bad_input.c, every method of the row, hrm_solve and
   hrm_transmittance, the result between canary bytes). "before": rejected
   before any callback (stats zero). "at": the solve stops at the bad value
   (stats counted so far, no callback called after it). An error's result
   is L = 0, Tr = 1, error = -1, njumps = 0; nothing but the result (and
   hrm_transmittance's stats) is written. R: see ERRORS, Range. Where two
   classes meet, the status is that of the one listed first.
   pointers
     medium NULL, result NULL (hrm_transmittance: Tr NULL, stats zeroed)
                                   HRM_ERR_NULL_ARGUMENT, before
     options NULL; stats NULL (hrm_transmittance); every callback NULL
                                   valid: defaults; absent terms
     breaks NULL with nbreaks > 0  HRM_ERR_BAD_BREAKS, before
     a user warp without t_of_u, dt_du or u_of_t
                                   HRM_ERR_BAD_WARP, before
   the interval
     t0 NaN or +-inf; t1 NaN or -inf; t1 < t0; t1 = +inf without a warp
     that ends it                  HRM_ERR_BAD_INTERVAL, before
     t1 = +inf under the distance or equiangular warp; t1 = t0; t1
     denormal; both ends 1e30      valid (warnings where t cannot resolve
                                   the medium: ROUNDOFF, H_MIN, TOLERANCE)
     t1 - t0 overflows             HRM_ERR_RANGE, before
     t1 huge (max / 4): coefficients or sources beyond R over that length
                                   HRM_ERR_RANGE (constants before, callbacks at)
   options: enumerators and counts
     method < 0 or >= HRM_METHOD_COUNT (also from hrm_default_options)
                                   HRM_ERR_BAD_METHOD, before
     steps < 0 (INT_MIN)           HRM_ERR_BAD_STEPS, before
     steps huge                    valid: fixed-step methods take N (no cap);
                                   nested Simpson and Gauss-Kronrod cap their
                                   initial panels; the pairs ignore it
     form, control, gk_mode, gk_rule, tau_mode unknown; find_jumps outside
     -1..1; exponential outside 0..2, or 1, 2 with a rule that has no fit,
     the RTE form or coupled tau   HRM_ERR_BAD_OPTION, before
     jitter, stratified any nonzero int
                                   valid: on
   options: tolerances, step bounds, budgets
     rtol, atol, h_min, h_max, h0, tau_tol, tr_tol, cutoff negative, NaN
     or infinite; cutoff above 1;
     h_max > 0 with h_min > h_max  HRM_ERR_BAD_OPTION, before
     max_evals < 0, or below one step of the method on every piece
     (adaptive)                    HRM_ERR_BAD_OPTION, before
     workspace below hrm_workspace_size or not aligned to 16; NULL with
     a workspace_size              HRM_ERR_BAD_OPTION, before
     rtol denormal                 raised to 100 eps: HRM_WARN_RTOL_CLIPPED
                                   (adaptive; fixed-step ignore rtol)
     tau_tol, tr_tol denormal      raised to 64 eps, silently
     rtol, atol, tau_tol, h_max, h0 huge; h_min huge (one step, H_MIN
     where it is refused); h_min, h0 denormal; max_evals LONG_MAX, or 1 for
     a fixed-step method (ignored) valid
   breakpoints
     nbreaks < 0 or > HRM_MAX_BREAKS (even INT_MAX, which no budget check
     sees first); an entry NaN or infinite, not strictly increasing, below
     t0 or above t1                HRM_ERR_BAD_BREAKS, before
     entries at t0 and t1          valid (no piece of zero length)
   warps
     kind unknown; sigma_ref or D negative, NaN or infinite; delta not
     finite - also on an empty ray HRM_ERR_BAD_WARP, before
     sigma_ref huge                valid: lowered to what the ray resolves
     sigma_ref denormal; D or delta huge (the light far from the whole
     ray)                          valid: no warp (the map is affine)
     D = 0 with the light on the ray
                                   HRM_ERR_SINGULAR, before
     D = 0 or u's range < sqrt(eps), the foot d off the ray (d < t1 - t0)
                                   valid: D = d / 8 where eps |t| / d <=
                                   sqrt(eps); else no warp (t1 = +inf:
                                   D = 0 BAD_INTERVAL, else distance warp
                                   and ROUNDOFF)
     user warp: u_of_t not increasing or not finite at t0 or t1
                                   HRM_ERR_BAD_WARP (only u_of_t called)
     user warp: t_of_u, u_of_t NaN or infinite inside the ray; dt_du < 0,
     NaN or infinite (a warp that folds back)
                                   HRM_ERR_CALLBACK_VALUE, at
     dt_du beyond R / (sigma or source)
                                   HRM_ERR_RANGE, at
   the medium
     const_sigma_a, const_sigma_s negative, NaN or infinite (homogeneous);
     an unknown bit in flags; feature negative, NaN or infinite; sigma
     given with sigma_a, sigma_s or sigma_t (even homogeneous)
                                   HRM_ERR_BAD_MEDIUM, before
     feature denormal or huge      valid: the scan's 4097 points at most,
                                   its 9 a piece at least
     a constant beyond R           HRM_ERR_RANGE, before
     a constant denormal; within R (warnings where the ray is opaque
     within t's resolution)        valid
   callbacks' values
     sigma_a, sigma_s, sigma_t, sigma NaN, infinite or negative (even
     -1e-30);
     Le, Li NaN, infinite or negative; a transmittance NaN, infinite,
     below 0, above 1, or rising along the ray (beyond 64 eps of
     max(1, tau) relative)         HRM_ERR_CALLBACK_VALUE, at
     a coefficient, or sigma_a Le + sigma_s Li, beyond R
                                   HRM_ERR_RANGE, at
     any value denormal; sources within R (also emission per length)
                                   valid
   the other functions
     hrm_equiangular_warp: a NULL argument; dir zero; a value not finite
                                   HRM_ERR_NULL_ARGUMENT, HRM_ERR_BAD_WARP;
                                   *warp zeroed (HRM_WARP_NONE) where given
     hrm_equiangular_warp: a light 1e307 or 1e-310 off the ray
                                   valid: D to full precision
     hrm_sphere_breaks: a NULL argument; dir zero; radius negative or NaN;
     t0 not finite, t1 < t0 or NaN; a point not finite
                                   HRM_ERR_NULL_ARGUMENT, HRM_ERR_BAD_WARP;
                                   *count 0 where given, out untouched
     hrm_sphere_breaks: t1 = +inf; a sphere 1e307 away
                                   valid
     hrm_status_string, hrm_method_name: unknown values
                                   "unknown status", "?"

   ==========================================================================
   THREAD SAFETY AND MEMORY
   ==========================================================================
   hrm holds no global or static mutable state and never allocates. Calls
   are thread-safe and re-entrant: an Li callback may call hrm_transmittance
   (or hrm_solve) for its shadow ray. Randomness (Monte Carlo, jitter) comes
   from options.seed alone: the same inputs give the same answer.
   Stack (tests/stack.c, worst case, double, 3 channels, gcc/clang -O2):
   fixed-step 5-7.5 KiB, 9.5-10.5 with the transmittance layer (8.8-10 with
   at most 7 breakpoints, 11.5-12.5 with find_jumps 1); pairs 22-23; Gauss-
   Kronrod 79-82, nested Simpson 89-92; the shadow-ray estimator 11.5; 2.2
   times that with 8 channels, half in float, at most 48 (1 + HRM_CHANNELS)
   KiB; twice with a shadow ray in Li. options.workspace (hrm_workspace_size
   bytes, aligned to 16, one a thread) holds layer, adaptive storage, panels,
   context: same answers; fixed-step 5 KiB, every method 18.5, 35 nested.
   GPU kernels: under nvcc or hipcc every function is __host__ __device__
   (HRM_DEVICE; define it to override) and the tables exist on both sides.
   Build the medium in the kernel (callbacks: device functions), give each
   thread a device slice as options.workspace, raise cudaLimitStackSize
   (make gpu prints each method's least); float on consumer GPUs (README).

   ==========================================================================
   ARCHITECTURE
   ==========================================================================
   hrm_solve -> hrm__run: options resolved (hrm__resolve), the storage
   the configuration needs (hrm__needs) held in frames of its own, then
   hrm__solve_job: hrm__setup (input checks; where tau comes from,
   hrm__tau_source; the warp), hrm__scan_medium (jumps of sigma made
   breakpoints), hrm__dispatch (the pieces between breakpoints, each by
   the driver of the method's family in the method table: fixed-step,
   worst-first quadrature, local Gauss-Kronrod, Runge-Kutta pairs; solved
   again where a jump or a missed medium sample was found), hrm__finish
   (Tr, the bound on L, the status). Every abscissa goes through hrm__eval:
   the warp's map, the memo, the medium and Tr, Le and Li, times dt/du.

   ==========================================================================
   ACCURACY AND COST   (N = options.steps; evaluations = source samples)
   ==========================================================================
   method               order  evaluations     notes
   HRM_RECTANGLE        2 (1)  N               midpoints; jitter: one offset
                                               a ray, order 1 (unbiased
                                               with a closed-form Tr)
   HRM_SIMPSON          4      2N + 1          N panels
   HRM_MONTE_CARLO      N^-1/2 N               stratified: N^-3/2 (smooth)
   HRM_EULER            1      N
   HRM_RK4              4      2N + 1
   HRM_ADAMS_BASHFORTH  4      N + 3           4-step, RK4 start (N >= 4)
   HRM_ANALYTIC_MARCH   2 (1)  N               Hillaire 2015: extinction
                                               exact a step in t, S/sigma_t
                                               held (equiangular: S dt/du);
                                               0 <= L <= sup(S/sigma_t)(1-Tr)
   HRM_NESTED_SIMPSON   6      4 a split       Lyness: Simpson on halves vs
                                               whole, Richardson-corrected;
                                               worst first (the default)
   HRM_GAUSS_KRONROD    22/12  15 or 7 an      K15 (G7/K15) or K7 (G3/K7);
                               interval + 2    gk_mode GLOBAL (worst first)
                                               or LOCAL (Munoz's recursion)
   HRM_BOGACKI_SHAMPINE 3(2)   3 a step        first same as last
   HRM_DORMAND_PRINCE   5(4)   5 a step        first same as last
   HRM_FEHLBERG         4(5)   5 a step        4th order propagated
   HRM_CASH_KARP        4(5)   5 a step        4th order propagated
   HRM_VERNER           6(5)   6 a step        DVERK's pair
   Orders hold on smooth integrands; a jump (a sharp shadow) drags every
   fixed-step method to first order (BREAKPOINTS).
   Forms of the IVP solvers (options.form): HRM_FORM_OPTICAL_DEPTH (the
   default), state (tau, A) with dA/dt = exp(-tau) S: nothing feeds back,
   L >= 0 and 0 <= Tr <= 1 at any step. HRM_FORM_RTE, dL/dt = S - sigma_t L
   (Munoz eq. 1) marched from t1 to t0: fixed steps blow up past h sigma_t
   = 2 (Euler), 2.79 (RK4), 0.3 (Adams-Bashforth), the papers' stiffness
   (warned); the pairs keep h sigma_t where R(-h sigma_t) is in [0, 1].

   ==========================================================================
   TOLERANCES (adaptive methods)
   ==========================================================================
   rtol (1e-3) and atol (0) bound the global error of L per channel:
   |L - L_exact| <~ rtol |L| + atol (tau's share: tau_tol, TRANSMITTANCE).
   Nested Simpson and global Gauss-Kronrod split the interval of largest
   estimate until the estimates add up to the tolerance of the current
   total (past their storage: the rest left to right); the pairs and local
   Gauss-Kronrod give a step atol f + rtol max(|dL|, f |L|), f its share.
   Each estimate is of the value returned (nested Simpson's |S2 - S1|, at least
   the 4th difference its 3rd and 2nd predict; Gauss-Kronrod's |K - G|; the
   pairs' embedded estimate, or stage values' Newton series if larger; at least
   1/2 (Gauss-Kronrod) or 1/4 (pairs) of the nodes' top Legendre coefficients
   that stop falling, a kink; scaled once splits show its rate and samples look
   resolved, but a kink's), raised where nodes miss the layer's 1 - Tr (a Tr
   callback's by 1/4), a pair's neighbours lie 20 times apart (both > 0, or >
   1 optical depth), others' 8 (nested Simpson's 6; no fit: half the gap). An
   interval whose error does not shrink may take rtol/16 of |L|, 16 times a
   call. Worst HRM_OK run, smooth scenes: 0.96 rtol. Missed tolerances: the best
   estimate and a warning: H_MIN (a step at h_min failed), MAX_EVALS
   (stats.evals <= max_evals, a user warp's calls 4 max_evals), STORAGE (a
   finish HRM_MAX_DEPTH deep), ROUNDOFF (bisection no longer helps, or t
   resolves no step, or a light's distance or a located jump's place to 2
   rtol), TOLERANCE (accepted estimates over atol + 3 rtol |L|, also at the
   scale found), RTOL_CLIPPED (rtol < 100 eps, raised); a piece's (between
   breakpoints) H_MIN or TOLERANCE only where all exceed atol + rtol |L|.
   result.error: their sum per channel (with a located jump's bracket), any
   status (-1: fixed steps). Every L (but the RTE form's fixed steps, Le per
   length) is in [0, the largest S/sigma_t sampled times 1 - Tr], cuts in
   result.error (fixed steps to 2x, Monte Carlo any; past: bound, TOLERANCE).
   Not seen: a feature between a step's samples (a light needs its warp, an
   occluder its breakpoints). Munoz's, Gonterman's controls unverified.

   ==========================================================================
   IMPORTANCE SAMPLING (options.warp; Munoz 2014 s.5)
   ==========================================================================
   A warp t = t(u) is a change of variable: every method integrates over u
   (fixed-step nodes uniform in u; h_min, h_max, h0 in u).
   HRM_WARP_DISTANCE     u = 1 - exp(-sigma_ref (t - t0)) (Munoz eq. 13);
                         sigma_ref 0: the thinnest channel's mean
                         extinction (lowered to what u resolves).
   HRM_WARP_EQUIANGULAR  u = atan((t - delta)/D), a point light D from the
                         ray at its foot delta (Munoz eq. 16; Kulla and
                         Fajardo 2012): hrm_equiangular_warp. D = 0 or u's
                         range < sqrt(eps): D = 1/8 of the light's distance
                         or none (BAD INPUT).
   HRM_WARP_USER         the host's t_of_u, dt_du (>= 0) and u_of_t.
   t1 = +INFINITY: valid where the warp maps it to a finite u (no callback
   sees infinity). The RTE form turns stiff under a warp (Munoz s.6).
   Lights: hrm_light_options turns the host's point, spot and directional
   lights and sphere occluders into a ray's warp and breakpoints (in an
   hrm_ray_plan the caller owns, one solve at a time): equiangular for the
   one light that reaches the ray; for several a mixture, density sum
   power / r(t)^2 over the HRM_MAX_LIGHTS of most power / D times the angle
   the ray subtends (a spot's peak in its lit part); breakpoints at spots'
   cone and falloff edges, spheres' shadows, light to light in < u / 48.

   ==========================================================================
   BREAKPOINTS (options.breaks, options.nbreaks; options.find_jumps)
   ==========================================================================
   Abscissae in [t0, t1], strictly increasing, at most HRM_MAX_BREAKS, where
   the integrand may jump (a shadow's edges, a medium's boundary): each piece
   is solved on its own (N, or the adaptive quadratures' first panels, shared
   by length in u: a step, 2 panels, 1 interval a piece at least; Simpson, RK4
   one more sample a breakpoint), sampled 64 ulps inside its ends (an edge 60
   ulps off still works), the layer's panels ending there. A budget below
   (nbreaks + 1) times a method's least cost (the first panels where nbreaks is
   0): HRM_ERR_BAD_OPTION. Found jumps (find_jumps 0, the default): nested
   Simpson and global Gauss-Kronrod bisect on the source an interval that keeps
   30% of its parent's estimate three splits in a row, where refining on would
   cost more than 64 evaluations; a jump of 1% or more is located to adjacent
   abscissae and made a breakpoint at the second, the solve run again (three
   halvings that split a smooth change end the search). Every adaptive method
   (fixed-step ones with find_jumps 1) first scans sigma_t (callbacks, no Tr
   callback) at the layer's first panels' degree-8 points (33, one panel a
   piece at least; medium.feature: gaps of at most it, 4097 points at most): a
   factor 2 between neighbours is bisected so too, a jump or edge made a
   breakpoint, a steep smooth change or a sample 1/8 off both neighbours (1/64
   if evenly at medium.feature) taught to the layer; the scan ends where its
   tau passes 2 ln(64 / rtol). Located: result.jumps (the next pixel's
   breakpoints). -1: neither. Finer detail needs medium.feature.

   ==========================================================================
   EXPONENTIAL FITTING (options.exponential)
   ==========================================================================
   In a thick medium Tr S falls by exp(-sigma_t h) over a step. With 1,
   Simpson, Gauss-Kronrod and the pairs (optical-depth form; tau from a closed
   form, the callback or the layer) factor the exponential of tau (its least
   slope between nodes) out of Tr S and integrate the rule's interpolant of the
   rest against it exactly (Legendre moments of exp(-b (y + 1))). With 2, where
   the source falls faster than Tr, the slope of -ln(Tr S) instead (a light
   seen through the medium). Without a warp: 1 is exact for a homogeneous
   medium and a source polynomial of the rule's degree, 2 for a source C
   exp(-mu t), at any step count and depth; L >= 0 always; sigma_t -> 0 gives
   the plain rule. Other methods, the RTE form, coupled tau, the stream:
   HRM_ERR_BAD_OPTION. For thick media and clouds (2: Li attenuated too).

   ==========================================================================
   TRANSMITTANCE (options.tau_mode, options.tau_tol)
   ==========================================================================
   tau is integrated in t, never in u: a constant sigma_t through callbacks
   gives the L and Tr of the homogeneous flag under every warp. A closed
   form (the homogeneous flag, the transmittance callback) is used where
   given; the RTE form carries Tr in its state. Otherwise options.tau_mode:
   HRM_TAU_DECOUPLED  (default: adaptive methods; fixed-step ones with a fit,
       or Simpson, RK4 and Adams-Bashforth under a warp) sigma_t on its own
       abscissae (Kulla, Fajardo 2012; Munoz 2014 s.6): panels in t, Chebyshev
       interpolants of degree 8, 16, each accepted when its error of tau times
       Tr at its start is at most tau_tol max(its increment of tau, 1/64); L's
       error from tau stays below tau_tol (1 + K/64) sup(S/sigma_t) (1 - Tr), K
       the panels thinner than 1/64: about L unless the source peaks where Tr
       is far lower (not the equiangular light). tau_tol 0: rtol/8 (adaptive),
       0.01 N^-order (fixed-step). What the scan or a missed node saw is kept.
   HRM_TAU_STREAM  (default: the rectangle rule, Monte Carlo and Euler under
       a warp) sigma_t at the nodes and at most 16 more points in t where the
       warp leaves them sparsest (2N + 8; Simpson, RK4 2N + 17), local cubics.
   HRM_TAU_COUPLED  (default: fixed-step methods without a warp, the
       analytic march) sigma_t from the source nodes at the rule's order,
       no extra medium evaluation (the papers' way); sigma_t at the first
       node is integrated exactly in t, so a constant medium is exact.

   ==========================================================================
   SHADOW RAYS (hrm_transmittance without a method)
   ==========================================================================
   With options NULL or options.method 0, hrm_transmittance integrates
   sigma_t by Simpson panels in t, the worst first, to
       |Tr - exact| <= tr_tol max(Tr, cutoff)      (tr_tol 0: 1e-3),
   a run of panels' error the larger of |sum e| and 2 sqrt(sum e^2), e a
   panel's S2 - S1 (at least its samples' predicted 4th difference), on
   segments between options.breaks, each from 4 panels (17 lookups), none
   wider than medium.feature where given. cutoff > 0: segments left to
   right, ending once every channel's Tr is below it (that Tr returned,
   stats.t_cut where). A named method or infinite ray: as hrm_solve.

   ==========================================================================
   NOT DONE BY hrm: tracing rays, sampling lights, phase functions (Li is
   the host's); direction-dependent media; multiple scattering beyond Li.
   The reasoning and measurements behind these sections: bench/README.md.

   LICENSE: MIT, see the end of this file.
*/
#ifndef HRM_H
#define HRM_H

#define HRM_VERSION_MAJOR 0
#define HRM_VERSION_MINOR 1
#define HRM_VERSION_PATCH 0

#include <stddef.h>
#include <stdint.h>

#ifndef HRM_REAL
#define HRM_REAL double
#endif
#ifndef HRM_CHANNELS
#define HRM_CHANNELS 3
#endif
#ifndef HRM_MAX_BREAKS
#define HRM_MAX_BREAKS 64 /* breakpoints per ray (options.breaks) */
#endif
#ifndef HRM_MAX_JUMPS
#define HRM_MAX_JUMPS 8   /* jumps located per ray (hrm_result.jumps) */
#endif
#ifndef HRM_MAX_LIGHTS
#define HRM_MAX_LIGHTS 8  /* lights in hrm_light_options's warp */
#endif
/* A configuration out of range fails to compile here (the array's size is
   negative): the stack a solve takes grows with these (CONFIGURATION). */
#define HRM__STATIC_ASSERT(name, cond) typedef char hrm__assert_##name[(cond) ? 1 : -1]
HRM__STATIC_ASSERT(channels_1_to_64, HRM_CHANNELS >= 1 && HRM_CHANNELS <= 64);
HRM__STATIC_ASSERT(max_breaks_1_to_1024, HRM_MAX_BREAKS >= 1 && HRM_MAX_BREAKS <= 1024);
HRM__STATIC_ASSERT(max_jumps_1_to_256, HRM_MAX_JUMPS >= 1 && HRM_MAX_JUMPS <= 256);
HRM__STATIC_ASSERT(max_lights_1_to_64, HRM_MAX_LIGHTS >= 1 && HRM_MAX_LIGHTS <= 64);
#ifdef HRM_STATIC
#define HRM_API static
#else
#define HRM_API extern
#endif
/* On every function: callable from CPU threads and from GPU kernels alike
   (pbrt-v4's PBRT_CPU_GPU). */
#ifndef HRM_DEVICE
#if defined(__CUDACC__) || defined(__HIPCC__)
#define HRM_DEVICE __host__ __device__
#else
#define HRM_DEVICE
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef HRM_REAL hrm_real;

/* Status codes: one list, so the enum and the messages never drift apart. */
#define HRM__STATUS_LIST(X)                                                   \
    X(HRM_OK, 0, "ok")                                                        \
    X(HRM_WARN_MAX_EVALS, 1, "evaluation budget exhausted before the tolerance was met; best estimate returned") \
    X(HRM_WARN_H_MIN, 2, "minimum step reached before the tolerance was met; best estimate returned") \
    X(HRM_WARN_STORAGE, 3, "interval storage exhausted before the tolerance was met; best estimate returned") \
    X(HRM_WARN_RTOL_CLIPPED, 4, "rtol below 100 machine epsilons was raised to that floor") \
    X(HRM_WARN_ROUNDOFF, 5, "round-off prevents the requested tolerance; best estimate returned") \
    X(HRM_WARN_TOLERANCE, 6, "the accepted error estimates add up to more than the tolerance allows, even when solved again at the scale found; best estimate returned with its estimated error") \
    X(HRM_ERR_NULL_ARGUMENT, -1, "a required pointer argument is NULL")      \
    X(HRM_ERR_BAD_INTERVAL, -2, "t0 not finite, t1 NaN or below t0, or t1 infinite without a warp that maps it to a finite end")       \
    X(HRM_ERR_BAD_STEPS, -3, "options.steps is negative")                    \
    X(HRM_ERR_BAD_METHOD, -4, "unknown method")                              \
    X(HRM_ERR_BAD_OPTION, -5, "an option is out of range (form, tolerances, step bounds, budget)") \
    X(HRM_ERR_BAD_MEDIUM, -6, "a constant coefficient or the feature of the medium is negative or not finite, an unknown flag, or sigma given with sigma_a, sigma_s or sigma_t") \
    X(HRM_ERR_CALLBACK_VALUE, -7, "a callback returned NaN, an infinity, a negative coefficient or source, or a transmittance outside [0,1] or rising along the ray") \
    X(HRM_ERR_BAD_WARP, -8, "warp parameters invalid: sigma_ref or D negative or not finite, a user warp without its callbacks or not increasing") \
    X(HRM_ERR_SINGULAR, -9, "the equiangular light lies on the ray within [t0, t1] (D = 0): the integral diverges") \
    X(HRM_ERR_BAD_BREAKS, -10, "breakpoints: nbreaks negative or above HRM_MAX_BREAKS, NULL with nbreaks > 0, or an entry not finite, not increasing or outside [t0, t1]") \
    X(HRM_ERR_RANGE, -11, "beyond HRM_REAL's range: a sample's sigma_t or source times the ray's length, t1 - t0 itself, or the RTE form's solution (explicit steps past their stability limit)")

typedef enum hrm_status {
#define HRM__STATUS_ENUM(name, value, text) name = value,
    HRM__STATUS_LIST(HRM__STATUS_ENUM)
#undef HRM__STATUS_ENUM
} hrm_status;

/* Methods. HRM_METHOD_DEFAULT (0) lets hrm choose (HRM_NESTED_SIMPSON).
   One list: the enum, the names and the implementation's method table
   (family, default steps, order on smooth integrands, whether the RTE form
   applies, tableau, whether an exponential fit applies, the tau stream: 0
   not, 1 on request, 2 the default under a warp; the driver that runs it)
   come from it, so they cannot drift apart. */
#define HRM__METHOD_LIST(X)                                                   \
    X(HRM_RECTANGLE, "rectangle", HRM__FIXED_QUAD, 32, 2, 0, 0, 0, 2, HRM__DRV_RECT) \
    X(HRM_SIMPSON, "simpson", HRM__FIXED_QUAD, 32, 4, 0, 0, 1, 1, HRM__DRV_SIMPSON) \
    X(HRM_MONTE_CARLO, "monte-carlo", HRM__FIXED_QUAD, 32, 0.5, 0, 0, 0, 2, HRM__DRV_MC) \
    X(HRM_EULER, "euler", HRM__FIXED_IVP, 32, 1, 1, &hrm__euler, 0, 2, HRM__DRV_IVP) \
    X(HRM_RK4, "rk4", HRM__FIXED_IVP, 32, 4, 1, &hrm__rk4, 0, 1, HRM__DRV_IVP) \
    X(HRM_ADAMS_BASHFORTH, "adams-bashforth", HRM__FIXED_IVP, 32, 4, 1, &hrm__rk4, 0, 1, HRM__DRV_AB4) \
    X(HRM_NESTED_SIMPSON, "nested-simpson", HRM__ADAPTIVE_QUAD, 4, 6, 0, 0, 0, 0, HRM__DRV_NS) \
    X(HRM_GAUSS_KRONROD, "gauss-kronrod", HRM__ADAPTIVE_QUAD, 1, 22, 0, 0, 1, 0, HRM__DRV_GK) \
    X(HRM_BOGACKI_SHAMPINE, "bogacki-shampine", HRM__PAIR, 0, 3, 1, &hrm__bs, 1, 0, HRM__DRV_PAIR) \
    X(HRM_DORMAND_PRINCE, "dormand-prince", HRM__PAIR, 0, 5, 1, &hrm__dp, 1, 0, HRM__DRV_PAIR) \
    X(HRM_FEHLBERG, "fehlberg", HRM__PAIR, 0, 4, 1, &hrm__rkf, 1, 0, HRM__DRV_PAIR) \
    X(HRM_CASH_KARP, "cash-karp", HRM__PAIR, 0, 4, 1, &hrm__ck, 1, 0, HRM__DRV_PAIR) \
    X(HRM_VERNER, "verner", HRM__PAIR, 0, 6, 1, &hrm__vr, 1, 0, HRM__DRV_PAIR) \
    X(HRM_ANALYTIC_MARCH, "analytic-march", HRM__FIXED_QUAD, 32, 2, 0, 0, 0, 0, HRM__DRV_MARCH)

typedef enum hrm_method {
    HRM_METHOD_DEFAULT = 0,
#define HRM__METHOD_ENUM(name, text, family, steps, order, rte, tableau, fit, stream, driver) name,
    HRM__METHOD_LIST(HRM__METHOD_ENUM)
#undef HRM__METHOD_ENUM
    HRM_METHOD_COUNT /* one past the last method */
} hrm_method;

typedef enum hrm_form {
    HRM_FORM_DEFAULT = 0,      /* HRM_FORM_OPTICAL_DEPTH */
    HRM_FORM_OPTICAL_DEPTH,    /* (tau, A): stable at any step */
    HRM_FORM_RTE               /* dL/dt = S - sigma_t L: stiff, for study */
} hrm_form;

/* Step-size control of the embedded Runge-Kutta methods. */
typedef enum hrm_control {
    HRM_CONTROL_DEFAULT = 0, /* HRM_CONTROL_PI */
    HRM_CONTROL_PI,          /* mixed tolerance, PI controller (Gustafsson) */
    HRM_CONTROL_MUNOZ,       /* Munoz 2014 eq. 12 */
    HRM_CONTROL_GONTERMAN    /* Gonterman 2010 eq. 3.4, error per unit step */
} hrm_control;

/* Gauss-Kronrod subdivision. */
typedef enum hrm_gk_mode {
    HRM_GK_DEFAULT = 0,      /* HRM_GK_GLOBAL */
    HRM_GK_GLOBAL,           /* bisect the worst interval (QUADPACK QAG) */
    HRM_GK_LOCAL             /* Munoz 2014: recursive local split */
} hrm_gk_mode;

/* Gauss-Kronrod pair. */
typedef enum hrm_gk_rule {
    HRM_GK_RULE_DEFAULT = 0, /* HRM_GK_K15 */
    HRM_GK_K15,              /* G7/K15: 15 samples per interval, degree 22 */
    HRM_GK_K7                /* G3/K7: 7 samples per interval, degree 11 */
} hrm_gk_rule;

/* How tau (hence Tr) is integrated where the medium has no closed form.
   Both integrate sigma_t in t over the actual distances between abscissae,
   so a constant sigma_t given through callbacks is exact under any warp. */
typedef enum hrm_tau_mode {
    HRM_TAU_DEFAULT = 0,     /* adaptive methods, and fixed-step ones
                                with a fit: HRM_TAU_DECOUPLED; under a
                                warp, the rectangle rule, Monte Carlo and
                                Euler HRM_TAU_STREAM, the other fixed-step
                                ones HRM_TAU_DECOUPLED; fixed-step ones
                                without a warp, and the analytic march:
                                HRM_TAU_COUPLED (TRANSMITTANCE) */
    HRM_TAU_DECOUPLED,       /* medium-only samples placed in t by their own
                                accuracy control (options.tau_tol), apart
                                from the source samples (Kulla and Fajardo
                                2012; Munoz 2014 s.6) */
    HRM_TAU_COUPLED,         /* from the sigma_t samples at the source
                                abscissae, at the rule's order: no extra
                                medium evaluation, as the papers do */
    HRM_TAU_STREAM           /* fixed-step methods (not the analytic
                                march): sigma_t at their nodes and at most
                                16 extra samples in t where the nodes are
                                sparsest, integrated in t (at most 2N + 8
                                samples; 2N + 17 for Simpson and RK4) */
} hrm_tau_mode;

/* Importance sampling as a change of variable t = t(u) (Munoz 2014 s.5):
   every method integrates over u, so fixed-step methods and Monte Carlo
   place their samples uniformly in u and adaptive methods start from it. */
typedef enum hrm_warp_kind {
    HRM_WARP_NONE = 0,
    HRM_WARP_DISTANCE,     /* u = 1 - exp(-sigma_ref (t - t0)) (eq. 13) */
    HRM_WARP_EQUIANGULAR,  /* u = atan((t - delta) / D) (eq. 16) */
    HRM_WARP_USER          /* t_of_u, dt_du, u_of_t below */
} hrm_warp_kind;

typedef struct hrm_warp {
    hrm_warp_kind kind;
    hrm_real sigma_ref; /* distance: 0 means the thinnest channel's mean
                           extinction over the ray, up to where its Tr has
                           fallen below eps/2 (see IMPORTANCE SAMPLING); a
                           larger value is lowered to what the ray allows.
                           Below the smallest normal number: no warp. */
    hrm_real delta, D;  /* equiangular: the point light projects onto the
                           ray at t = delta and lies D >= 0 from it (units
                           of t; see hrm_equiangular_warp) */
    void *user;         /* user warp: an increasing map u -> t and back */
    hrm_real (*t_of_u)(void *user, hrm_real u);
    hrm_real (*dt_du)(void *user, hrm_real u);
    hrm_real (*u_of_t)(void *user, hrm_real t); /* may be called with t1 = +inf */
} hrm_warp;

/* Medium flags. */
#define HRM_MEDIUM_HOMOGENEOUS   1u /* use const_sigma_a/_s, closed-form Tr */
#define HRM_EMISSION_PER_LENGTH  2u /* source is Le itself, not sigma_a*Le */

typedef void (*hrm_spectrum_fn)(void *user, hrm_real t, hrm_real out[HRM_CHANNELS]);
typedef void (*hrm_sigma_fn)(void *user, hrm_real t, hrm_real sigma_a[HRM_CHANNELS],
                             hrm_real sigma_s[HRM_CHANNELS]);
typedef void (*hrm_transmittance_fn)(void *user, hrm_real ta, hrm_real tb,
                                     hrm_real out[HRM_CHANNELS]);

typedef struct hrm_medium {
    void *user;                        /* passed to every callback */
    hrm_spectrum_fn sigma_a, sigma_s;  /* NULL: zero */
    hrm_spectrum_fn sigma_t;           /* NULL: sigma_a + sigma_s */
    hrm_sigma_fn sigma;                /* sigma_a and sigma_s from one call
                                          (one density lookup), instead of
                                          the three above; NULL: those */
    hrm_spectrum_fn Le, Li;            /* NULL: absent, never called */
    hrm_transmittance_fn transmittance;/* NULL: integrate sigma_t. Given,
                                          no medium scan runs, and a
                                          slab or bump between the nodes
                                          is seen only where it holds a
                                          quarter of an interval's
                                          absorption and sigma comes as
                                          one call (give sigma alone, or
                                          the breakpoints) */
    unsigned flags;                    /* HRM_MEDIUM_*, HRM_EMISSION_* */
    hrm_real const_sigma_a[HRM_CHANNELS]; /* with HRM_MEDIUM_HOMOGENEOUS */
    hrm_real const_sigma_s[HRM_CHANNELS];
    hrm_real feature;                  /* sigma through callbacks: the width
                                          along t of its thinnest feature (a
                                          voxel, a noise's finest wisp); the
                                          medium scan samples sigma at this
                                          spacing, 9 a piece at least
                                          (BREAKPOINTS), and the
                                          transmittance layer's panels
                                          sample it as closely. 0: unknown,
                                          33 samples a ray */
} hrm_medium;

typedef struct hrm_options {
    hrm_method method;  /* 0: HRM_METHOD_DEFAULT */
    int steps;          /* fixed-step methods: segments, panels, steps or
                           Monte Carlo samples. 0: 32. Typical values to start
                           with: 8-32 for Simpson/RK4 on smooth media,
                           64-256 for the rectangle rule. Nested Simpson and
                           Gauss-Kronrod: initial panels/intervals over the
                           ray (0: 4 and 1), shared by length between
                           breakpoints, at least 2 and 1 a piece; ignored
                           by the Runge-Kutta pairs. Negative: error. */
    hrm_form form;      /* IVP solvers (Euler, RK4, Adams-Bashforth and the
                           Runge-Kutta pairs). 0: optical-depth form */
    uint64_t seed;      /* Monte Carlo and jitter; vary it per ray/pixel. */
    int jitter;         /* rectangle rule: nonzero offsets the ray's samples
                           by one random fraction of a segment per ray
                           (Gonterman's anti-banding jitter). 0: midpoints */
    int stratified;     /* Monte Carlo: nonzero takes one sample per segment */

    /* Adaptive methods (see TOLERANCES in the manual). */
    hrm_real rtol;      /* relative tolerance on L and tau. 0: 1e-3. Typical:
                           1e-2 (previews) to 1e-6; clipped at 100 epsilons */
    hrm_real atol;      /* absolute tolerance on L. 0: none */
    hrm_real h_min;     /* smallest step or interval, in the integration
                           variable (t, or u under a warp). 0: 64 epsilons
                           of the range (1/1024 of it with HRM_CONTROL_MUNOZ) */
    hrm_real h_max;     /* largest step or interval. 0: the whole range */
    hrm_real h0;        /* first step of the Runge-Kutta methods. 0: chosen
                           from rtol and the method's order */
    long max_evals;     /* source evaluation budget. 0: 100000. Also
                           bounds an adaptive method's attempts (steps
                           or intervals, accepted or rejected), which
                           cost no evaluation where their nodes fall on
                           remembered abscissae, and a user warp's calls
                           (a quarter each). Fixed-step methods
                           spend what N says and ignore it. */
    hrm_control control;/* Runge-Kutta step control. 0: HRM_CONTROL_PI */
    hrm_gk_mode gk_mode;/* Gauss-Kronrod. 0: HRM_GK_GLOBAL */
    hrm_gk_rule gk_rule;/* Gauss-Kronrod. 0: HRM_GK_K15 */
    hrm_warp warp;      /* importance sampling. 0: none */
    hrm_tau_mode tau_mode; /* 0: decoupled (adaptive methods, fixed-step
                              ones with a fit, or of order 4 under a
                              warp), the stream (the rectangle rule,
                              Monte Carlo, Euler under a warp), else
                              coupled */
    hrm_real tau_tol;   /* decoupled tau: the error of each optical-depth
                           increment relative to itself (or to 1/64, the
                           larger), weighted by Tr where it occurs, so that
                           L's relative error from tau stays below about
                           it (TRANSMITTANCE). 0: rtol/8 for the adaptive
                           methods, 0.01 N^-order for the fixed-step ones
                           (their own error's rate); at least 64 epsilons */
    const hrm_real *breaks; /* abscissae in [t0, t1], strictly increasing,
                           where the integrand may jump: a shadow's edges,
                           a medium's boundary. No step, interval or tau
                           panel straddles one; each side is sampled on
                           its own side. NULL / 0: none. At most
                           HRM_MAX_BREAKS (64); entries equal to t0 or t1
                           change nothing */
    int nbreaks;
    int find_jumps;     /* 0 (the default): every adaptive method scans
                           sigma (callbacks; not where a transmittance
                           callback gives Tr) for jumps before it runs, and
                           nested Simpson and global Gauss-Kronrod also
                           locate a jump of the source that refinement
                           does not shrink (a shadow's edge); each jump is
                           located by bisection to the resolution of t
                           and made a breakpoint (BREAKPOINTS). 1: as 0,
                           and fixed-step methods scan sigma too. -1:
                           never */
    int exponential;    /* 1: exponentially fitted rules (EXPONENTIAL
                           FITTING): Simpson, Gauss-Kronrod and the
                           Runge-Kutta pairs (optical-depth form) integrate
                           their source polynomial against the exact local
                           exponential of tau. 2: of Tr S where the source
                           falls too (a light seen through the medium).
                           0: the plain rules */

    /* hrm_transmittance without a method (options NULL, or method 0): the
       shadow-ray estimator (SHADOW RAYS in the manual). */
    hrm_real tr_tol;    /* the error of Tr relative to max(Tr, cutoff).
                           0: 1e-3. Typical: 1e-2 (previews) to 1e-4 */
    hrm_real cutoff;    /* opacity cut-off: hrm_transmittance's estimator
                           stops once Tr (every channel) falls below it, and
                           returns the Tr reached there; hrm_solve solves
                           up to there (see hrm_solve), the remainder
                           estimated in result.error. stats.t_cut says
                           where. 0: none. Typical: 1e-3 to 1e-4. Within
                           [0, 1] */

    /* The solve's deep storage (the transmittance layer, the adaptive
       methods' intervals, samples and finish) in memory the caller owns
       instead of on the stack (THREAD SAFETY AND MEMORY): at least
       hrm_workspace_size(options) bytes, aligned to 16. NULL / 0: the
       stack. hrm only uses it during the call; a shadow ray solved inside
       Li may use what lies past that size. */
    void *workspace;
    size_t workspace_size;
} hrm_options;

typedef struct hrm_stats {
    long evals;         /* source (Le/Li) evaluations: one per abscissa */
    long medium_evals;  /* medium (sigma or transmittance) evaluations */
    long steps;         /* steps, panels, segments or samples taken */
    long rejected;      /* rejected adaptive steps (0 for fixed methods) */
    hrm_real t_cut;     /* where the integration ended: t1, or where Tr
                           fell below options.cutoff (hrm_transmittance's
                           estimator: Tr(t0, t_cut) returned, at least the
                           exact Tr(t0, t1)). 0 for an error before it began */
} hrm_stats;

typedef struct hrm_result {
    hrm_real L[HRM_CHANNELS];   /* radiance added by the medium */
    hrm_real Tr[HRM_CHANNELS];  /* eye-ray transmittance Tr(t0, t1) */
    hrm_stats stats;
    hrm_real error[HRM_CHANNELS]; /* the adaptive methods' estimate of |L -
                                     exact|: the error estimates of what
                                     they accepted, whatever the status (a
                                     warning's estimated miss); -1: none
                                     (fixed-step methods, errors) */
    int njumps;                 /* jumps located along the ray (the
                                   medium scan, and the source's search
                                   in nested Simpson and global
                                   Gauss-Kronrod: options.find_jumps) */
    hrm_real jumps[HRM_MAX_JUMPS]; /* their abscissae, ascending: the
                                   breakpoints to give the next ray */
} hrm_result;

/* The defaults of `method`: what an all-zero hrm_options means, with the
   method set (HRM_METHOD_DEFAULT kept: nested Simpson's defaults for
   hrm_solve, the shadow-ray estimator for hrm_transmittance). */
HRM_API HRM_DEVICE hrm_options hrm_default_options(hrm_method method);

/* The bytes options.workspace must hold for a solve with these options
   (options NULL: the defaults'; 0 for options hrm_solve would reject): the
   transmittance layer, the solve's context, its pieces' ends between
   breakpoints, and the adaptive methods' memo, fits, intervals, samples
   and finish. A multiple of 16. */
HRM_API HRM_DEVICE size_t hrm_workspace_size(const hrm_options *options);

/* Solve along one ray from t0 to t1 (t0 <= t1, both finite).
   medium, result: required.  options: NULL means all defaults.
   options->cutoff > 0: early ray termination (stats.t_cut); L covers
   [t0, t_cut], and an adaptive method's result.error adds the
   remainder's estimate: the largest S / sigma_t sampled (at least the
   mean of the part solved; the equiangular warp's light foot, where
   behind t_cut, sampled once for it; another source peaking behind
   t_cut is not seen) times Tr(t0, t_cut) - Tr(t0, t1) where known, else
   Tr(t0, t_cut), which bounds it. The remainder is asked for: it does
   not make a warning. With a closed-form Tr (homogeneous, or the
   transmittance callback): t_cut where every channel's Tr falls below
   the cut-off, Tr the whole ray's. With sigma callbacks, where the
   medium scan runs and tau comes from the transmittance layer (the
   adaptive methods' default; the distance warp keeps the whole ray's
   sigma_ref): t_cut the scan's first sample where its trapezoid tau
   passes ln(1 / cutoff) in every channel (a medium that varies faster
   than the scan's spacing can leave Tr there above the cut-off), Tr =
   Tr(t0, t_cut) (the whole ray's is at most it); elsewhere no cut.
   Returns HRM_OK, a warning (result holds the best estimate) or an error
   (result holds L = 0, Tr = 1, and the stats counted so far). */
HRM_API HRM_DEVICE hrm_status hrm_solve(const hrm_medium *medium, hrm_real t0, hrm_real t1,
                             const hrm_options *options, hrm_result *result);

/* Eye-ray (or shadow-ray) transmittance Tr(t0, t1) alone: no source is
   evaluated. Closed form when the medium has one (no sigma evaluation for a
   homogeneous medium). Else, options NULL or options->method 0: the
   shadow-ray estimator, to options->tr_tol with options->cutoff (SHADOW
   RAYS); a method named: sigma_t integrated in t by the transmittance
   layer to options->tau_tol (HRM_TAU_COUPLED: by options' method over its
   nodes). options->warp is used only to end an infinite ray.
   Tr: required. stats: optional. On error Tr is 1 in every channel and
   stats, where given, holds what was counted (zero for a NULL Tr). */
HRM_API HRM_DEVICE hrm_status hrm_transmittance(const hrm_medium *medium, hrm_real t0,
                                     hrm_real t1, const hrm_options *options,
                                     hrm_real Tr[HRM_CHANNELS], hrm_stats *stats);

/* Equiangular warp for a point light seen from the ray origin + t * dir
   (dir need not be unit length; t, delta and D are in units of t): delta
   from a dot product, D from a cross product, so a light near the ray
   keeps its full precision. warp: required; overwritten whole.
   Returns HRM_ERR_NULL_ARGUMENT, HRM_ERR_BAD_WARP (dir zero or a value not
   finite; *warp is then zeroed, HRM_WARP_NONE, wherever warp is given) or
   HRM_OK. */
HRM_API HRM_DEVICE hrm_status hrm_equiangular_warp(const hrm_real origin[3], const hrm_real dir[3],
                                        const hrm_real light[3], hrm_warp *warp);

/* Breakpoints of one spherical occluder (center, radius) in front of a
   point light, along the ray origin + t * dir, t in (t0, t1): the
   abscissae where the shadow ray from the ray to the light grazes the
   sphere (the ray meets the cone from the light tangent to the sphere,
   beyond the circle where the cone touches it), ascending, into out[0..1];
   *count receives how many (0, 1 or 2). Where the ray passes through the
   sphere, its entry and exit are the host's (the camera ray usually ends
   there). Precision: the two roots of a quadratic taken in their stable
   form, within a few ulps of max(|t|, |t0|) except where the ray grazes
   the cone itself (a double root), where they are good to about the
   square root of epsilon relative - there the shadow's extent along the
   ray is itself that small. Returns HRM_ERR_NULL_ARGUMENT, HRM_ERR_BAD_WARP
   (dir zero, radius negative, a value not finite, or t1 < t0; *count 0
   wherever count is given)
   or HRM_OK; a light inside the sphere, which shadows the whole ray, gives
   no breakpoint. */
HRM_API HRM_DEVICE hrm_status hrm_sphere_breaks(const hrm_real origin[3], const hrm_real dir[3],
                                     const hrm_real light[3], const hrm_real center[3],
                                     hrm_real radius, hrm_real t0, hrm_real t1,
                                     hrm_real out[2], int *count);

/* Lights and sphere occluders that hrm_light_options turns into a warp and
   breakpoints for one ray (IMPORTANCE SAMPLING in the manual). */
typedef enum hrm_light_kind {
    HRM_LIGHT_POINT = 1,
    HRM_LIGHT_SPOT,
    HRM_LIGHT_DIRECTIONAL
} hrm_light_kind;

typedef struct hrm_light {
    hrm_light_kind kind;
    hrm_real position[3];  /* point and spot */
    hrm_real direction[3]; /* spot: its axis, the way it shines;
                              directional: the way its light travels */
    hrm_real power;        /* > 0: weighs the lights in the warp */
    hrm_real cone;         /* spot: the lit cone's half-angle, (0, pi] */
    hrm_real falloff;      /* spot: where its falloff starts, [0, cone];
                              0 for none (the cone's edge alone) */
} hrm_light;

typedef struct hrm_sphere {
    hrm_real center[3];
    hrm_real radius; /* >= 0 */
} hrm_sphere;

/* What hrm_light_options fills for one ray; the options it sets point
   into it, so it must outlive the solve. The mixture keeps the
   HRM_MAX_LIGHTS lights of most weight. */
typedef struct hrm_ray_plan {
    hrm_real breaks[HRM_MAX_BREAKS]; /* ascending, inside (t0, t1) */
    int nbreaks;
    int nmix;                        /* lights in the warp's mixture */
    double delta[HRM_MAX_LIGHTS], D[HRM_MAX_LIGHTS], c[HRM_MAX_LIGHTS];
    double a0[HRM_MAX_LIGHTS];       /* atan((t0 - delta) / D) */
    double t0, t1, u1;               /* the ray's ends (t1 may be inf), u at t1 */
    double res;                      /* t's resolution where the ray passes
                                        nearest a light, over its distance
                                        there, weighed by its share of u */
    double last_u, last_t;           /* the warp's last inversion: a plan
                                        serves one solve at a time */
} hrm_ray_plan;

/* Sets options->warp and options->breaks / nbreaks (into plan) for the ray
   origin + t dir, t in [t0, t1] (t1 may be +inf), from lights[0..nlights)
   and spheres[0..nspheres); the options' other fields are kept, and so are
   breakpoints options already holds in (t0, t1) (merged). The warp: none
   where no point or spot light reaches the ray; equiangular for one; for
   several, a user warp whose density is the sum of their unshadowed
   irradiance along the ray, power / r(t)^2 (each light weighted by power
   over its distance to the ray times the angle the ray subtends), which
   flattens each light's peak; a spot whose cone leaves dark the ray's
   point nearest it counts from the lit point nearest that one instead (its
   density there, power / r^2 with r its distance from there). The
   breakpoints: the foot on the ray of a
   light left out of the mixture (beyond HRM_MAX_LIGHTS), a spot's cone
   and falloff edges, each sphere's shadow from each light (a cone from a
   point or spot light, a cylinder behind it for a directional one), and
   where two of the mixture's lights light the ray alike and most, the
   edges of the band where one's irradiance goes from 4 to 1/4 of the
   other's if it holds less than 1/48 of u (there the warp squeezes the
   change between them); the first HRM_MAX_BREAKS in order along the ray.
   Returns
   HRM_ERR_NULL_ARGUMENT (a NULL pointer, or NULL lights or spheres with a
   count > 0), HRM_ERR_BAD_WARP (dir zero, a value not finite, t1 < t0, a
   count negative, an unknown kind, power not above 0, radius negative,
   cone outside (0, pi], falloff outside [0, cone], a direction of zero
   length), HRM_ERR_SINGULAR (a point or spot
   light on the ray within [t0, t1]) with *plan zeroed and *options as it
   was; else HRM_OK. */
HRM_API HRM_DEVICE hrm_status hrm_light_options(const hrm_light *lights, int nlights, const hrm_sphere *spheres,
                                     int nspheres, const hrm_real origin[3], const hrm_real dir[3],
                                     hrm_real t0, hrm_real t1, hrm_ray_plan *plan, hrm_options *options);

HRM_API HRM_DEVICE const char *hrm_method_name(hrm_method method); /* "?" if unknown */
HRM_API HRM_DEVICE const char *hrm_status_string(hrm_status status); /* "unknown status" */
/* HRM_VERSION_MAJOR*10000 + MINOR*100 + PATCH of the compiled library. */
HRM_API HRM_DEVICE int hrm_version(void);

#ifdef __cplusplus
}
#endif
#endif /* HRM_H */

/* ======================================================================== */
/*                             IMPLEMENTATION                               */
/* ======================================================================== */
#ifdef HRM_IMPLEMENTATION
#ifndef HRM__IMPLEMENTATION_DONE
#define HRM__IMPLEMENTATION_DONE

#include <math.h>
#include <float.h>
#include <string.h>

#ifndef HRM_ASSERT
#include <assert.h>
#define HRM_ASSERT(x) assert(x)
#endif

#if defined(HRM_STATIC) && (defined(__GNUC__) || defined(__clang__))
#define HRM__DEF __attribute__((unused)) static
#elif defined(HRM_STATIC)
#define HRM__DEF static
#else
#define HRM__DEF
#endif

/* A function that holds a large frame (storage a solve needs only in some
   configurations) is never inlined into its caller, whose frame would
   otherwise reserve it whatever the configuration. */
#if defined(__GNUC__) || defined(__clang__)
#define HRM__NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define HRM__NOINLINE __declspec(noinline)
#else
#define HRM__NOINLINE
#endif

/* On a GPU the large functions stay calls: inlined whole into a kernel,
   they take ptxas minutes per kernel and registers from every thread.
   The small ones on an evaluation's path (the sigma callbacks' wrapper,
   the warp's map, the memo, the medium step, the Chebyshev sum) are left
   to the compiler: each call saves and restores its registers in local
   memory, and a kernel spends most of its time waiting on local memory
   (H100, nested Simpson: 77% of its stall cycles; these five inlined,
   6-9% more rays a second, examples/gpu.cu). */
#if defined(__CUDACC__) || defined(__HIPCC__)
#define HRM__CALL __noinline__
#else
#define HRM__CALL
#endif

/* The coefficient tables live in device memory in the device pass of
   nvcc or hipcc and in the host's in its host pass, so that a function on
   both sides reads its own copy. */
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
#define HRM__TABLE __device__
#else
#define HRM__TABLE
#endif

/* Internal limits (fixed storage: no allocation in a solve). */
#ifndef HRM_MAX_DEPTH
#define HRM_MAX_DEPTH 60     /* nested Simpson and local Gauss-Kronrod depth */
#endif
#ifndef HRM_NS_PANELS
#define HRM_NS_PANELS 32     /* nested Simpson's initial panels at most */
#endif
#ifndef HRM_GK_INITIAL
#define HRM_GK_INITIAL 32    /* Gauss-Kronrod's initial intervals at most */
#endif
#ifndef HRM_GK_INTERVALS
#define HRM_GK_INTERVALS 128 /* global Gauss-Kronrod's interval storage */
#endif
#ifndef HRM_NS_INTERVALS
#define HRM_NS_INTERVALS 64  /* nested Simpson's worst-first interval storage */
#endif
#ifndef HRM_SHADOW_PANELS
#define HRM_SHADOW_PANELS 48 /* the shadow-ray estimator's panels a segment */
#endif
HRM__STATIC_ASSERT(max_depth_8_to_200, HRM_MAX_DEPTH >= 8 && HRM_MAX_DEPTH <= 200);
HRM__STATIC_ASSERT(ns_intervals_8_to_4096, HRM_NS_INTERVALS >= 8 && HRM_NS_INTERVALS <= 4096);
HRM__STATIC_ASSERT(ns_panels_1_to_ns_intervals, HRM_NS_PANELS >= 1 && HRM_NS_PANELS <= HRM_NS_INTERVALS);
HRM__STATIC_ASSERT(gk_intervals_8_to_4096, HRM_GK_INTERVALS >= 8 && HRM_GK_INTERVALS <= 4096);
HRM__STATIC_ASSERT(gk_initial_1_to_gk_intervals, HRM_GK_INITIAL >= 1 && HRM_GK_INITIAL <= HRM_GK_INTERVALS);
HRM__STATIC_ASSERT(shadow_panels_16_to_4096, HRM_SHADOW_PANELS >= 16 && HRM_SHADOW_PANELS <= 4096);
/* the panels a next segment of the estimator aims to start with
   (hrm__shadow_run) */
#define HRM__SHADOW_AIM (HRM_SHADOW_PANELS / 4 > 8 ? HRM_SHADOW_PANELS / 4 : 8)

#define HRM__MEMO 32 /* abscissae the adaptive methods remember, and the
                        ray's end in a slot of its own (the last index) */
#define HRM__MEMO_BINS 128 /* the memo's abscissae counted by a hash */

/* Method families (the method table's second column). */
#define HRM__FIXED_QUAD 0
#define HRM__FIXED_IVP 1
#define HRM__ADAPTIVE_QUAD 2
#define HRM__PAIR 3

/* Drivers (the method table's last column): the code that runs a method. */
#define HRM__DRV_RECT 0    /* midpoints (or one jittered offset) */
#define HRM__DRV_SIMPSON 1
#define HRM__DRV_MC 2      /* Monte Carlo */
#define HRM__DRV_MARCH 3   /* the analytic march */
#define HRM__DRV_IVP 4     /* fixed-step Runge-Kutta: Euler, RK4 */
#define HRM__DRV_AB4 5     /* Adams-Bashforth, started by RK4 */
#define HRM__DRV_NS 6      /* nested Simpson, worst first */
#define HRM__DRV_GK 7      /* Gauss-Kronrod, worst first or local */
#define HRM__DRV_PAIR 8    /* embedded Runge-Kutta pairs */

#define HRM__R(x) ((hrm_real)(x))
#define HRM__IS_FLOAT (sizeof(hrm_real) == sizeof(float))
#define HRM__TINY (HRM__IS_FLOAT ? HRM__R(FLT_MIN) : HRM__R(DBL_MIN)) /* smallest normal */
#define HRM__EPS (HRM__IS_FLOAT ? HRM__R(FLT_EPSILON) : HRM__R(DBL_EPSILON))
#define HRM__SQRT_EPS (HRM__IS_FLOAT ? HRM__R(3.4526698e-4) : HRM__R(1.4901161193847656e-8))
#define HRM__CH HRM_CHANNELS

/* The libm function matching the scalar type; the branch is a constant. */
#define HRM__MATH1(fn, x) (HRM__IS_FLOAT ? (hrm_real)fn##f((float)(x)) : (hrm_real)fn((double)(x)))
#ifndef HRM_SQRT
#define HRM_SQRT(x) HRM__MATH1(sqrt, x)
#endif
#ifndef HRM_EXP
#define HRM_EXP(x) HRM__MATH1(exp, x)
#endif
#ifndef HRM_EXPM1
#define HRM_EXPM1(x) HRM__MATH1(expm1, x)
#endif
#ifndef HRM_LOG
#define HRM_LOG(x) HRM__MATH1(log, x)
#endif
#ifndef HRM_LOG1P
#define HRM_LOG1P(x) HRM__MATH1(log1p, x)
#endif
#ifndef HRM_FABS
#define HRM_FABS(x) HRM__MATH1(fabs, x)
#endif
#ifndef HRM_SIN
#define HRM_SIN(x) HRM__MATH1(sin, x)
#endif
#ifndef HRM_COS
#define HRM_COS(x) HRM__MATH1(cos, x)
#endif
#ifndef HRM_ATAN2
#define HRM_ATAN2(y, x) (HRM__IS_FLOAT ? (hrm_real)atan2f((float)(y), (float)(x)) \
                                       : (hrm_real)atan2((double)(y), (double)(x)))
#endif
#ifndef HRM_HYPOT
#define HRM_HYPOT(x, y) (HRM__IS_FLOAT ? (hrm_real)hypotf((float)(x), (float)(y)) \
                                       : (hrm_real)hypot((double)(x), (double)(y)))
#endif
#ifndef HRM_POW
#define HRM_POW(x, y) (HRM__IS_FLOAT ? (hrm_real)powf((float)(x), (float)(y)) \
                                     : (hrm_real)pow((double)(x), (double)(y)))
#endif

/* Finite test without <math.h> classification macros (C and C++ alike):
   x - x is 0 for finite x and NaN for infinities and NaN. */
#define HRM__FINITE(x) ((x) - (x) == 0)

/* ---------------------------------------------------------------------- */
/* Coefficient tables, each with its source                               */
/* ---------------------------------------------------------------------- */

#define HRM__MAX_STAGES 8
#define HRM__NY (2 * HRM__CH)

/* An explicit Runge-Kutta method: stages s, order, row-major a (s x s,
   strictly lower), weights b (the propagated solution), nodes c; embedded
   pairs add the weights bh of the other solution. */
typedef struct hrm__tableau {
    int s, order;
    const hrm_real *a, *b, *c, *bh; /* bh: embedded weights, or NULL */
    int k; /* the error estimate is O(h^(k+1)) */
    /* the RTE form's step limit in h sigma_t (pairs): the largest z, a
       multiple of 1/64, with the stability function R(-z') = 1 - z' b^T
       (I + z' A)^-1 1 in [0, 1] for every z' in [0, z], so that Tr and L
       decay monotonically over a step as the exact solution does
       (tests/test_tables.c recomputes it) */
    hrm_real zmax;
} hrm__tableau;

/* Euler (1768). */
static HRM__TABLE const hrm_real hrm__euler_a[] = {0};
static HRM__TABLE const hrm_real hrm__euler_b[] = {1};
static HRM__TABLE const hrm_real hrm__euler_c[] = {0};
static HRM__TABLE const hrm__tableau hrm__euler = {1, 1, hrm__euler_a, hrm__euler_b, hrm__euler_c, 0, 0, 0};

/* Classical Runge-Kutta (Kutta 1901). */
static HRM__TABLE const hrm_real hrm__rk4_a[] = {
    0, 0, 0, 0,
    HRM__R(0.5), 0, 0, 0,
    0, HRM__R(0.5), 0, 0,
    0, 0, 1, 0};
static HRM__TABLE const hrm_real hrm__rk4_b[] = {HRM__R(1.0 / 6), HRM__R(1.0 / 3), HRM__R(1.0 / 3), HRM__R(1.0 / 6)};
static HRM__TABLE const hrm_real hrm__rk4_c[] = {0, HRM__R(0.5), HRM__R(0.5), 1};
static HRM__TABLE const hrm__tableau hrm__rk4 = {4, 4, hrm__rk4_a, hrm__rk4_b, hrm__rk4_c, 0, 0, 0};

/* Adams-Bashforth 4-step (Bashforth & Adams 1883), newest value first. */
static HRM__TABLE const hrm_real hrm__ab4_beta[4] = {HRM__R(55.0 / 24), HRM__R(-59.0 / 24), HRM__R(37.0 / 24), HRM__R(-9.0 / 24)};

/* Bogacki & Shampine 1989, 3(2), first same as last. */
static HRM__TABLE const hrm_real hrm__bs_a[] = {
    0, 0, 0, 0,
    HRM__R(1.0 / 2), 0, 0, 0,
    0, HRM__R(3.0 / 4), 0, 0,
    HRM__R(2.0 / 9), HRM__R(1.0 / 3), HRM__R(4.0 / 9), 0};
static HRM__TABLE const hrm_real hrm__bs_b[] = {HRM__R(2.0 / 9), HRM__R(1.0 / 3), HRM__R(4.0 / 9), 0};
static HRM__TABLE const hrm_real hrm__bs_bh[] = {HRM__R(7.0 / 24), HRM__R(1.0 / 4), HRM__R(1.0 / 3), HRM__R(1.0 / 8)};
static HRM__TABLE const hrm_real hrm__bs_c[] = {0, HRM__R(1.0 / 2), HRM__R(3.0 / 4), 1};

/* Dormand & Prince 1980, 5(4), first same as last. */
static HRM__TABLE const hrm_real hrm__dp_a[] = {
    0, 0, 0, 0, 0, 0, 0,
    HRM__R(1.0 / 5), 0, 0, 0, 0, 0, 0,
    HRM__R(3.0 / 40), HRM__R(9.0 / 40), 0, 0, 0, 0, 0,
    HRM__R(44.0 / 45), HRM__R(-56.0 / 15), HRM__R(32.0 / 9), 0, 0, 0, 0,
    HRM__R(19372.0 / 6561), HRM__R(-25360.0 / 2187), HRM__R(64448.0 / 6561), HRM__R(-212.0 / 729), 0, 0, 0,
    HRM__R(9017.0 / 3168), HRM__R(-355.0 / 33), HRM__R(46732.0 / 5247), HRM__R(49.0 / 176), HRM__R(-5103.0 / 18656), 0, 0,
    HRM__R(35.0 / 384), 0, HRM__R(500.0 / 1113), HRM__R(125.0 / 192), HRM__R(-2187.0 / 6784), HRM__R(11.0 / 84), 0};
static HRM__TABLE const hrm_real hrm__dp_b[] = {HRM__R(35.0 / 384), 0, HRM__R(500.0 / 1113), HRM__R(125.0 / 192),
                                     HRM__R(-2187.0 / 6784), HRM__R(11.0 / 84), 0};
static HRM__TABLE const hrm_real hrm__dp_bh[] = {HRM__R(5179.0 / 57600), 0, HRM__R(7571.0 / 16695), HRM__R(393.0 / 640),
                                      HRM__R(-92097.0 / 339200), HRM__R(187.0 / 2100), HRM__R(1.0 / 40)};
static HRM__TABLE const hrm_real hrm__dp_c[] = {0, HRM__R(1.0 / 5), HRM__R(3.0 / 10), HRM__R(4.0 / 5), HRM__R(8.0 / 9), 1, 1};

/* Fehlberg 1969, 4(5): the fourth-order solution is propagated. */
static HRM__TABLE const hrm_real hrm__rkf_a[] = {
    0, 0, 0, 0, 0, 0,
    HRM__R(1.0 / 4), 0, 0, 0, 0, 0,
    HRM__R(3.0 / 32), HRM__R(9.0 / 32), 0, 0, 0, 0,
    HRM__R(1932.0 / 2197), HRM__R(-7200.0 / 2197), HRM__R(7296.0 / 2197), 0, 0, 0,
    HRM__R(439.0 / 216), -8, HRM__R(3680.0 / 513), HRM__R(-845.0 / 4104), 0, 0,
    HRM__R(-8.0 / 27), 2, HRM__R(-3544.0 / 2565), HRM__R(1859.0 / 4104), HRM__R(-11.0 / 40), 0};
static HRM__TABLE const hrm_real hrm__rkf_b[] = {HRM__R(25.0 / 216), 0, HRM__R(1408.0 / 2565), HRM__R(2197.0 / 4104), HRM__R(-1.0 / 5), 0};
static HRM__TABLE const hrm_real hrm__rkf_bh[] = {HRM__R(16.0 / 135), 0, HRM__R(6656.0 / 12825), HRM__R(28561.0 / 56430),
                                       HRM__R(-9.0 / 50), HRM__R(2.0 / 55)};
static HRM__TABLE const hrm_real hrm__rkf_c[] = {0, HRM__R(1.0 / 4), HRM__R(3.0 / 8), HRM__R(12.0 / 13), 1, HRM__R(1.0 / 2)};

/* Cash & Karp 1990, 4(5): the fourth-order solution is propagated. */
static HRM__TABLE const hrm_real hrm__ck_a[] = {
    0, 0, 0, 0, 0, 0,
    HRM__R(1.0 / 5), 0, 0, 0, 0, 0,
    HRM__R(3.0 / 40), HRM__R(9.0 / 40), 0, 0, 0, 0,
    HRM__R(3.0 / 10), HRM__R(-9.0 / 10), HRM__R(6.0 / 5), 0, 0, 0,
    HRM__R(-11.0 / 54), HRM__R(5.0 / 2), HRM__R(-70.0 / 27), HRM__R(35.0 / 27), 0, 0,
    HRM__R(1631.0 / 55296), HRM__R(175.0 / 512), HRM__R(575.0 / 13824), HRM__R(44275.0 / 110592), HRM__R(253.0 / 4096), 0};
static HRM__TABLE const hrm_real hrm__ck_b[] = {HRM__R(2825.0 / 27648), 0, HRM__R(18575.0 / 48384), HRM__R(13525.0 / 55296),
                                     HRM__R(277.0 / 14336), HRM__R(1.0 / 4)};
static HRM__TABLE const hrm_real hrm__ck_bh[] = {HRM__R(37.0 / 378), 0, HRM__R(250.0 / 621), HRM__R(125.0 / 594), 0, HRM__R(512.0 / 1771)};
static HRM__TABLE const hrm_real hrm__ck_c[] = {0, HRM__R(1.0 / 5), HRM__R(3.0 / 10), HRM__R(3.0 / 5), 1, HRM__R(7.0 / 8)};

/* Verner 1978, 6(5), the pair of DVERK (Hull, Enright & Jackson 1976). */
static HRM__TABLE const hrm_real hrm__vr_a[] = {
    0, 0, 0, 0, 0, 0, 0, 0,
    HRM__R(1.0 / 6), 0, 0, 0, 0, 0, 0, 0,
    HRM__R(4.0 / 75), HRM__R(16.0 / 75), 0, 0, 0, 0, 0, 0,
    HRM__R(5.0 / 6), HRM__R(-8.0 / 3), HRM__R(5.0 / 2), 0, 0, 0, 0, 0,
    HRM__R(-165.0 / 64), HRM__R(55.0 / 6), HRM__R(-425.0 / 64), HRM__R(85.0 / 96), 0, 0, 0, 0,
    HRM__R(12.0 / 5), -8, HRM__R(4015.0 / 612), HRM__R(-11.0 / 36), HRM__R(88.0 / 255), 0, 0, 0,
    HRM__R(-8263.0 / 15000), HRM__R(124.0 / 75), HRM__R(-643.0 / 680), HRM__R(-81.0 / 250), HRM__R(2484.0 / 10625), 0, 0, 0,
    HRM__R(3501.0 / 1720), HRM__R(-300.0 / 43), HRM__R(297275.0 / 52632), HRM__R(-319.0 / 2322), HRM__R(24068.0 / 84065), 0,
    HRM__R(3850.0 / 26703), 0};
static HRM__TABLE const hrm_real hrm__vr_b[] = {HRM__R(3.0 / 40), 0, HRM__R(875.0 / 2244), HRM__R(23.0 / 72), HRM__R(264.0 / 1955), 0,
                                     HRM__R(125.0 / 11592), HRM__R(43.0 / 616)};
static HRM__TABLE const hrm_real hrm__vr_bh[] = {HRM__R(13.0 / 160), 0, HRM__R(2375.0 / 5984), HRM__R(5.0 / 16), HRM__R(12.0 / 85),
                                      HRM__R(3.0 / 44), 0, 0};
static HRM__TABLE const hrm_real hrm__vr_c[] = {0, HRM__R(1.0 / 6), HRM__R(4.0 / 15), HRM__R(2.0 / 3), HRM__R(5.0 / 6), 1, HRM__R(1.0 / 15), 1};

static HRM__TABLE const hrm__tableau hrm__bs = {4, 3, hrm__bs_a, hrm__bs_b, hrm__bs_c, hrm__bs_bh, 2, HRM__R(102.0 / 64)};
static HRM__TABLE const hrm__tableau hrm__dp = {7, 5, hrm__dp_a, hrm__dp_b, hrm__dp_c, hrm__dp_bh, 4, HRM__R(211.0 / 64)};
static HRM__TABLE const hrm__tableau hrm__rkf = {6, 4, hrm__rkf_a, hrm__rkf_b, hrm__rkf_c, hrm__rkf_bh, 4, HRM__R(131.0 / 64)};
static HRM__TABLE const hrm__tableau hrm__ck = {6, 4, hrm__ck_a, hrm__ck_b, hrm__ck_c, hrm__ck_bh, 4, HRM__R(269.0 / 64)};
static HRM__TABLE const hrm__tableau hrm__vr = {8, 6, hrm__vr_a, hrm__vr_b, hrm__vr_c, hrm__vr_bh, 5, HRM__R(181.0 / 64)};

/* Gauss-Kronrod G7/K15 on [-1, 1], the 15 nodes ascending with their
   Kronrod weights and the Gauss weights (0 off the G7 nodes) (Piessens et
   al. 1983, QUADPACK qk15). */
static HRM__TABLE const hrm_real hrm__gk_x[15] = {
    HRM__R(-0.991455371120812639206854697526329), HRM__R(-0.949107912342758524526189684047851), HRM__R(-0.864864423359769072789712788640926),
    HRM__R(-0.741531185599394439863864773280788), HRM__R(-0.586087235467691130294144845693013), HRM__R(-0.405845151377397166906606412076961),
    HRM__R(-0.207784955007898467600689403773245), 0, HRM__R(0.207784955007898467600689403773245),
    HRM__R(0.405845151377397166906606412076961), HRM__R(0.586087235467691130294144845693013), HRM__R(0.741531185599394439863864773280788),
    HRM__R(0.864864423359769072789712788640926), HRM__R(0.949107912342758524526189684047851), HRM__R(0.991455371120812639206854697526329)};
static HRM__TABLE const hrm_real hrm__gk_wk[15] = {
    HRM__R(0.022935322010529224963732008058970), HRM__R(0.063092092629978553290700663189204), HRM__R(0.104790010322250183839876322541518),
    HRM__R(0.140653259715525918745189590510238), HRM__R(0.169004726639267902826583426598550), HRM__R(0.190350578064785409913256402421014),
    HRM__R(0.204432940075298892414161999234649), HRM__R(0.209482141084727828012999174891714), HRM__R(0.204432940075298892414161999234649),
    HRM__R(0.190350578064785409913256402421014), HRM__R(0.169004726639267902826583426598550), HRM__R(0.140653259715525918745189590510238),
    HRM__R(0.104790010322250183839876322541518), HRM__R(0.063092092629978553290700663189204), HRM__R(0.022935322010529224963732008058970)};
static HRM__TABLE const hrm_real hrm__gk_wg[15] = {
    0, HRM__R(0.129484966168869693270611432679082), 0,
    HRM__R(0.279705391489276667901467771423780), 0, HRM__R(0.381830050505118944950369775488975),
    0, HRM__R(0.417959183673469387755102040816327), 0,
    HRM__R(0.381830050505118944950369775488975), 0, HRM__R(0.279705391489276667901467771423780),
    0, HRM__R(0.129484966168869693270611432679082), 0};

/* tau at the K15 nodes from the same sigma_t samples, at the rule's own
   order: row k integrates the degree-14 interpolant of the 15 samples
   (nodes ascending) from -1 to node k. Derived from the nodes above by
   solving the moment equations in 60-digit arithmetic. */
static HRM__TABLE const hrm_real hrm__gk_tau[15 * 15] = {
    HRM__R(1.03981052571528020e-02), HRM__R(-2.83769996283116761e-03), HRM__R(1.62788193298481925e-03), HRM__R(-1.11841594714680325e-03), HRM__R(8.45482170423812371e-04), HRM__R(-6.66001240133393471e-04), HRM__R(5.32680720730747438e-04), HRM__R(-4.30041676019444997e-04), HRM__R(3.48989628422702184e-04), HRM__R(-2.80737088267947129e-04), HRM__R(2.19579858925692716e-04), HRM__R(-1.64513471435547557e-04), HRM__R(1.15766632496470633e-04), HRM__R(-7.01728856955884225e-05), HRM__R(2.37249495802066603e-05),
    HRM__R(2.59676963544380954e-02), HRM__R(2.89875870535199719e-02), HRM__R(-6.27697160882417261e-03), HRM__R(3.73995774299085539e-03), HRM__R(-2.68023068806569169e-03), HRM__R(2.05710230908247391e-03), HRM__R(-1.62137543376796684e-03), HRM__R(1.29718279755412997e-03), HRM__R(-1.04651322220011703e-03), HRM__R(8.38503193963724522e-04), HRM__R(-6.54039450176873024e-04), HRM__R(4.89084267608792854e-04), HRM__R(-3.43721602645067541e-04), HRM__R(2.08186242500220495e-04), HRM__R(-7.03602987368992560e-05),
    HRM__R(2.10599038857128759e-02), HRM__R(7.07105324151710846e-02), HRM__R(5.00573892969998213e-02), HRM__R(-1.03156106672409823e-02), HRM__R(6.09949512399137091e-03), HRM__R(-4.31472273996388270e-03), HRM__R(3.25691411481426798e-03), HRM__R(-2.53940842894569011e-03), HRM__R(2.01527612105997789e-03), HRM__R(-1.59712331800328428e-03), HRM__R(1.23646392203085177e-03), HRM__R(-9.19841684291590857e-04), HRM__R(6.44210468122750944e-04), HRM__R(-3.89363950916298929e-04), HRM__R(1.31462081689653302e-04),
    HRM__R(2.42361841520569617e-02), HRM__R(5.86298373985222609e-02), HRM__R(1.15772886460054306e-01), HRM__R(6.88096505007365078e-02), HRM__R(-1.37058744019498586e-02), HRM__R(7.85917909244863294e-03), HRM__R(-5.40850940628008568e-03), HRM__R(4.01068356429491821e-03), HRM__R(-3.08798503965356354e-03), HRM__R(2.40012223793888580e-03), HRM__R(-1.83413561933193315e-03), HRM__R(1.35247571776085803e-03), HRM__R(-9.41674029335289064e-04), HRM__R(5.67143618117730490e-04), HRM__R(-1.91169844774781038e-04),
    HRM__R(2.19798996704970509e-02), HRM__R(6.61632913922189508e-02), HRM__R(9.85944173781882344e-02), HRM__R(1.54281109069179939e-01), HRM__R(8.34799022449225353e-02), HRM__R(-1.59578818165279600e-02), HRM__R(8.84168511858526157e-03), HRM__R(-5.95436655325001871e-03), HRM__R(4.35037688885598663e-03), HRM__R(-3.27595449198800391e-03), HRM__R(2.45305274072773116e-03), HRM__R(-1.78470449783212841e-03), HRM__R(1.23177661238402193e-03), HRM__R(-7.37994393805901146e-04), HRM__R(2.48155170153167447e-04),
    HRM__R(2.36791640034627604e-02), HRM__R(6.07765649633377480e-02), HRM__R(1.09085903509984733e-01), HRM__R(1.33009801043256881e-01), HRM__R(1.84981283957081966e-01), HRM__R(9.42381352810250927e-02), HRM__R(-1.73600808733072424e-02), HRM__R(9.40125173691372037e-03), HRM__R(-6.23525912547830997e-03), HRM__R(4.45482244064482075e-03), HRM__R(-3.23169297372776984e-03), HRM__R(2.30432284193334610e-03), HRM__R(-1.57020300006580115e-03), HRM__R(9.33719392744436754e-04), HRM__R(-3.12884575203547480e-04),
    HRM__R(2.23317819580927633e-02), HRM__R(6.49366741874042169e-02), HRM__R(1.01516111104036494e-01), HRM__R(1.45960556314527978e-01), HRM__R(1.60089011532322550e-01), HRM__R(2.08140264531676472e-01), HRM__R(1.01532689898125916e-01), HRM__R(-1.82882132069951790e-02), HRM__R(9.75431889378732334e-03), HRM__R(-6.32660677307881215e-03), HRM__R(4.35470331563592682e-03), HRM__R(-3.00922255514957148e-03), HRM__R(2.01163520001652494e-03), HRM__R(-1.18315104249449351e-03), HRM__R(3.94491634193419312e-04),
    HRM__R(2.34274478211548287e-02), HRM__R(6.16051040320834478e-02), HRM__R(1.07360685303677469e-01), HRM__R(1.36690329643342851e-01), HRM__R(1.75047571388848411e-01), HRM__R(1.80674995628903823e-01), HRM__R(2.23002257024795453e-01), HRM__R(1.04741070542363909e-01), HRM__R(-1.85693169494965671e-02), HRM__R(9.67558243588159325e-03), HRM__R(-6.04284474958050391e-03), HRM__R(3.96293007218306154e-03), HRM__R(-2.57067498142728341e-03), HRM__R(1.48698859789510264e-03), HRM__R(-4.92125810625604235e-04),
    HRM__R(2.25408303763358041e-02), HRM__R(6.42752436724730453e-02), HRM__R(1.02778375122233659e-01), HRM__R(1.43662482270675490e-01), HRM__R(1.64650023323631989e-01), HRM__R(1.96677184837864227e-01), HRM__R(1.94678621181511580e-01), HRM__R(2.27770354291723015e-01), HRM__R(1.02900250177172969e-01), HRM__R(-1.77896864668910595e-02), HRM__R(8.91571510694534955e-03), HRM__R(-5.30729659900206537e-03), HRM__R(3.27389921821368869e-03), HRM__R(-1.84458155742565737e-03), HRM__R(6.03540052436463007e-04),
    HRM__R(2.32482065857327717e-02), HRM__R(6.21583732372341172e-02), HRM__R(1.06360213322315988e-01), HRM__R(1.38348936873592565e-01), HRM__R(1.72236419612995684e-01), HRM__R(1.85895755624140596e-01), HRM__R(2.10668199200777201e-01), HRM__R(2.00080889347814095e-01), HRM__R(2.21793020948606145e-01), HRM__R(9.61124427837603268e-02), HRM__R(-1.59765573178140656e-02), HRM__R(7.64345867226903092e-03), HRM__R(-4.29589318773454260e-03), HRM__R(2.31552766664080241e-03), HRM__R(-7.43841992933535925e-04),
    HRM__R(2.26871668403760586e-02), HRM__R(6.38300870237844542e-02), HRM__R(1.03558233709866165e-01), HRM__R(1.42437964213358054e-01), HRM__R(1.66551673898540170e-01), HRM__R(1.93626532556773423e-01), HRM__R(2.00082563186442908e-01), HRM__R(2.15436507637977837e-01), HRM__R(1.95591254956713617e-01), HRM__R(2.06308459881313383e-01), HRM__R(8.55248243943453751e-02), HRM__R(-1.36278493536540288e-02), HRM__R(6.19559294406194817e-03), HRM__R(-3.07119876224039344e-03), HRM__R(9.55422340032172383e-04),
    HRM__R(2.31264918553040072e-02), HRM__R(6.25249490118608281e-02), HRM__R(1.05731684351585475e-01), HRM__R(1.39300783997765049e-01), HRM__R(1.70838862258599844e-01), HRM__R(1.87950455826846524e-01), HRM__R(2.07520925114952459e-01), HRM__R(2.05471457520432915e-01), HRM__R(2.09841449481578984e-01), HRM__R(1.82491398972336766e-01), HRM__R(1.82710601041217752e-01), HRM__R(7.18436092147894112e-02), HRM__R(-1.09828761378041283e-02), HRM__R(4.46225523145629081e-03), HRM__R(-1.30086214152773643e-03),
    HRM__R(2.28038599288395705e-02), HRM__R(6.34814565808948517e-02), HRM__R(1.04145799854127433e-01), HRM__R(1.41573101399817519e-01), HRM__R(1.67768262717237049e-01), HRM__R(1.91947701382788688e-01), HRM__R(2.02417663954238908e-01), HRM__R(2.12021549513673524e-01), HRM__R(2.01176025960484617e-01), HRM__R(1.94665300804749281e-01), HRM__R(1.62905231515276527e-01), HRM__R(1.50968870382766907e-01), HRM__R(5.47326210252503664e-02), HRM__R(-7.61843978519253541e-03), HRM__R(1.87541812481634780e-03),
    HRM__R(2.30056823092661226e-02), HRM__R(6.28839063874783305e-02), HRM__R(1.05133731924895252e-01), HRM__R(1.40164175447917122e-01), HRM__R(1.69658766089444774e-01), HRM__R(1.89512074870821695e-01), HRM__R(2.05479453297499004e-01), HRM__R(2.08184958287173705e-01), HRM__R(2.06054315509066860e-01), HRM__R(1.88293475755702933e-01), HRM__R(1.71684957327333604e-01), HRM__R(1.36913301972535068e-01), HRM__R(1.11066981931074352e-01), HRM__R(3.41045055764585825e-02), HRM__R(-3.03237434390886927e-03),
    HRM__R(2.29115970609490190e-02), HRM__R(6.31622655156741375e-02), HRM__R(1.04674243689753713e-01), HRM__R(1.40817773186961454e-01), HRM__R(1.68785146780342205e-01), HRM__R(1.90631315153053343e-01), HRM__R(2.04083950446876189e-01), HRM__R(2.09912182760747273e-01), HRM__R(2.03900259354568153e-01), HRM__R(1.91016579304918804e-01), HRM__R(1.68159244468844088e-01), HRM__R(1.41771675662672736e-01), HRM__R(1.03162128389265362e-01), HRM__R(6.59297925928097189e-02), HRM__R(1.25372167533764223e-02),
};

/* Gauss-Kronrod G3/K7 on [-1, 1]: the Kronrod extension of the 3-point
   Gauss rule, exact to degree 11 (nodes and weights from the moment
   equations in 50-digit arithmetic; the values tabulated by Kronrod 1965). */
static HRM__TABLE const hrm_real hrm__k7_x[7] = {
    HRM__R(-0.960491268708020283423507092629079963), HRM__R(-0.774596669241483377035853079956479922), HRM__R(-0.434243749346802558002071502844627817),
    0, HRM__R(0.434243749346802558002071502844627817), HRM__R(0.774596669241483377035853079956479922),
    HRM__R(0.960491268708020283423507092629079963)};
static HRM__TABLE const hrm_real hrm__k7_wk[7] = {
    HRM__R(0.104656226026467265193823857192073038), HRM__R(0.268488089868333440728569280666709625), HRM__R(0.401397414775962222905051818618431879),
    HRM__R(0.450916538658474142345110087045570917), HRM__R(0.401397414775962222905051818618431879), HRM__R(0.268488089868333440728569280666709625),
    HRM__R(0.104656226026467265193823857192073038)};
static HRM__TABLE const hrm_real hrm__k7_wg[7] = {
    0, HRM__R(0.555555555555555555555555555555555556), 0,
    HRM__R(0.888888888888888888888888888888888889), 0, HRM__R(0.555555555555555555555555555555555556),
    0};
/* tau at the K7 nodes: row k integrates the degree-6 interpolant of the 7
   samples from -1 to node k (50-digit quadrature of the Lagrange basis). */
static HRM__TABLE const hrm_real hrm__k7_tau[7 * 7] = {
    HRM__R(0.0481496455686497328621236293498), HRM__R(-0.0130360908056543319319257724666), HRM__R(0.00700577096934105189603216828381),
    HRM__R(-0.00428231888789362889754385797461), HRM__R(0.00272596459404615386195021000773), HRM__R(-0.00157297682571128731846100459503),
    HRM__R(0.000518736679202026104317534765771),
    HRM__R(0.117808240183343764755767317213), HRM__R(0.124361311477770450717200491237), HRM__R(-0.0250548635778850230812518851319),
    HRM__R(0.0132563814267296594664430245876), HRM__R(-0.00801061715598765799513410782215), HRM__R(0.00452069012015710009776088527137),
    HRM__R(-0.00147781171561167099663880531059),
    HRM__R(0.0967620363480509583880666623129), HRM__R(0.299671729373368531074003356892), HRM__R(0.193453235451728566206801772282),
    HRM__R(-0.035600487606178007749199607425), HRM__R(0.0178891733849423784096871482136), HRM__R(-0.00941953396680635289235104894583),
    HRM__R(0.00300009766809136856092021382586),
    HRM__R(0.109708656676477259896398377912), HRM__R(0.251617102477383148859089283566), HRM__R(0.440125779262853033412855573478),
    HRM__R(0.225458269329237071172555043523), HRM__R(-0.0387283644868908105078037548599), HRM__R(0.0168709873909502918694799971002),
    HRM__R(-0.00505243065000999470257452071963),
    HRM__R(0.101656128358375896632903643366), HRM__R(0.277907623835139793620920329613), HRM__R(0.383508241391019844495364670405),
    HRM__R(0.486517026264652150094309694471), HRM__R(0.207944179324233656698250046336), HRM__R(-0.0311836395050350903454340762249),
    HRM__R(0.00789418967841630680575719487919),
    HRM__R(0.106134037742078936190462662503), HRM__R(0.263967399748176340630808395395), HRM__R(0.409408031931949880900185926441),
    HRM__R(0.437660157231744482878667062458), HRM__R(0.42645227835384724598630370375), HRM__R(0.14412677839056299001136878943),
    HRM__R(-0.0131520141568764995619434600205),
    HRM__R(0.104137489347265239089506322426), HRM__R(0.270061066694044728047030285262), HRM__R(0.398671450181916069043101608611),
    HRM__R(0.45519885754636777124265394502), HRM__R(0.394391643806621171009019650335), HRM__R(0.281524180673987772660495053133),
    HRM__R(0.0565065804578175323317002278422),
};

/* The Legendre coefficients of the polynomial through a pair's nodes:
   row k of the inverse of V[j][k] = P_k(x_j), for k = n - 1, n - 2 (the
   highest two) and n - 5, n - 6 (K15; K7, of 7 nodes: n - 3, n - 4), so
   that c_k = sum_j row[j] f(x_j)
   (computed from the nodes above in 50-digit arithmetic; test_tables
   checks them against P_k at the nodes). */
static HRM__TABLE const hrm_real hrm__gk_leg[4 * 15] = {
    HRM__R(0.0505052523670278229946), HRM__R(-0.146201951379381873356), HRM__R(0.230755247928894226339), HRM__R(-0.306202939037978631794), HRM__R(0.372160738193176938474), HRM__R(-0.421651768144555709568), HRM__R(0.450176248927154346585), HRM__R(-0.459081657708674239350), HRM__R(0.450176248927154346585), HRM__R(-0.421651768144555709568), HRM__R(0.372160738193176938474), HRM__R(-0.306202939037978631794), HRM__R(0.230755247928894226339), HRM__R(-0.146201951379381873356), HRM__R(0.0505052523670278229946),
    HRM__R(-0.0965707143346964659757), HRM__R(0.267611327075807899989), HRM__R(-0.384888865700437042525), HRM__R(0.437899554807784831224), HRM__R(-0.420657412237561756348), HRM__R(0.330027413794407741529), HRM__R(-0.180398285284409871493), 0, HRM__R(0.180398285284409871493), HRM__R(-0.330027413794407741529), HRM__R(0.420657412237561756348), HRM__R(-0.437899554807784831224), HRM__R(0.384888865700437042525), HRM__R(-0.267611327075807899989), HRM__R(0.0965707143346964659757),
    HRM__R(0.138729956396644884713), HRM__R(-0.235232635615776707345), HRM__R(-0.00454163115413780707059), HRM__R(0.363653242793321034349), HRM__R(-0.473150543882563846277), HRM__R(0.172624106953099187664), HRM__R(0.302462337722854959012), HRM__R(-0.529089666426883410093), HRM__R(0.302462337722854959012), HRM__R(0.172624106953099187664), HRM__R(-0.473150543882563846277), HRM__R(0.363653242793321034349), HRM__R(-0.00454163115413780707059), HRM__R(-0.235232635615776707345), HRM__R(0.138729956396644884713),
    HRM__R(-0.141673669082500858888), HRM__R(0.166256623422168808444), HRM__R(0.181442566122020068672), HRM__R(-0.419714075932214606837), HRM__R(0.147129786215698378210), HRM__R(0.362454172761982560613), HRM__R(-0.463727794251539658791), 0, HRM__R(0.463727794251539658791), HRM__R(-0.362454172761982560613), HRM__R(-0.147129786215698378210), HRM__R(0.419714075932214606837), HRM__R(-0.181442566122020068672), HRM__R(-0.166256623422168808444), HRM__R(0.141673669082500858888),
};
static HRM__TABLE const hrm_real hrm__k7_leg[4 * 7] = {
    HRM__R(0.158570039434041310900), HRM__R(-0.434950705586700173980), HRM__R(0.608177901175700337735), HRM__R(-0.663594470046082949309), HRM__R(0.608177901175700337735), HRM__R(-0.434950705586700173980), HRM__R(0.158570039434041310900),
    HRM__R(-0.279226086984319099777), HRM__R(0.617670841024766852943), HRM__R(-0.484178662140076336046), 0, HRM__R(0.484178662140076336046), HRM__R(-0.617670841024766852943), HRM__R(0.279226086984319099777),
    HRM__R(0.300922614828066390215), HRM__R(-0.362458921322250144984), HRM__R(-0.318924522998903802835), HRM__R(0.760921658986175115207), HRM__R(-0.318924522998903802835), HRM__R(-0.362458921322250144984), HRM__R(0.300922614828066390215),
    HRM__R(-0.283697042072339787012), 0, HRM__R(0.627501333706372321802), 0, HRM__R(-0.627501333706372321802), 0, HRM__R(0.283697042072339787012),
};

/* A Gauss-Kronrod pair: n nodes ascending, Kronrod and Gauss weights,
   the tau matrix, the Kronrod rule's exact degree, and a bound below the
   gap between its nodes and an ancestor's (hrm__gk_resolved). */
typedef struct hrm__gk_pair {
    int n, degree;
    const hrm_real *x, *wk, *wg, *tau;
    hrm_real gap; /* below the closest node of an ancestor, per width */
    const hrm_real *leg; /* four rows of Legendre coefficients (hrm__gk_leg) */
} hrm__gk_pair;
static HRM__TABLE const hrm__gk_pair hrm__k15 = {15, 22, hrm__gk_x, hrm__gk_wk, hrm__gk_wg, hrm__gk_tau, HRM__R(1e-4), hrm__gk_leg};
static HRM__TABLE const hrm__gk_pair hrm__k7 = {7, 11, hrm__k7_x, hrm__k7_wk, hrm__k7_wg, hrm__k7_tau, HRM__R(1e-2), hrm__k7_leg};

/* The Chebyshev polynomials at the degree-16 Lobatto points, ascending in t:
   T_k(-cos(j pi / 16)) = (-1)^k cos(j k pi / 16), row k, column j (the
   degree-8 points are the even columns). */
static HRM__TABLE const hrm_real hrm__cheb_T[17][17] = {
    {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1},
    {-1, HRM__R(-0.980785280403230449126), HRM__R(-0.923879532511286756128), HRM__R(-0.831469612302545237079), HRM__R(-0.707106781186547524401), HRM__R(-0.555570233019602224743), HRM__R(-0.382683432365089771728), HRM__R(-0.195090322016128267848), 0, HRM__R(0.195090322016128267848), HRM__R(0.382683432365089771728), HRM__R(0.555570233019602224743), HRM__R(0.707106781186547524401), HRM__R(0.831469612302545237079), HRM__R(0.923879532511286756128), HRM__R(0.980785280403230449126), 1},
    {1, HRM__R(0.923879532511286756128), HRM__R(0.707106781186547524401), HRM__R(0.382683432365089771728), 0, HRM__R(-0.382683432365089771728), HRM__R(-0.707106781186547524401), HRM__R(-0.923879532511286756128), -1, HRM__R(-0.923879532511286756128), HRM__R(-0.707106781186547524401), HRM__R(-0.382683432365089771728), 0, HRM__R(0.382683432365089771728), HRM__R(0.707106781186547524401), HRM__R(0.923879532511286756128), 1},
    {-1, HRM__R(-0.831469612302545237079), HRM__R(-0.382683432365089771728), HRM__R(0.195090322016128267848), HRM__R(0.707106781186547524401), HRM__R(0.980785280403230449126), HRM__R(0.923879532511286756128), HRM__R(0.555570233019602224743), 0, HRM__R(-0.555570233019602224743), HRM__R(-0.923879532511286756128), HRM__R(-0.980785280403230449126), HRM__R(-0.707106781186547524401), HRM__R(-0.195090322016128267848), HRM__R(0.382683432365089771728), HRM__R(0.831469612302545237079), 1},
    {1, HRM__R(0.707106781186547524401), 0, HRM__R(-0.707106781186547524401), -1, HRM__R(-0.707106781186547524401), 0, HRM__R(0.707106781186547524401), 1, HRM__R(0.707106781186547524401), 0, HRM__R(-0.707106781186547524401), -1, HRM__R(-0.707106781186547524401), 0, HRM__R(0.707106781186547524401), 1},
    {-1, HRM__R(-0.555570233019602224743), HRM__R(0.382683432365089771728), HRM__R(0.980785280403230449126), HRM__R(0.707106781186547524401), HRM__R(-0.195090322016128267848), HRM__R(-0.923879532511286756128), HRM__R(-0.831469612302545237079), 0, HRM__R(0.831469612302545237079), HRM__R(0.923879532511286756128), HRM__R(0.195090322016128267848), HRM__R(-0.707106781186547524401), HRM__R(-0.980785280403230449126), HRM__R(-0.382683432365089771728), HRM__R(0.555570233019602224743), 1},
    {1, HRM__R(0.382683432365089771728), HRM__R(-0.707106781186547524401), HRM__R(-0.923879532511286756128), 0, HRM__R(0.923879532511286756128), HRM__R(0.707106781186547524401), HRM__R(-0.382683432365089771728), -1, HRM__R(-0.382683432365089771728), HRM__R(0.707106781186547524401), HRM__R(0.923879532511286756128), 0, HRM__R(-0.923879532511286756128), HRM__R(-0.707106781186547524401), HRM__R(0.382683432365089771728), 1},
    {-1, HRM__R(-0.195090322016128267848), HRM__R(0.923879532511286756128), HRM__R(0.555570233019602224743), HRM__R(-0.707106781186547524401), HRM__R(-0.831469612302545237079), HRM__R(0.382683432365089771728), HRM__R(0.980785280403230449126), 0, HRM__R(-0.980785280403230449126), HRM__R(-0.382683432365089771728), HRM__R(0.831469612302545237079), HRM__R(0.707106781186547524401), HRM__R(-0.555570233019602224743), HRM__R(-0.923879532511286756128), HRM__R(0.195090322016128267848), 1},
    {1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1, 0, 1, 0, -1, 0, 1},
    {-1, HRM__R(0.195090322016128267848), HRM__R(0.923879532511286756128), HRM__R(-0.555570233019602224743), HRM__R(-0.707106781186547524401), HRM__R(0.831469612302545237079), HRM__R(0.382683432365089771728), HRM__R(-0.980785280403230449126), 0, HRM__R(0.980785280403230449126), HRM__R(-0.382683432365089771728), HRM__R(-0.831469612302545237079), HRM__R(0.707106781186547524401), HRM__R(0.555570233019602224743), HRM__R(-0.923879532511286756128), HRM__R(-0.195090322016128267848), 1},
    {1, HRM__R(-0.382683432365089771728), HRM__R(-0.707106781186547524401), HRM__R(0.923879532511286756128), 0, HRM__R(-0.923879532511286756128), HRM__R(0.707106781186547524401), HRM__R(0.382683432365089771728), -1, HRM__R(0.382683432365089771728), HRM__R(0.707106781186547524401), HRM__R(-0.923879532511286756128), 0, HRM__R(0.923879532511286756128), HRM__R(-0.707106781186547524401), HRM__R(-0.382683432365089771728), 1},
    {-1, HRM__R(0.555570233019602224743), HRM__R(0.382683432365089771728), HRM__R(-0.980785280403230449126), HRM__R(0.707106781186547524401), HRM__R(0.195090322016128267848), HRM__R(-0.923879532511286756128), HRM__R(0.831469612302545237079), 0, HRM__R(-0.831469612302545237079), HRM__R(0.923879532511286756128), HRM__R(-0.195090322016128267848), HRM__R(-0.707106781186547524401), HRM__R(0.980785280403230449126), HRM__R(-0.382683432365089771728), HRM__R(-0.555570233019602224743), 1},
    {1, HRM__R(-0.707106781186547524401), 0, HRM__R(0.707106781186547524401), -1, HRM__R(0.707106781186547524401), 0, HRM__R(-0.707106781186547524401), 1, HRM__R(-0.707106781186547524401), 0, HRM__R(0.707106781186547524401), -1, HRM__R(0.707106781186547524401), 0, HRM__R(-0.707106781186547524401), 1},
    {-1, HRM__R(0.831469612302545237079), HRM__R(-0.382683432365089771728), HRM__R(-0.195090322016128267848), HRM__R(0.707106781186547524401), HRM__R(-0.980785280403230449126), HRM__R(0.923879532511286756128), HRM__R(-0.555570233019602224743), 0, HRM__R(0.555570233019602224743), HRM__R(-0.923879532511286756128), HRM__R(0.980785280403230449126), HRM__R(-0.707106781186547524401), HRM__R(0.195090322016128267848), HRM__R(0.382683432365089771728), HRM__R(-0.831469612302545237079), 1},
    {1, HRM__R(-0.923879532511286756128), HRM__R(0.707106781186547524401), HRM__R(-0.382683432365089771728), 0, HRM__R(0.382683432365089771728), HRM__R(-0.707106781186547524401), HRM__R(0.923879532511286756128), -1, HRM__R(0.923879532511286756128), HRM__R(-0.707106781186547524401), HRM__R(0.382683432365089771728), 0, HRM__R(-0.382683432365089771728), HRM__R(0.707106781186547524401), HRM__R(-0.923879532511286756128), 1},
    {-1, HRM__R(0.980785280403230449126), HRM__R(-0.923879532511286756128), HRM__R(0.831469612302545237079), HRM__R(-0.707106781186547524401), HRM__R(0.555570233019602224743), HRM__R(-0.382683432365089771728), HRM__R(0.195090322016128267848), 0, HRM__R(-0.195090322016128267848), HRM__R(0.382683432365089771728), HRM__R(-0.555570233019602224743), HRM__R(0.707106781186547524401), HRM__R(-0.831469612302545237079), HRM__R(0.923879532511286756128), HRM__R(-0.980785280403230449126), 1},
    {1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1},
};

/* The method table, one row a method in the enum's order, from the same
   list as the enum: a method added at the end gets its own family. */
typedef struct hrm__method_info {
    const char *name;
    int family;                /* HRM__FIXED_QUAD ... HRM__PAIR */
    int steps;                 /* default steps, or initial panels/intervals */
    double order;              /* on smooth integrands (Monte Carlo: 1/2) */
    int rte;                   /* HRM_FORM_RTE applies (IVP solvers) */
    const hrm__tableau *tb;    /* IVP solvers */
    int fit;                   /* options.exponential applies */
    int stream;                /* HRM_TAU_STREAM: 0 not, 1 on request (its
                                  nodes in t, tau at each), 2 also the
                                  default under a warp (order 2 at most:
                                  its 16 extra samples stay below the
                                  rule's own error) */
    int driver;                /* HRM__DRV_*: the code that runs it */
} hrm__method_info;

static HRM__TABLE const hrm__method_info hrm__methods[HRM_METHOD_COUNT] = {
    {"default", HRM__FIXED_QUAD, 32, 4, 0, 0, 0, 0, 0}, /* never read: resolved to HRM_NESTED_SIMPSON first */
#define HRM__METHOD_INFO(name, text, family, steps, order, rte, tableau, fit, stream, driver) \
    {text, family, steps, order, rte, tableau, fit, stream, driver},
    HRM__METHOD_LIST(HRM__METHOD_INFO)
#undef HRM__METHOD_INFO
};

/* Adaptive: nested Simpson, Gauss-Kronrod and the Runge-Kutta pairs (a
   tolerance, an error estimate, a budget, remembered abscissae). */
static HRM_DEVICE int hrm__is_adaptive(hrm_method method)
{
    int fam = hrm__methods[method].family;
    return fam == HRM__ADAPTIVE_QUAD || fam == HRM__PAIR;
}

/* The driver of resolved options o: the method's; Gauss-Kronrod's by its
   mode (HRM__DRV_GK: worst first, global; HRM__DRV_GK_LOCAL: Munoz's). */
#define HRM__DRV_GK_LOCAL 9
static HRM_DEVICE int hrm__driver(const hrm_options *o)
{
    int d = hrm__methods[o->method].driver;
    return d == HRM__DRV_GK && o->gk_mode == HRM_GK_LOCAL ? HRM__DRV_GK_LOCAL : d;
}

/* ---------------------------------------------------------------------- */
/* Shared machinery: the solve context, callbacks, random numbers         */
/* ---------------------------------------------------------------------- */

/* One evaluated abscissa. The solvers integrate over a parameter p with
   s = t0 + off(p) (the identity, or a warp); gs and gq are already multiplied
   by ds/dp, so every rule below works in p alone. */
typedef struct hrm__pt {
    hrm_real p, off, J;    /* J = ds/dp */
    hrm_real gs[HRM__CH];  /* sigma_t(s) * ds/dp */
    hrm_real gq[HRM__CH];  /* S(s) * ds/dp */
    hrm_real tr[HRM__CH];  /* Tr(t0, s), when the medium has a closed form */
    hrm_real tau[HRM__CH]; /* and tau(t0, s) (exponential fits), likewise */
    hrm_real sg[HRM__CH];  /* sigma_t(s) * ds/dp as the transmittance layer
                              interpolates it (c->mcheck only) */
} hrm__pt;

/* An exponentially fitted rule on nodes y[0..n) of [-1, 1] (ascending):
   A[k n + j] is the coefficient of the Legendre polynomial P_k in the
   Lagrange polynomial of node j (n x n: Simpson's 9 values, Gauss-Kronrod's
   225 and its Gauss rule's 64, in storage sized by the method: hrm__stage). */
#define HRM__EFIT_MAX 15
typedef struct hrm__efit {
    int n;
    hrm_real y[HRM__EFIT_MAX];
    hrm_real *A;
    int cap;                /* A's entries, n n at least */
} hrm__efit;
#define HRM__EFIT_HEAD ((2 * sizeof(hrm__efit) + 15) / 16 * 16) /* in a workspace: the two fits, their matrices after them */
#define HRM__EFIT_BYTES (HRM__EFIT_HEAD + 2 * HRM__EFIT_MAX * HRM__EFIT_MAX * sizeof(hrm_real))

/* Where tau at the nodes comes from: one choice per solve (hrm__setup),
   of which the flags homog, closed, decoupled, coupled and tau_from_tr
   below are views. */
typedef enum hrm__tau_src {
    HRM__TAU_HOMOG,   /* constants: tau = sigma_t * distance */
    HRM__TAU_TRCB,    /* the host's transmittance callback */
    HRM__TAU_LAYER,   /* the transmittance layer (decoupled) */
    HRM__TAU_STREAM,  /* fixed-step nodes under a warp: their sigma_t and
                         extra samples in t (hrm__stream) */
    HRM__TAU_RULES,   /* the rules' own sigma_t samples (coupled) */
    HRM__TAU_STATE    /* the RTE form's Tr in its state */
} hrm__tau_src;

#define HRM__STREAM_EXTRA 16

/* The stream: sigma_t at a fixed-step rule's nodes, which come in
   increasing t, and at extra points in t wherever two consecutive nodes
   are farther apart than a level set so that the extra points allowed
   (at most 16) go where the nodes are sparsest: the gaps of the
   method's grid in t filled to a common width (hrm__stream_level); tau
   integrated from point to point by the interpolating polynomial of the
   points around (hrm__stream_push). */
typedef struct hrm__stream {
    hrm_real x[4], f[4][HRM_CHANNELS]; /* the last points (offsets), sigma_t */
    int n;                             /* points held since the piece began */
    hrm_real tau[HRM_CHANNELS];        /* tau(t0, t0 + x[n - 1]) */
    hrm_real tc[HRM_CHANNELS];         /* tau(t0, t0 + x[ci]), for good */
    int ci;
    hrm_real start;                    /* the piece's first offset */
    long extra, left;                  /* extra points allowed, left */
    hrm_real level;                    /* a gap wider than it takes points */
} hrm__stream;

/* An abscissa the adaptive methods remember: its callbacks' values. */
typedef struct hrm__memo {
    hrm_real s, p, q[HRM__CH], st[HRM__CH], tr[HRM__CH];
} hrm__memo;

/* The memo's storage: its entries, their abscissae side by side, and how
   many of them fall in each bin of a hash of the abscissa (a node in an
   empty bin, most of them, is not searched for). */
typedef struct hrm__memo_tab {
    hrm__memo e[HRM__MEMO + 1];
    hrm_real s[HRM__MEMO];
    unsigned char bin[HRM__MEMO_BINS];
    unsigned char sbin[HRM__MEMO]; /* each entry's bin */
} hrm__memo_tab;

/* The pieces between breakpoints: their ends in p, and a fixed-step
   method's steps on each (hrm__solve_broken). */
typedef struct hrm__piece_tab {
    hrm_real P[HRM_MAX_BREAKS + 2];
    int N[HRM_MAX_BREAKS + 1];
} hrm__piece_tab;

typedef struct hrm__ctx {
    const hrm_medium *m;
    hrm__tau_src src;      /* where tau comes from */
    hrm__stream sm;        /* src == HRM__TAU_STREAM */
    hrm_real t0, t1, T;    /* T = t1 - t0 */
    hrm_real pa, pb;       /* parameter range, s(pa) = t0, s(pb) = t1 */
    int homog;             /* constant coefficients */
    int closed;            /* Tr at every node known: a closed form, or the
                              decoupled transmittance layer */
    int decoupled;         /* tau from the transmittance layer */
    int tr_at_nodes;       /* the driver reads Tr at its nodes (not the
                              analytic march: its steps' ends) */
    int mcheck;            /* the adaptive rules' nodes are checked against
                              the layer's tau or the host's Tr
                              (hrm__medium_miss) */
    int coupled;           /* tau by the rules from the source nodes' sigma_t */
    int need_st;           /* sigma_t samples at the source nodes needed
                              (coupled tau, or the RTE form) */
    struct hrm__tau *tau;  /* the transmittance layer, when decoupled */
    hrm_real sbar[HRM__CH];/* coupled tau: sigma_t at the first node; the
                              rules integrate sigma_t - sbar and add
                              sbar * (distance) exactly */
    int have_sbar;
    hrm_real off_end;      /* s_end - t0 */
    /* The adaptive methods' last abscissae: a retry after a rejected step,
       or a node below the resolution of t, finds its values here instead
       of calling the callbacks again. */
    int use_memo, nmemo, memo_next, have_end;
    hrm_real *memo_s;           /* the memo's abscissae, side by side for
                                   the search (memo[k].s; hrm__memo_tab) */
    unsigned char *memo_bin;    /* and their count by hash (hrm__memo_bin) */
    unsigned char *memo_sbin;   /* each entry's bin */
    hrm_real memo_max;          /* the largest ever stored: a march's new
                                   nodes beyond it are not searched for */
    hrm_real err_acc[HRM__CH]; /* adaptive: the accepted error estimates */
    hrm_real em_max[HRM__CH];  /* the largest emission per extinction sampled
                                  (hrm__medium_miss) */
    hrm_real src_max[HRM__CH]; /* the largest S / sigma_t sampled (the larger
                                  of Le and Li where sigma_t is not known,
                                  S / sigma_t being their weighted mean) */
    int scale_fixed;           /* the scale is the solution's, not a pilot's */
    hrm_real h_res;            /* the smallest step t resolves (no warp) */
    int nbrk;                  /* breakpoints strictly inside the ray */
    hrm_real brk_off[HRM_MAX_BREAKS]; /* their offsets from t0 */
    hrm_real o_lo, o_hi;       /* the current piece's ends where they are
                                  breakpoints, as offsets (else -inf,
                                  +inf): samples at them are taken on the
                                  piece's side */
    hrm_real w_delta;          /* equiangular: the light's foot on the ray */
    int find_jumps;            /* locate jumps (options.find_jumps) */
    int scan;                  /* scan the medium for jumps first */
    hrm_real cut_tau;          /* options.cutoff's optical depth, where the
                                  scan may cut the ray (0: it may not) */
    hrm_real cut_at;           /* where it cut (offset; 0: nowhere) */
    int keep_layer;            /* hrm__setup on a ray cut by the scan: the
                                  layer keeps what the scan taught it */
    int end_have[2];           /* sigma_a and sigma_s at t0 and t1 kept */
    hrm_real end_sa[2][HRM__CH], end_ss[2][HRM__CH]; /* from their first
                                  lookup (hrm__coeffs) */
    int expo;                  /* exponentially fitted rules */
    int tau_from_tr;           /* tau at nodes is -ln of the transmittance
                                  callback's Tr: capped where it underflows */
    hrm_real unsure[HRM__CH];  /* what fixed steps across that cap added:
                                  upper bounds, not estimates */
    hrm__efit *ef;             /* their fits: the rule's, G's (Gauss-Kronrod);
                                  with options.exponential only */
    long piece_cost;           /* the least evaluations a piece costs */
    long split_cost;           /* a worst-first split's evaluations */
    hrm_real wf_tol;           /* worst first: the current tolerance, summed */
    int jump_found;            /* a split found an interval that does not
                                  shrink, and a jump in it, at cand_t */
    hrm_real cand_t;
    hrm_real cand_miss[HRM__CH]; /* what placing it there may miss: the
                                  jump times Tr times half its bracket (its
                                  whole gap between adjacent abscissae) */
    hrm_real jump_miss[HRM__CH]; /* the same, summed over the jumps made
                                  breakpoints (in result.error) */
    int njumps;
    hrm_real jumps[HRM_MAX_JUMPS]; /* located, as t */
    int layer_miss, restarts;  /* a node's sigma the layer's panel missed */
    int panels0;               /* nested Simpson and Gauss-Kronrod: this piece's first panels */
    hrm_real miss_off, miss_s;
    hrm_real w_ua;             /* equiangular: the angle of t0 (pa, which a
                                  piece between breakpoints moves) */
    int noise_only;            /* the last step or interval judged passed on
                                  the round-off floor alone */
    const struct hrm__gk_pair *gk; /* Gauss-Kronrod: the pair */
    hrm__memo *memo;       /* HRM__MEMO + 1 entries (adaptive methods) */
    struct hrm__ns_store *ns;  /* nested Simpson's storage */
    struct hrm__ns_half *finish; /* its finish's stack in the workspace, or NULL */
    hrm__piece_tab *pieces; /* the pieces' tables in the workspace, or NULL */
    struct hrm__gk_store *gks; /* global Gauss-Kronrod's */
    int unresolved;        /* a warp's distinct nodes at one abscissa */
    long warp_calls;       /* the user warp's t_of_u and dt_du calls */
    hrm_real ksum[HRM__NY];/* fixed-step IVPs: what the state's rounding
                              lost, fed back (hrm__sum) */
    int use_le, use_li;    /* source terms present */
    int per_length;        /* HRM_EMISSION_PER_LENGTH */
    int rte;               /* HRM_FORM_RTE */
    hrm_real sa[HRM__CH], ss[HRM__CH], st[HRM__CH]; /* constants (homog) */
    hrm_status status;     /* first callback failure, else HRM_OK */
    hrm_status warning;    /* first warning, else HRM_OK */
    hrm_real rtol, atol, h_min, h_max; /* resolved; steps in parameter units */
    long max_evals;
    hrm_real range;        /* hrm__range(T): coefficients, sources, state */
    uint64_t rng;
    hrm_stats stats;
    hrm_warp_kind warp;    /* the warp in use, after fallbacks */
    hrm_real w_sigma;      /* distance */
    hrm_real w_D, w_ra, w_rb; /* equiangular: D, distance from the light to t0, t1 (0: inf) */
    hrm_real w_res;           /* equiangular: t's resolution near the light over its distance */
    hrm_real w_cos_a, w_sin_a, w_cos_b, w_sin_b, w_ub; /* cos, sin of u(t0),
                              u(t1); u(t1) itself (pi/2 for t1 = inf) */
    hrm_real w_umid;       /* equiangular: u at t0 + T/2 (offsets below it from t0) */
    const hrm_warp *uw;    /* user */
    hrm_real s_end;        /* the last abscissa: t1, or s(pb) when t1 = inf */
    hrm_real scale[2 * HRM__CH]; /* adaptive: coarse |total| of (tau, L) / 2 */
    int rough_left;        /* adaptive: rough intervals still allowed */
    int tr_have;           /* the transmittance callback's previous call: */
    hrm_real tr_s, tr_v[HRM__CH]; /* its abscissa and values */
} hrm__ctx;

static HRM_DEVICE void hrm__fill(hrm_real *v, int n, hrm_real x)
{
    int i;
    for (i = 0; i < n; ++i) v[i] = x;
}

/* Validate callback output. kind 0: finite, 1: coefficient (>= 0, within
   the range), 2: transmittance ([0, 1]), 3: source (>= 0). A failure is
   recorded once and the values are zeroed so that the arithmetic in flight
   stays harmless until the driver notices and stops; no callback is called
   after it. */
static HRM_DEVICE void hrm__check(hrm__ctx *c, hrm_real *v, int kind)
{
    int i;
    for (i = 0; i < HRM__CH; ++i) {
        int ok = HRM__FINITE(v[i]) && (kind == 0 || v[i] >= 0) &&
                 (kind != 2 || v[i] <= 1);
        if (!ok) {
            if (c->status == HRM_OK) c->status = HRM_ERR_CALLBACK_VALUE;
            v[i] = 0;
        } else if (kind == 1 && v[i] > c->range) {
            if (c->status == HRM_OK) c->status = HRM_ERR_RANGE;
            v[i] = 0;
        }
    }
}

/* The range every rule's sums stay finite in (ERRORS): a coefficient or
   source at most the largest real / 1024 over the ray's length (at least
   1; an infinite ray counts as 1): tau, a step's source times its length,
   their sums over the ray and the estimates' differences all fit with a
   factor 1024 to spare (a finite coefficient of 1e308 made S Tr h inf - inf
   in ten rules). */
static HRM_DEVICE hrm_real hrm__range(hrm_real T)
{
    hrm_real big = HRM__IS_FLOAT ? HRM__R(FLT_MAX) : HRM__R(DBL_MAX);
    return big / 1024 / (HRM__FINITE(T) && T > 1 ? T : 1);
}

/* What an adaptive driver has spent of its budget: evaluations, or its
   attempts (accepted and rejected steps or intervals) where these are
   more. An attempt whose nodes all fall on remembered abscissae (steps
   below t's resolution: a ray far from the origin under a warp, a light
   within 1e-12 of the ray) costs no evaluation; without this count the
   budget never ran out and such solves never ended. */
static HRM_DEVICE long hrm__spent(const hrm__ctx *c)
{
    long work = c->stats.steps + c->stats.rejected;
    /* a user warp's calls count a quarter each (two a node: an attempt
       of 15 nodes on remembered abscissae cost 30 and no evaluation;
       Gauss-Kronrod on a ray 1e-3 long at 1e9 called t_of_u 2e6 times) */
    if (c->warp_calls / 4 > work) work = c->warp_calls / 4;
    return c->stats.evals > work ? c->stats.evals : work;
}

/* The RTE form's explicit steps past their stability limit grow without
   bound: a state beyond the range ends the solve (HRM_ERR_RANGE) before it
   turns inf, then NaN (a step size from NaN never ended the loop). The
   range of a state is the largest real / 1024: sources and coefficients
   within R integrate to at most R (t1 - t0). */
static HRM_DEVICE void hrm__state_check(hrm__ctx *c, const hrm_real *y, int n)
{
    hrm_real lim = hrm__range(1);
    int i;
    for (i = 0; i < n; ++i)
        if (!(HRM_FABS(y[i]) <= lim) && c->status == HRM_OK) c->status = HRM_ERR_RANGE;
}

/* sigma_a and sigma_s at the ray's end `end` (0: t0, 1: t1) kept for
   the lookups there to come (hrm__coeffs), unless a callback failed. */
static HRM_DEVICE void hrm__end_keep(hrm__ctx *c, int end, const hrm_real sa[HRM__CH], const hrm_real ss[HRM__CH])
{
    if (c->status != HRM_OK) return;
    c->end_have[end] = 1;
    memcpy(c->end_sa[end], sa, sizeof c->end_sa[end]);
    memcpy(c->end_ss[end], ss, sizeof c->end_ss[end]);
}

/* The sigma callbacks at s, those that are wanted and present (absent ones
   are zero; sigma_t defaults to sigma_a + sigma_s), validated. Returns
   whether any was called (one medium evaluation). */
static HRM_DEVICE int hrm__coeffs(hrm__ctx *c, hrm_real s, int want_sa, int want_ss, int want_st,
                       hrm_real sa[HRM__CH], hrm_real ss[HRM__CH], hrm_real st[HRM__CH])
{
    const hrm_medium *m = c->m;
    int i, called = 0, derive_st = want_st && !m->sigma_t;
    /* the ray's ends: the scan, the layer and the rules' end nodes all
       sample there, one lookup serves them (not with a sigma_t callback,
       whose value is no sum of these) */
    int end = m->sigma_t ? -1 : s == c->t0 ? 0 : s == c->t1 ? 1 : -1;
    int both = want_st || (want_sa && want_ss); /* what a lookup keeps: both
                                  asked for (as every form of the medium
                                  then calls for both) */
    hrm__fill(sa, HRM__CH, 0);
    hrm__fill(ss, HRM__CH, 0);
    hrm__fill(st, HRM__CH, 0);
    if (end >= 0 && c->end_have[end] && (want_sa || want_ss || want_st)) {
        for (i = 0; i < HRM__CH; ++i) {
            if (want_sa || want_st) sa[i] = c->end_sa[end][i];
            if (want_ss || want_st) ss[i] = c->end_ss[end][i];
            if (want_st) st[i] = c->end_sa[end][i] + c->end_ss[end][i];
        }
        return 0;
    }
    if (m->sigma) {
        /* both coefficients from one call, sigma_t their sum; one that is
           not wanted reads as zero, as where it has its own callback */
        if (!(want_sa || want_ss || want_st) || c->status != HRM_OK) return 0;
        m->sigma(m->user, s, sa, ss);
        hrm__check(c, sa, 1);
        hrm__check(c, ss, 1);
        if (end >= 0 && both) hrm__end_keep(c, end, sa, ss);
        for (i = 0; i < HRM__CH; ++i) {
            if (want_st) st[i] = sa[i] + ss[i];
            if (!want_sa && !want_st) sa[i] = 0;
            if (!want_ss && !want_st) ss[i] = 0;
        }
        return 1;
    }
    if (m->sigma_a && (want_sa || derive_st) && c->status == HRM_OK) {
        m->sigma_a(m->user, s, sa);
        hrm__check(c, sa, 1);
        called = 1;
    }
    if (m->sigma_s && (want_ss || derive_st) && c->status == HRM_OK) {
        m->sigma_s(m->user, s, ss);
        hrm__check(c, ss, 1);
        called = 1;
    }
    if (end >= 0 && both) hrm__end_keep(c, end, sa, ss); /* (both called, or absent) */
    if (want_st && m->sigma_t) {
        if (c->status == HRM_OK) {
            m->sigma_t(m->user, s, st);
            hrm__check(c, st, 1);
            called = 1;
        }
    } else if (want_st) {
        for (i = 0; i < HRM__CH; ++i) st[i] = sa[i] + ss[i];
    }
    return called;
}

static HRM_DEVICE hrm_real hrm__abscissa(const hrm__ctx *c, hrm_real off)
{
    hrm_real s = c->t0 + off;
    return s < c->t1 ? s : c->t1; /* t0 + (t1 - t0) may round past t1 */
}

/* The transmittance callback Tr(t0, s), validated and counted: within
   [0, 1], and not rising along the ray against its previous call (beyond
   the rounding of a closed form: 64 epsilons of max(1, tau) relative).
   Returns whether the callback was called (not after an error). */
static HRM_DEVICE HRM__CALL int hrm__tr_call(hrm__ctx *c, hrm_real s, hrm_real tr[HRM__CH])
{
    hrm_real tiny = HRM__TINY;
    int i, far = s > c->tr_s;
    if (c->status != HRM_OK) {
        hrm__fill(tr, HRM__CH, 1);
        return 0;
    }
    c->m->transmittance(c->m->user, c->t0, s, tr);
    hrm__check(c, tr, 2);
    c->stats.medium_evals++;
    for (i = 0; i < HRM__CH && c->status == HRM_OK && c->tr_have && s != c->tr_s; ++i) {
        hrm_real near = far ? c->tr_v[i] : tr[i], beyond = far ? tr[i] : c->tr_v[i];
        /* (the logarithm only where it rose at all) */
        if (beyond > near + tiny &&
            beyond > near + 64 * HRM__EPS * near * (1 - HRM_LOG(near)) + tiny) {
            c->status = HRM_ERR_CALLBACK_VALUE;
            hrm__fill(tr, HRM__CH, 1);
        }
    }
    c->tr_have = 1;
    c->tr_s = s;
    memcpy(c->tr_v, tr, sizeof c->tr_v);
    return 1;
}

/* A sample within 64 ulps of a breakpoint that ends the current piece (or
   past it) is taken 64 ulps inside: each side of a jump is sampled on its
   own side, even where the warp puts the piece's end node an ulp or two
   off the breakpoint, or the breakpoint is some ulps off the true edge (a
   host's shadow test and its breakpoint: 18 ulps apart in make render's
   shafts). */
static HRM_DEVICE hrm_real hrm__inside(hrm_real s, int dir)
{
    hrm_real tiny = HRM__TINY;
    return s + (hrm_real)dir * (64 * HRM__EPS * HRM_FABS(s) + tiny);
}

/* Never outside the ray: a jump within 64 ulps of t0 put a piece's inner
   end, moved inside it, before t0. */
static HRM_DEVICE hrm_real hrm__in_ray(const hrm__ctx *c, hrm_real s)
{
    return s < c->t0 ? c->t0 : s > c->t1 ? c->t1 : s;
}

static HRM_DEVICE hrm_real hrm__side(const hrm__ctx *c, hrm_real s)
{
    hrm_real lo, hi, s_lo, s_hi;
    if (c->o_lo == -HRM__R(HUGE_VAL) && c->o_hi == HRM__R(HUGE_VAL)) return s;
    s_lo = c->t0 + c->o_lo;
    s_hi = c->t0 + c->o_hi;
    lo = c->o_lo == -HRM__R(HUGE_VAL) ? s_lo : hrm__inside(s_lo, 1);
    hi = c->o_hi == HRM__R(HUGE_VAL) ? s_hi : hrm__inside(s_hi, -1);
    if (lo > hi) s = s_lo / 2 + s_hi / 2; /* a piece of a few ulps */
    else s = s < lo ? lo : s > hi ? hi : s;
    return hrm__in_ray(c, s);
}

/* Whether an offset is one of the breakpoints'. */
static HRM_DEVICE int hrm__is_break(const hrm__ctx *c, hrm_real off)
{
    int k;
    for (k = 0; k < c->nbrk; ++k)
        if (c->brk_off[k] == off) return 1;
    return 0;
}

/* splitmix64 (Steele, Lea, Flood 2014): the generator's state lives in the
   call, so results depend on options.seed alone. */
static HRM_DEVICE uint64_t hrm__next(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1), exactly representable in hrm_real (never rounds to 1). */
static HRM_DEVICE hrm_real hrm__uniform(uint64_t *state)
{
    uint64_t x = hrm__next(state);
    if (HRM__IS_FLOAT) return (hrm_real)((float)(x >> 40) * (1.0f / 16777216.0f));
    return (hrm_real)((double)(x >> 11) * (1.0 / 9007199254740992.0));
}

/* ---------------------------------------------------------------------- */
/* The transmittance layer                                                 */
/* ---------------------------------------------------------------------- */

/* Optical depth is integrated in t, never in a warped variable: a warp's
   dt/du is nearly singular at its ends, and even a constant sigma_t comes
   out wrong there. In the decoupled mode (the default) sigma_t is sampled
   at its own abscissae, apart from the source samples (Kulla and Fajardo
   2012; Munoz 2014 s.6), on panels [a, b] in t that march along the ray.
   On each panel sigma_t is interpolated at the Chebyshev-Lobatto points of
   degree 8, then 16 (nested: the 9 points of degree 8 are among the 17 of
   degree 16, and a panel shares its first point with its neighbour), and
   the interpolant's antiderivative gives tau anywhere in the panel at the
   interpolant's accuracy (Clenshaw-Curtis; Trefethen, "Approximation
   Theory and Approximation Practice", 2013, ch. 3 and 19). The size of the
   last two coefficients, times the panel's length, estimates the error of
   the panel's tau; a panel is accepted when that error, weighted by the
   transmittance at its start, is at most tau_tol times the panel's own
   increment of tau or times 1/64, the larger. Summed over the panels, the
   error of L that tau causes then stays below tau_tol (1 + K/64) times
   sup(S/sigma_t) (1 - Tr) (sum of tol * max(dtau, 1/64) * exp(-tau) <= tol
   (1 + K/64), K panels thinner than 1/64), L's own scale unless the
   source peaks where Tr is far below it (a light at optical depth 20 or
   more in a varying medium: 8% off at rtol 1e-2 with HRM_OK, an
   independent check's case; under the equiangular warp the weight is at
   least an eighth of Tr relative to the light's foot, hrm__tau_fit), and
   no effort goes where Tr is already 0. Without
   the floor a kink of sigma (error ~ h^2 against an increment ~ h) forced
   panels down to tau_tol of the ray, and past HRM_TAU_PANELS of them the
   layer marched again from t0 at every query behind its window. Panels that fail are shrunk;
   the next panel's length follows the last one's error.

   The layer keeps a table of the panels it accepted (their ends, degree
   and tau at the start), so that a query behind the current panel (a
   rejected Runge-Kutta step, a Gauss-Kronrod interval bisected anywhere)
   rebuilds that panel from the same abscissae, to the same values, instead
   of marching again. Eight panels' coefficients are cached. Past the
   table (a ray crossing many kinks of sigma), a query behind its window
   marches again from the nearest checkpoint (hrm__tau_checkpoint), to the
   same panels: sigma = 0.3 max(0, sin 10 t) over 20 (63 kinks, 600
   panels), global Gauss-Kronrod at rtol 1e-5, 442 474 medium calls, from
   1.26e6 when it marched again from t0. */

#ifndef HRM_TAU_PANELS
#define HRM_TAU_PANELS 128 /* panels remembered; older ones are rebuilt by
                              marching again from a checkpoint */
#endif
HRM__STATIC_ASSERT(tau_panels_16_to_65536, HRM_TAU_PANELS >= 16 && HRM_TAU_PANELS <= 65536);
/* Without a workspace the table is 32 panels (on the stack): the panels
   past it are marched again from a checkpoint when asked for, to the same
   values, so that answers do not depend on the table's size, only the
   medium evaluations do. */
#define HRM__TAU_STACK (HRM_TAU_PANELS < 32 ? HRM_TAU_PANELS : 32)
#define HRM__CHEB 16       /* the highest degree of a panel */
#define HRM__TCACHE 8      /* panels whose coefficients are kept */
/* A fixed-step rule asks for tau at nodes in increasing t: its frame's
   layer keeps 4 panels and the coefficients of 2 (the panel asked for
   and the one marched after it), 4 checkpoints and, unless it scans the
   medium (options.find_jumps 1), no scan storage: 7.9 KiB less at 3
   channels than an adaptive method's (make bench's and make render's
   lookups the same as with 8 panels and 16 checkpoints). A pair
   steps forward too, but retries a rejected step and starts again where
   the medium check found a miss: 8 panels, 8 panels' coefficients (with
   4, make bench's hifreq rows took 10% more lookups). */
#define HRM__TAU_STACK_FIXED 8 /* a pair's */
#define HRM__TAU_STACK_RULE 4  /* a fixed-step rule's */
#define HRM__TCACHE_FIXED 2
#define HRM__TMEM 32       /* samples of rejected panels remembered */
#define HRM__TCHECK 16     /* checkpoints of the march */
#define HRM__TCHECK_FIXED 4 /* in a fixed-step rule's frame */
#define HRM__SCAN 32       /* the medium scan's intervals (hrm__scan_medium) */
#define HRM__SCAN_Q 8      /* its panels at most (hrm__scan_layout) */
/* The widest gap between a panel's degree-8 points, over its width
   (sin(pi/8)/2: beside its centre). */
#define HRM__SCAN_GAP HRM__R(0.19134171618254488)
#define HRM__SCAN_MAX 4096 /* the scan's points at most (medium.feature) */

typedef struct hrm__tpanel {
    hrm_real a, b;          /* offsets from t0 */
    hrm_real tau_a[HRM__CH], tau_b[HRM__CH];
    hrm_real smax[HRM__CH]; /* the largest sigma_t it sampled */
    int deg;                /* 8 or 16 */
} hrm__tpanel;

typedef struct hrm__tcoef {
    long id;                /* the panel's index, -1: empty */
    hrm_real e[HRM__CHEB + 2][HRM__CH]; /* antiderivative's coefficients,
                                            channels innermost */
} hrm__tcoef;

/* Where the march can start again: the state before panel id, taken
   where no remembered sample lay ahead (hrm__tau_march), so that marching
   from it gives the same panels, to the same values, as the first time. */
typedef struct hrm__tcheck {
    long id;
    hrm_real a, h;          /* panel id's start and trial length */
    hrm_real tau[HRM__CH], sig[HRM__CH]; /* tau and sigma_t at a */
} hrm__tcheck;

/* The medium scan's panels (hrm__scan_layout: hrm__tau.scan_q of them,
   ends b) and its samples at their degree-8 points (hrm__scan_at), where
   it took them (have; at a breakpoint the left side, and the right side
   at a panel's start in a, ha): the panels that the march tries first
   (hrm__tau_scan_panel). Held by the layers of the methods that scan
   (adaptive ones, and the fixed-step rules with options.find_jumps 1). */
typedef struct hrm__tscan {
    hrm_real b[HRM__SCAN_Q + 1];
    hrm_real s[8 * HRM__SCAN_Q + 1][HRM__CH];
    hrm_real a[HRM__SCAN_Q][HRM__CH];
    char have[8 * HRM__SCAN_Q + 1], ha[HRM__SCAN_Q];
} hrm__tscan;

typedef struct hrm__tau {
    hrm__tpanel *tab;       /* panel i at tab[i % ntab] (HRM_TAU_PANELS in a
                               workspace, HRM__TAU_STACK, _FIXED or _RULE
                               in a frame) */
    long ntab;
    long count;             /* panels accepted so far */
    long base;              /* the first panel marched since the last start */
    hrm_real base_a, base_tau[HRM__CH]; /* where that march started */
    hrm__tcheck *cp;        /* ascending in id, cpcap at most (HRM__TCHECK,
                               fewer in a fixed-step rule's frame) */
    int ncp, cpcap;
    long cp_every;          /* a checkpoint every cp_every panels */
    hrm_real end;           /* the farthest offset that may be asked for */
    hrm_real tol;
    hrm_real next_h;        /* the next panel's trial length */
    hrm_real sig_b[HRM__CH];/* sigma_t at the last panel's end */
    hrm_real sig0[HRM__CH]; /* sigma_t at t0 */
    hrm__tcoef *cache;      /* ncache entries (HRM__TCACHE, or
                               HRM__TCACHE_FIXED in a fixed-step rule's frame) */
    int ncache;
    int last;               /* the cache entry used last */
    int next;               /* the entry to fill next (round robin) */
    /* Samples a panel over which must reproduce them, ascending in x:
       what a rejected panel saw ahead of the march (its largest and
       smallest sigma_t), so that a thin feature once seen is not lost
       when the panel that saw it is split, dropped once the march is
       past; and what the medium scan or a missed node taught (mem_keep),
       kept, so that a march begun again from t0 or a checkpoint sees all
       that the first one saw and repeats it. */
    int nmem;
    hrm_real mem_x[HRM__TMEM], mem_s[HRM__TMEM][HRM__CH];
    char mem_keep[HRM__TMEM];
    long hit;               /* the panel of the last hrm__tau_at */
    hrm_real foot;          /* the equiangular light's foot (offset; -1:
                               none): a panel weighs its error by Tr
                               relative to the foot's too (at most 1) */
    hrm_real tau_foot[HRM__CH]; /* tau at the start of the panel holding it */
    /* The medium scan's panels kept (scan_q of them, 0 without scan
       storage): the panels that the march tries first. */
    int scan_q;
    hrm__tscan *scan;
} hrm__tau;
/* its scan storage and checkpoints after it, then its cache and table */
#define HRM__TAU_HEAD                                                             \
    ((sizeof(hrm__tau) + sizeof(hrm__tscan) + sizeof(hrm__tcheck) * HRM__TCHECK + 15) / 16 * 16)
#define HRM__TAU_CACHE_BYTES ((sizeof(hrm__tcoef) * HRM__TCACHE + 15) / 16 * 16)

/* sigma_t at offset off from t0: one medium evaluation. */
static HRM_DEVICE void hrm__sigma_t_at(hrm__ctx *c, hrm_real off, int side, hrm_real st[HRM__CH])
{
    hrm_real sa[HRM__CH], ss[HRM__CH], s = hrm__abscissa(c, off);
    /* a panel's end at a breakpoint: sigma_t on the panel's side */
    if (side && hrm__is_break(c, off)) s = hrm__in_ray(c, hrm__inside(s, side));
    c->stats.medium_evals += hrm__coeffs(c, s, 0, 0, 1, sa, ss, st);
}

/* The integral over [x[i], x[i + 1]] of the polynomial through the
   stream's points a..b (two-point Gauss-Legendre: exact to degree 3),
   per channel, never negative (sigma_t >= 0); 0 where two of the points
   lie closer than a sixteenth of the interval (no ill-conditioned
   stencil: the caller takes fewer). */
static HRM_DEVICE HRM__CALL int hrm__stream_int(const hrm__stream *S, int i, int a, int b, hrm_real out[HRM__CH])
{
    static const hrm_real r = HRM__R(0.28867513459481288225); /* 1 / (2 sqrt 3) */
    hrm_real h = S->x[i + 1] - S->x[i], w[4], g, sum;
    int j, l, q, ch;
    if (!(h > 0)) {
        hrm__fill(out, HRM__CH, 0);
        return 1;
    }
    for (j = a; j < b; ++j)
        if (S->x[j + 1] - S->x[j] < h / 16) return 0;
    for (j = a; j <= b; ++j) w[j - a] = 0;
    for (q = 0; q < 2; ++q) {
        g = S->x[i] + h * (q ? HRM__R(0.5) + r : HRM__R(0.5) - r);
        for (j = a; j <= b; ++j) {
            hrm_real lj = 1;
            for (l = a; l <= b; ++l)
                if (l != j) lj *= (g - S->x[l]) / (S->x[j] - S->x[l]);
            w[j - a] += lj;
        }
    }
    for (ch = 0; ch < HRM__CH; ++ch) {
        for (j = a, sum = 0; j <= b; ++j) sum += w[j - a] * S->f[j][ch];
        out[ch] = sum > 0 ? sum * h / 2 : 0;
    }
    return 1;
}

/* The integral over the stream's interval i (of points 0..m) by the
   widest well-conditioned stencil around it: a point each side where
   there are (centred), else what there is; the last interval, whose
   right neighbour has not come, only from points before it that spread
   over a quarter of it (no extrapolation from a cluster: a warp's nodes
   crowd near the light). */
static HRM_DEVICE void hrm__stream_interval(const hrm__stream *S, int i, int m, hrm_real d[HRM__CH])
{
    hrm_real h = S->x[i + 1] - S->x[i];
    if (i + 1 < m) {
        int lo = i >= 1 ? i - 1 : i, hi = i + 2 <= m ? (i == 0 && m >= 3 ? 3 : i + 2) : i + 1;
        if (hrm__stream_int(S, i, lo, hi, d) || hrm__stream_int(S, i, i, hi, d) ||
            hrm__stream_int(S, i, lo, i + 1, d))
            return;
        hrm__stream_int(S, i, i, i + 1, d);
        return;
    }
    {
        int a = i >= 2 && S->x[i] - S->x[i - 2] >= h / 4 ? i - 2
              : i >= 1 && S->x[i] - S->x[i - 1] >= h / 4 ? i - 1 : i;
        while (!hrm__stream_int(S, i, a, m, d)) ++a;
    }
}

/* The stream's last point's index in its window. */
static HRM_DEVICE int hrm__stream_last(const hrm__stream *S) { return (S->n < 4 ? S->n : 4) - 1; }

/* The stream's next point, offset x beyond the last, sigma_t f. An
   interval is integrated for good (tc, up to point ci) once a point
   beyond its right end has come (the first of a piece: two), by the
   cubic centred on it; tau at x adds what is not yet, the last interval
   one-sided: its error is provisional, never carried along the ray. */
static HRM_DEVICE HRM__CALL void hrm__stream_push(hrm__stream *S, hrm_real x, const hrm_real f[HRM__CH])
{
    hrm_real d[HRM__CH];
    int m = S->n < 4 ? S->n : 4, j, ch, i;
    if (m == 4) {
        for (j = 0; j < 3; ++j) {
            S->x[j] = S->x[j + 1];
            memcpy(S->f[j], S->f[j + 1], sizeof S->f[j]);
        }
        S->ci--;
        m = 3;
    }
    S->x[m] = x;
    memcpy(S->f[m], f, sizeof S->f[m]);
    S->n++;
    if (m == 0) {
        memcpy(S->tc, S->tau, sizeof S->tc);
        S->ci = 0;
        return;
    }
    while (S->ci <= m - 2 && (S->ci >= 1 || m >= 3)) {
        hrm__stream_interval(S, S->ci, m, d);
        for (ch = 0; ch < HRM__CH; ++ch) S->tc[ch] += d[ch];
        S->ci++;
    }
    memcpy(S->tau, S->tc, sizeof S->tau);
    for (i = S->ci; i < m; ++i) {
        hrm__stream_interval(S, i, m, d);
        for (ch = 0; ch < HRM__CH; ++ch) S->tau[ch] += d[ch];
    }
}

/* The pieces of width at most 1 that q > 0 (not above LONG_MAX) takes:
   its ceiling. */
static HRM_DEVICE long hrm__pieces(hrm_real q)
{
    long n = (long)q;
    return (hrm_real)n < q ? n + 1 : n;
}

/* Advance the stream to offset x: extra samples, evenly spaced, where
   the gap from the last point is wider than the stream's level (a user
   warp: the gap's share by length of the points left), then x itself
   (sigma_t f there, or NULL: sampled, on side `side` of a breakpoint).
   The first point of a piece is its start (sampled on its side). */
static HRM_DEVICE HRM__CALL void hrm__stream_to(hrm__ctx *c, hrm_real x, int side, const hrm_real *f)
{
    hrm__stream *S = &c->sm;
    hrm_real st[HRM__CH], last;
    long k, j;
    /* (a first node within rounding of the piece's start is its start:
       both are sampled 64 ulps inside, at one t) */
    if (S->n == 0 && x - S->start > 4 * HRM__EPS * HRM_FABS(x)) {
        hrm__sigma_t_at(c, S->start, 1, st);
        hrm__stream_push(S, S->start, st);
    }
    if (c->status != HRM_OK) return;
    if (S->n == 0) {
        /* the piece's first point */
        if (!f) {
            hrm__sigma_t_at(c, x, side, st);
            f = st;
        }
        hrm__stream_push(S, x, f);
        return;
    }
    last = S->x[hrm__stream_last(S)];
    if (!(x > last)) return;
    if (x - last <= 4 * HRM__EPS * HRM_FABS(x)) {
        /* the same offset but for rounding: its value, no interval */
        if (f) memcpy(S->f[hrm__stream_last(S)], f, sizeof S->f[0]);
        return;
    }
    /* the gap cut into pieces no wider than the level, while points are
       left */
    k = 0;
    if (S->left > 0 && S->level > 0 && x - last > S->level) {
        hrm_real q = (x - last) / S->level;
        k = q < (hrm_real)S->left ? hrm__pieces(q) - 1 : S->left;
    } else if (S->left > 0 && !(S->level > 0) && c->off_end > last) {
        k = (long)((x - last) / (c->off_end - last) * (hrm_real)S->left);
    }
    if (k > S->left) k = S->left;
    S->left -= k;
    for (j = 1; j <= k && c->status == HRM_OK; ++j) {
        hrm_real xe = last + (x - last) * (hrm_real)j / (hrm_real)(k + 1);
        if (!(xe > S->x[hrm__stream_last(S)] && xe < x)) continue; /* (rounding) */
        hrm__sigma_t_at(c, xe, 0, st);
        hrm__stream_push(S, xe, st);
    }
    if (!f) {
        hrm__sigma_t_at(c, x, side, st);
        f = st;
    }
    hrm__stream_push(S, x, f);
}

/* A new piece of the ray from offset off (a breakpoint): the stream
   reaches it on the left side, and starts again (tau kept) on the
   right. */
static HRM_DEVICE void hrm__stream_piece(hrm__ctx *c, hrm_real off)
{
    if (c->sm.n > 0) hrm__stream_to(c, off, -1, NULL);
    c->sm.n = 0;
    c->sm.start = off;
}

/* Chebyshev coefficients of sigma_t on a panel from its samples f at the
   degree-n Lobatto points (f[j * 16 / n], ascending in t), integrated into
   the antiderivative that vanishes at the panel's start: e[0..n+1]. Also
   the panel's increment (in units of half its length) and the error
   estimate |d_(n-1)| + |d_n| (in units of sigma_t). */
static HRM_DEVICE HRM__CALL void hrm__cheb_fit(const hrm_real f[HRM__CHEB + 1], int n,
                          hrm_real e[HRM__CHEB + 2][HRM__CH], int ch,
                          hrm_real *incr, hrm_real *err, hrm_real d[HRM__CHEB + 3])
{
    hrm_real sum = 0, alt = 0;
    int j, k, step = HRM__CHEB / n;
    /* the DCT-I: T_k at the degree-n points are row k, every step-th
       column, the ends halved; rows below n four at a time (their sums
       independent chains), the rest one at a time */
    for (k = 0; k + 4 <= n; k += 4) {
        const hrm_real *T0 = hrm__cheb_T[k], *T1 = hrm__cheb_T[k + 1], *T2 = hrm__cheb_T[k + 2],
                       *T3 = hrm__cheb_T[k + 3];
        hrm_real a0 = (f[0] * T0[0] + f[HRM__CHEB] * T0[HRM__CHEB]) / 2,
                 a1 = (f[0] * T1[0] + f[HRM__CHEB] * T1[HRM__CHEB]) / 2,
                 a2 = (f[0] * T2[0] + f[HRM__CHEB] * T2[HRM__CHEB]) / 2,
                 a3 = (f[0] * T3[0] + f[HRM__CHEB] * T3[HRM__CHEB]) / 2, w = (hrm_real)2 / (hrm_real)n;
        for (j = step; j < HRM__CHEB; j += step) {
            a0 += f[j] * T0[j];
            a1 += f[j] * T1[j];
            a2 += f[j] * T2[j];
            a3 += f[j] * T3[j];
        }
        d[k] = k == 0 ? a0 * w / 2 : a0 * w;
        d[k + 1] = a1 * w;
        d[k + 2] = a2 * w;
        d[k + 3] = a3 * w;
    }
    for (; k <= n; ++k) {
        const hrm_real *T = hrm__cheb_T[k];
        hrm_real a = (f[0] * T[0] + f[HRM__CHEB] * T[HRM__CHEB]) / 2;
        for (j = step; j < HRM__CHEB; j += step) a += f[j] * T[j];
        a *= (hrm_real)2 / (hrm_real)n;
        d[k] = (k == 0 || k == n) ? a / 2 : a;
    }
    d[n + 1] = d[n + 2] = 0;
    /* the integral of T_0 is T_1, of T_1 is T_2 / 4, of T_k is
       T_(k+1) / (2(k+1)) - T_(k-1) / (2(k-1)) */
    e[1][ch] = d[0] - d[2] / 2;
    for (k = 2; k <= n + 1; ++k) e[k][ch] = (d[k - 1] - d[k + 1]) / (hrm_real)(2 * k);
    for (k = 1; k <= n + 1; ++k) {
        sum += e[k][ch];
        alt += (k % 2) ? -e[k][ch] : e[k][ch];
    }
    e[0][ch] = -alt;         /* F(-1) = 0 */
    *incr = e[0][ch] + sum;  /* F(1) */
    *err = HRM_FABS(d[n - 1]) + HRM_FABS(d[n]);
}

/* F(xi) = sum e_k T_k(xi) in every channel by Clenshaw's recurrence, two
   terms a step (b_(k-1) = e_(k-1) + x2 e_k + (x2^2 - 1) b_(k+1) - x2
   b_(k+2) alongside b_k: half the chain of dependent operations), up to
   four channels at a time in scalars that stay in registers. This is the
   layer's cost a sample. */
#define HRM__CLENSHAW2(j, u1, u2)                                             \
    do {                                                                      \
        hrm_real bk_ = ek[j] + x2 * u1 - u2;                                  \
        u1 = ek1[j] + x2 * ek[j] + q * u1 - x2 * u2;                          \
        u2 = bk_;                                                             \
    } while (0)

static HRM_DEVICE void hrm__cheb_eval(const hrm_real e[HRM__CHEB + 2][HRM__CH], int n, hrm_real xi,
                           hrm_real F[HRM__CH])
{
    hrm_real x2 = 2 * xi, q = x2 * x2 - 1;
    int k, i0;
    for (i0 = 0; i0 < HRM__CH; i0 += 4) {
        int m = HRM__CH - i0 < 4 ? HRM__CH - i0 : 4;
        hrm_real a1 = 0, a2 = 0, b1 = 0, b2 = 0, c1 = 0, c2 = 0, d1 = 0, d2 = 0;
        k = n + 1;
        if (k % 2) { /* an odd count of terms: one single step first */
            a1 = e[k][i0];
            if (m > 1) b1 = e[k][i0 + 1];
            if (m > 2) c1 = e[k][i0 + 2];
            if (m > 3) d1 = e[k][i0 + 3];
            --k;
        }
        for (; k >= 2; k -= 2) {
            const hrm_real *ek = e[k] + i0, *ek1 = e[k - 1] + i0;
            HRM__CLENSHAW2(0, a1, a2);
            if (m > 1) HRM__CLENSHAW2(1, b1, b2);
            if (m > 2) HRM__CLENSHAW2(2, c1, c2);
            if (m > 3) HRM__CLENSHAW2(3, d1, d2);
        }
        F[i0] = e[0][i0] + xi * a1 - a2;
        if (m > 1) F[i0 + 1] = e[0][i0 + 1] + xi * b1 - b2;
        if (m > 2) F[i0 + 2] = e[0][i0 + 2] + xi * c1 - c2;
        if (m > 3) F[i0 + 3] = e[0][i0 + 3] + xi * d1 - d2;
    }
}
#undef HRM__CLENSHAW2

/* F'(xi) = sum k e_k U_(k-1)(xi) in every channel (Clenshaw's recurrence
   for the Chebyshev polynomials of the second kind): the interpolant of
   sigma_t itself. */
static HRM_DEVICE void hrm__cheb_deriv(const hrm_real e[HRM__CHEB + 2][HRM__CH], int n, hrm_real xi,
                            hrm_real D[HRM__CH])
{
    hrm_real x2 = 2 * xi;
    int k, i0;
    /* four channels side by side, in scalars: independent chains in
       flight together */
    for (i0 = 0; i0 < HRM__CH; i0 += 4) {
        int m = HRM__CH - i0 < 4 ? HRM__CH - i0 : 4;
        hrm_real a1 = 0, a2 = 0, b1 = 0, b2 = 0, c1 = 0, c2 = 0, d1 = 0, d2 = 0, kk = (hrm_real)(n + 1), u;
        for (k = n + 1; k >= 1; --k, kk -= 1) {
            const hrm_real *ek = e[k] + i0;
            u = kk * ek[0] + x2 * a1 - a2, a2 = a1, a1 = u;
            if (m > 1) u = kk * ek[1] + x2 * b1 - b2, b2 = b1, b1 = u;
            if (m > 2) u = kk * ek[2] + x2 * c1 - c2, c2 = c1, c1 = u;
            if (m > 3) u = kk * ek[3] + x2 * d1 - d2, d2 = d1, d1 = u;
        }
        D[i0] = a1;
        if (m > 1) D[i0 + 1] = b1;
        if (m > 2) D[i0 + 2] = c1;
        if (m > 3) D[i0 + 3] = d1;
    }
}

/* The sample positions of a panel: a + (b - a) (1 - cos(j pi / 16)) / 2. */
static HRM_DEVICE hrm_real hrm__cheb_at(hrm_real a, hrm_real b, int j16)
{
    /* (1 - cos(j pi / 16)) / 2 = (1 + T_1 at point j) / 2 */
    return j16 == 16 ? b : a + (b - a) * ((1 + hrm__cheb_T[1][j16]) / 2);
}

/* The medium scan's point k: of its panels' (nq of them, ends b) the
   Lobatto points of degree 8, which the transmittance layer's march tries
   first (hrm__tau_scan_panel); without panels (nq 0), n evenly spaced
   intervals of [0, end]. */
static HRM_DEVICE hrm_real hrm__scan_at(const hrm_real *b, int nq, hrm_real end, int k, int n)
{
    if (!nq) return k >= n ? end : end * ((hrm_real)k / (hrm_real)n);
    if (k >= 8 * nq) return b[nq];
    return hrm__cheb_at(b[k / 8], b[k / 8 + 1], 2 * (k % 8));
}

/* Sample the panel [a, b] at degree n given f[.][0] (and, when have8, the
   degree-8 samples), fit every channel: dtau its increments, err its
   error estimates, worst the largest error over its share of tol. */
static HRM_DEVICE HRM__CALL hrm_real hrm__tau_fit(hrm__ctx *c, const hrm__tau *L, hrm_real a, hrm_real b, int n,
                             int have8, const hrm_real *tau_a,
                             hrm_real f[HRM__CH][HRM__CHEB + 1], hrm__tcoef *co,
                             hrm_real dtau[HRM__CH])
{
    hrm_real v[HRM__CH], worst = 0;
    int j, i, k, step = HRM__CHEB / n;
    for (j = step; j <= HRM__CHEB; j += step) {
        if (have8 && j % 2 == 0) continue;
        hrm__sigma_t_at(c, hrm__cheb_at(a, b, j), j == HRM__CHEB ? -1 : 0, v);
        for (i = 0; i < HRM__CH; ++i) f[i][j] = v[i];
    }
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real err, big = 0, allow, w, d[HRM__CHEB + 3];
        hrm__cheb_fit(f[i], n, co->e, i, &dtau[i], &err, d);
        /* a remembered sample inside must be reproduced: its miss, per
           unit length, counts as the interpolant's error */
        for (k = 0; k < L->nmem; ++k) {
            hrm_real x = L->mem_x[k], xi, b1 = 0, b2 = 0, b0, miss;
            int kk;
            if (!(x > a && x < b)) continue;
            xi = 2 * (x - a) / (b - a) - 1;
            for (kk = n; kk >= 1; --kk) {
                b0 = d[kk] + 2 * xi * b1 - b2;
                b2 = b1;
                b1 = b0;
            }
            miss = HRM_FABS(d[0] + xi * b1 - b2 - L->mem_s[k][i]);
            if (miss > err) err = miss;
        }
        dtau[i] *= (b - a) / 2;
        if (dtau[i] < 0) dtau[i] = 0;
        for (j = 0; j <= HRM__CHEB; j += step) big = f[i][j] > big ? f[i][j] : big;
        /* round-off in the coefficients is a few epsilons of sigma_t */
        allow = L->tol * (dtau[i] > HRM__R(1.0 / 64) ? dtau[i] : HRM__R(1.0 / 64)) +
                16 * HRM__EPS * (b - a) * big;
        err *= b - a;
        if (err > 0) {
            /* an error where Tr is 0 costs nothing; but an equiangular
               light's part of L lies at its foot, where Tr may be far
               lower (optical depth 43 to it in a varying medium: L 8%
               off with HRM_OK at rtol 1e-2): Tr relative to the foot's,
               at most 1, counts too, over 8 (tau_tol = rtol / 8), so
               that a light within depth ln 8 of the panel changes
               nothing */
            w = HRM_EXP(-tau_a[i]);
            if (L->foot >= 0) {
                hrm_real rel = a < L->foot ? 1 : HRM_EXP(-(tau_a[i] - L->tau_foot[i]));
                if (rel / 8 > w) w = rel / 8;
            }
            err *= w;
            if (err > 0) {
                hrm_real r = allow > 0 ? err / allow : HRM__R(1e30);
                worst = r > worst ? r : worst;
            }
        }
    }
    return worst;
}

static HRM_DEVICE void hrm__forget(hrm__tau *L)
{
    int k;
    for (k = 0; k < L->ncache; ++k) L->cache[k].id = -1;
    L->last = L->next = 0;
}

/* A cache entry for a new panel's coefficients. */
static HRM_DEVICE hrm__tcoef *hrm__tcache_slot(hrm__tau *L)
{
    L->last = L->next;
    L->next = (L->next + 1) % L->ncache;
    return &L->cache[L->last];
}

/* The remembered samples of rejected panels at or before b dropped
   (those the layer was taught stay). */
static HRM_DEVICE void hrm__tau_drop(hrm__tau *L, hrm_real b)
{
    int i, n = 0;
    for (i = 0; i < L->nmem; ++i) {
        if (!L->mem_keep[i] && L->mem_x[i] <= b) continue;
        L->mem_x[n] = L->mem_x[i];
        memcpy(L->mem_s[n], L->mem_s[i], sizeof L->mem_s[0]);
        L->mem_keep[n++] = L->mem_keep[i];
    }
    L->nmem = n;
}

/* The layer built again from t0 (new breakpoints, or a sample it missed),
   as a new one would be with what it was taught. */
static HRM_DEVICE void hrm__tau_rebuild(hrm__tau *L)
{
    L->count = 0;
    L->base = 0;
    L->ncp = 0;
    L->cp_every = L->ntab / 4;
    L->next_h = 0;
    L->hit = 0; /* (read, guarded, before the first hrm__tau_at: UB on an
                   uninitialized stack) */
    hrm__tau_drop(L, HRM__R(HUGE_VAL));
    hrm__forget(L);
}

static HRM_DEVICE void hrm__tau_init(hrm__tau *L, hrm_real end, hrm_real tol)
{
    L->end = end;
    L->tol = tol;
    L->nmem = 0;
    L->scan_q = 0;
    L->foot = -1;
    hrm__tau_rebuild(L);
}

/* The layer of a ray cut short at end: the scan's whole panels and what
   it taught up to there kept. */
static HRM_DEVICE void hrm__tau_cut(hrm__tau *L, hrm_real end)
{
    int q = 0;
    while (q < L->scan_q && L->scan->b[q + 1] <= end * (1 + 4 * HRM__EPS)) ++q;
    L->scan_q = q;
    if (q && L->scan->b[q] > end) L->scan->b[q] = end; /* (rounding) */
    while (L->nmem > 0 && L->mem_x[L->nmem - 1] >= end) L->nmem--;
    L->end = end;
    hrm__tau_rebuild(L);
}

/* A sample the layer must reproduce (sorted, while room is left); keep:
   taught, never dropped. */
static HRM_DEVICE void hrm__tau_insert(hrm__tau *L, hrm_real x, const hrm_real s[HRM__CH], int keep)
{
    int at, i;
    for (at = 0; at < L->nmem && L->mem_x[at] < x; ++at) {}
    if (at < L->nmem && L->mem_x[at] == x) {
        L->mem_keep[at] = (char)(L->mem_keep[at] | keep);
        return;
    }
    if (L->nmem == HRM__TMEM) return;
    for (i = L->nmem; i > at; --i) { /* memmove is host-only in CUDA */
        L->mem_x[i] = L->mem_x[i - 1];
        memcpy(L->mem_s[i], L->mem_s[i - 1], sizeof L->mem_s[0]);
        L->mem_keep[i] = L->mem_keep[i - 1];
    }
    L->mem_x[at] = x;
    memcpy(L->mem_s[at], s, sizeof L->mem_s[0]);
    L->mem_keep[at] = (char)keep;
    L->nmem++;
}

/* What the medium scan saw, or a node the layer missed: kept. */
static HRM_DEVICE void hrm__tau_learn(hrm__tau *L, hrm_real x, const hrm_real s[HRM__CH])
{
    hrm__tau_insert(L, x, s, 1);
}

/* Whether x is a sample the layer was taught (hrm__tau_learn). */
static HRM_DEVICE int hrm__tau_taught(const hrm__tau *L, hrm_real x)
{
    int k;
    for (k = 0; k < L->nmem && L->mem_x[k] < x; ++k) {}
    return k < L->nmem && L->mem_x[k] == x && L->mem_keep[k];
}

/* Remember the largest and the smallest sigma_t (summed over channels)
   that a rejected panel [a, b] sampled inside it: a thin layer or a hole
   it saw. */
static HRM_DEVICE void hrm__tau_remember(hrm__tau *L, hrm_real a, hrm_real b, int n,
                              hrm_real f[HRM__CH][HRM__CHEB + 1])
{
    int j, i, k, pick[2] = {-1, -1}, step = HRM__CHEB / n;
    hrm_real hi = -1, lo = -1;
    for (j = step; j < HRM__CHEB; j += step) {
        hrm_real sum = 0;
        for (i = 0; i < HRM__CH; ++i) sum += f[i][j];
        if (pick[0] < 0 || sum > hi) { hi = sum; pick[0] = j; }
        if (pick[1] < 0 || sum < lo) { lo = sum; pick[1] = j; }
    }
    for (k = 0; k < 2; ++k) {
        hrm_real s[HRM__CH];
        if (pick[k] < 0 || (k == 1 && pick[1] == pick[0])) continue;
        for (i = 0; i < HRM__CH; ++i) s[i] = f[i][pick[k]];
        hrm__tau_insert(L, hrm__cheb_at(a, b, pick[k]), s, 0);
    }
}


/* A checkpoint before panel id, which starts at a, taken cp_every panels
   after the last one or at the first chance past that: past the table's
   window a query behind it (the worst-first rules bisect anywhere) marches
   again from the nearest one instead of from t0, and a query ahead of the
   march starts at the farthest one before it. Full, every other one is
   dropped and they are taken half as often. Taken only where no rejected
   panel's sample lies ahead (what the layer was taught stays throughout),
   so that the march from it repeats the first one exactly. */
static HRM_DEVICE void hrm__tau_checkpoint(hrm__tau *L, long id, hrm_real a)
{
    hrm__tcheck *q;
    if (L->ncp == L->cpcap) {
        int k;
        for (k = 0; k < L->cpcap / 2; ++k) L->cp[k] = L->cp[2 * k + 1];
        L->ncp = L->cpcap / 2;
        L->cp_every *= 2;
    }
    q = &L->cp[L->ncp++];
    q->id = id;
    q->a = a;
    q->h = L->next_h;
    memcpy(q->tau, L->tab[(id - 1) % L->ntab].tau_b, sizeof q->tau);
    memcpy(q->sig, L->sig_b, sizeof q->sig);
}

/* The march restarted at checkpoint k. */
static HRM_DEVICE void hrm__tau_from(hrm__tau *L, int k)
{
    const hrm__tcheck *q = &L->cp[k];
    L->count = L->base = q->id;
    L->base_a = q->a;
    memcpy(L->base_tau, q->tau, sizeof L->base_tau);
    L->next_h = q->h;
    memcpy(L->sig_b, q->sig, sizeof L->sig_b);
    hrm__tau_drop(L, HRM__R(HUGE_VAL));
    hrm__forget(L);
}

/* The last checkpoint that starts before off, or -1. */
static HRM_DEVICE int hrm__tau_cp_before(const hrm__tau *L, hrm_real off)
{
    int k = L->ncp - 1;
    while (k >= 0 && !(L->cp[k].a < off)) --k;
    return k;
}

/* The medium scan's panel q that starts at a, where the scan took its
   samples (at a breakpoint, both sides of it) and no breakpoint lies
   inside; else -1. */
static HRM_DEVICE int hrm__tau_scan_panel(const hrm__ctx *c, const hrm__tau *L, hrm_real a)
{
    int q = 0, j, k;
    hrm_real b;
    while (q < L->scan_q && L->scan->b[q] != a) ++q;
    if (q == L->scan_q) return -1;
    b = L->scan->b[q + 1];
    if (b > L->end) return -1;
    /* its start: at a breakpoint the right side's sample */
    if (a > 0 && hrm__is_break(c, a) ? !L->scan->ha[q] : !L->scan->have[8 * q]) return -1;
    for (j = 1; j <= 8; ++j)
        if (!L->scan->have[8 * q + j]) return -1;
    for (k = 0; k < c->nbrk; ++k)
        if (c->brk_off[k] > a && c->brk_off[k] < b) return -1;
    return q;
}

/* The scan's samples of its panel q at the degree-8 points, into
   f[.][0, 2, .., 16] (the start's right side at a breakpoint). */
static HRM_DEVICE void hrm__tau_scan_take(const hrm__ctx *c, const hrm__tau *L, int q,
                               hrm_real f[HRM__CH][HRM__CHEB + 1])
{
    int i, j, right = L->scan->b[q] > 0 && hrm__is_break(c, L->scan->b[q]);
    for (i = 0; i < HRM__CH; ++i) {
        f[i][0] = right ? L->scan->a[q][i] : L->scan->s[8 * q][i];
        for (j = 1; j <= 8; ++j) f[i][2 * j] = L->scan->s[8 * q + j][i];
    }
}

/* Accept one more panel after the last (the ray's first from t0), its
   coefficients into co. Where the medium scan's samples are the degree-8
   samples of the panel that starts there (hrm__tau_scan_panel), that
   panel is the first try, its degree 8 at no medium evaluation (a smooth
   or constant medium's first panels cost nothing beyond the scan). */
static HRM_DEVICE HRM__CALL void hrm__tau_march(hrm__ctx *c, hrm__tau *L, hrm__tcoef *co)
{
    hrm_real f[HRM__CH][HRM__CHEB + 1], dtau[HRM__CH];
    hrm_real a = 0, tau_a[HRM__CH], h, res;
    int i, j, n, k, failed = 0, q;
    long id = L->count;

    if (id == 0) {
        hrm_real big = 0;
        hrm__fill(tau_a, HRM__CH, 0);
        if (L->scan_q && L->scan->have[0]) memcpy(L->sig_b, L->scan->s[0], sizeof L->sig_b);
        else hrm__sigma_t_at(c, 0, 0, L->sig_b);
        memcpy(L->sig0, L->sig_b, sizeof L->sig0);
        for (i = 0; i < HRM__CH; ++i) big = L->sig_b[i] > big ? L->sig_b[i] : big;
        /* start at 8 mean free paths of the densest channel, or the ray */
        h = big > 0 && 8 / big < L->end ? 8 / big : L->end;
    } else if (id == L->base) { /* from a checkpoint (hrm__tau_from) */
        a = L->base_a;
        memcpy(tau_a, L->base_tau, sizeof tau_a);
        h = L->next_h;
    } else {
        const hrm__tpanel *p = &L->tab[(id - 1) % L->ntab];
        a = p->b;
        memcpy(tau_a, p->tau_b, sizeof tau_a);
        h = L->next_h;
    }
    q = hrm__tau_scan_panel(c, L, a);
    /* with medium.feature, no panel wider than the scan's layout makes
       them (its degree-8 points at most the feature apart), so that a
       feature the scan saw but did not teach is sampled here too (past
       the scan's panels, or where it lays its points evenly: a slab as
       wide as the feature, 17% of the density on a steep bump, at rtol
       1e-3 silent in 41 of 528 solves, its Tr that of the medium without
       it); 32 panels a ray at most (the layer's table on the stack), so
       that a march begun again seldom has to (at most 512: nested Simpson
       and Gauss-Kronrod on a ray of 1000 features made 4-6 times the
       lookups, marching again from checkpoints; with 32, 1.1-1.5 times) */
    if (q < 0 && c->m->feature > 0) {
        hrm_real wide = c->m->feature / HRM__SCAN_GAP, least = L->end / 32;
        wide = wide > least ? wide : least;
        if (h > wide) h = wide;
    }
    /* past a breakpoint sigma_t may jump: its value on this side (the
       scan's, where it starts a panel of the scan) */
    if (id > 0 && hrm__is_break(c, a)) {
        if (q >= 0) memcpy(L->sig_b, L->scan->a[q], sizeof L->sig_b);
        else hrm__sigma_t_at(c, a, 1, L->sig_b);
    }
    /* res: what t resolves near a. A trial below it is fitted at its own
       length: sigma_t there is what t resolves, which a constant fits,
       and the panel's tau keeps eps of its own increment (a panel of res
       carries eps of all of its increment, 1e6 on a ray 8 ulps long at
       1e9, to tau near t0: L 1.6e-11 off a constant's). The panels it
       starts at least double; where it fails the panel is res long,
       accepted whatever its error. */
    res = 64 * HRM__EPS * (HRM_FABS(c->t0) + a) +
          HRM__TINY;
    for (;;) {
        hrm_real b, worst, fac;
        int small = h < res && !failed && q < 0, floor = !small && h <= res && q < 0; /* floor: the last try */
        n = 8;
        if (q >= 0) {
            b = L->scan->b[q + 1];
            hrm__tau_scan_take(c, L, q, f);
            worst = hrm__tau_fit(c, L, a, b, n, 1, tau_a, f, co, dtau);
        } else {
            if (floor) h = res;
            b = a + h;
            if (b > L->end || L->end - b < h / 8) b = L->end; /* no sliver */
            for (k = 0; k < c->nbrk; ++k) /* no panel straddles a breakpoint */
                if (c->brk_off[k] > a && (c->brk_off[k] < b || c->brk_off[k] - b < h / 8)) {
                    b = c->brk_off[k];
                    break;
                }
            for (i = 0; i < HRM__CH; ++i) f[i][0] = L->sig_b[i];
            worst = hrm__tau_fit(c, L, a, b, n, 0, tau_a, f, co, dtau);
        }
        /* degree 16 when degree 8 is near; hopeless panels shrink at once */
        if (worst > 1 && worst < HRM__R(1e6) && !floor) {
            n = 16;
            worst = hrm__tau_fit(c, L, a, b, n, 1, tau_a, f, co, dtau);
        }
        fac = worst > 0 ? HRM__R(0.8) * HRM_POW(worst, -HRM__R(1) / (hrm_real)(n + 1)) : 4;
        if (worst <= 1 || floor || c->status != HRM_OK) {
            hrm__tpanel *p = &L->tab[id % L->ntab];
            p->a = a;
            p->b = b;
            p->deg = n;
            for (i = 0; i < HRM__CH; ++i) {
                p->tau_a[i] = tau_a[i];
                p->tau_b[i] = tau_a[i] + dtau[i];
                if (a <= L->foot && L->foot <= b) L->tau_foot[i] = tau_a[i];
                L->sig_b[i] = f[i][HRM__CHEB];
                p->smax[i] = 0;
                for (j = 0; j <= HRM__CHEB; j += HRM__CHEB / n)
                    p->smax[i] = f[i][j] > p->smax[i] ? f[i][j] : p->smax[i];
            }
            co->id = id;
            L->count = id + 1;
            L->next_h = (b - a) * (fac < HRM__R(0.5) ? HRM__R(0.5) : fac > 4 ? 4 : fac);
            if (small && L->next_h < 2 * (b - a)) L->next_h = 2 * (b - a);
            hrm__tau_drop(L, b); /* rejected panels' samples behind the march */
            for (i = 0; i < L->nmem && L->mem_keep[i]; ++i) {}
            if (i == L->nmem && id + 1 >= (L->ncp ? L->cp[L->ncp - 1].id : 0) + L->cp_every)
                hrm__tau_checkpoint(L, id + 1, b);
            return;
        }
        hrm__tau_remember(L, a, b, n, f);
        q = -1;
        failed |= small;
        h = (b - a) * (fac < HRM__R(0.125) ? HRM__R(0.125) : fac > HRM__R(0.5) ? HRM__R(0.5) : fac);
    }
}

/* Panel lo's coefficients, fallen out of the cache, fitted again from
   the same abscissae (the same values again) into a new cache entry: a
   frame of its own, which the march to a new panel does not hold. */
static HRM_DEVICE HRM__CALL HRM__NOINLINE hrm__tcoef *hrm__tau_refit(hrm__ctx *c, hrm__tau *L, long lo)
{
    const hrm__tpanel *p = &L->tab[lo % L->ntab];
    hrm_real f[HRM__CH][HRM__CHEB + 1], dtau[HRM__CH], v[HRM__CH];
    hrm__tcoef *co = hrm__tcache_slot(L);
    int i, q = hrm__tau_scan_panel(c, L, p->a);
    if (q >= 0 && L->scan->b[q + 1] == p->b) {
        /* a panel of the scan's: its samples, not the medium's again */
        hrm__tau_scan_take(c, L, q, f);
        hrm__tau_fit(c, L, p->a, p->b, p->deg, 1, p->tau_a, f, co, dtau);
    } else {
        hrm__sigma_t_at(c, p->a, 1, v);
        for (i = 0; i < HRM__CH; ++i) f[i][0] = v[i];
        hrm__tau_fit(c, L, p->a, p->b, p->deg, 0, p->tau_a, f, co, dtau);
    }
    co->id = lo;
    return co;
}

/* tau(t0, t0 + off) in every channel. */
static HRM_DEVICE HRM__CALL void hrm__tau_at(hrm__ctx *c, hrm__tau *L, hrm_real off, hrm_real tau[HRM__CH],
                        hrm_real *sig)
{
    const hrm__tpanel *p;
    hrm__tcoef *co;
    long lo, hi;
    hrm_real xi;
    int i;

    hrm__fill(tau, HRM__CH, 0);
    if (!(off > 0)) {
        if (sig) {
            if (L->count == 0) hrm__tau_march(c, L, hrm__tcache_slot(L));
            memcpy(sig, L->sig0, sizeof L->sig0);
        }
        return;
    }
    if (off > L->end) off = L->end;
    /* Past the last panel: march on, from the farthest checkpoint before
       off if it is ahead. */
    if (L->count > 0 && off > L->tab[(L->count - 1) % L->ntab].b) {
        int k = hrm__tau_cp_before(L, off);
        if (k >= 0 && L->cp[k].id > L->count) hrm__tau_from(L, k);
    }
    while (L->count == 0 || L->count == L->base ||
           off > L->tab[(L->count - 1) % L->ntab].b) {
        hrm__tau_march(c, L, hrm__tcache_slot(L));
        if (c->status != HRM_OK) return;
    }
    lo = L->count > L->ntab ? L->count - L->ntab : 0;
    if (lo < L->base) lo = L->base;
    hi = L->count - 1;
    co = &L->cache[L->last];
    if (co->id >= lo && off > L->tab[co->id % L->ntab].a &&
        off <= L->tab[co->id % L->ntab].b)
        lo = hi = co->id; /* the panel asked last: a march's next node */
    if (off < L->tab[lo % L->ntab].a) {
        /* forgotten: march again, from the nearest checkpoint before off
           (or t0) */
        int k = hrm__tau_cp_before(L, off);
        if (k >= 0) {
            hrm__tau_from(L, k);
        } else {
            L->count = L->base = 0;
            hrm__tau_drop(L, HRM__R(HUGE_VAL));
            hrm__forget(L);
        }
        hrm__tau_at(c, L, off, tau, sig);
        return;
    }
    /* The panel holding off: the last one whose start is below it. */
    while (lo < hi) {
        long mid = lo + (hi - lo + 1) / 2;
        if (L->tab[mid % L->ntab].a < off) lo = mid;
        else hi = mid - 1;
    }
    p = &L->tab[lo % L->ntab];
    L->hit = lo;
    co = &L->cache[L->last];
    if (co->id != lo) {
        int k;
        for (k = 0; k < L->ncache && L->cache[k].id != lo; ++k) {}
        if (k < L->ncache) {
            L->last = k;
            co = &L->cache[k];
        } else {
            co = hrm__tau_refit(c, L, lo);
        }
    }
    xi = 2 * (off - p->a) / (p->b - p->a) - 1;
    xi = xi < -1 ? -1 : xi > 1 ? 1 : xi;
    hrm__cheb_eval((const hrm_real(*)[HRM__CH])co->e, p->deg, xi, tau);
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real v = p->tau_a[i] + (p->b - p->a) / 2 * tau[i];
        /* nondecreasing: within the panel's ends */
        tau[i] = v < p->tau_a[i] ? p->tau_a[i] : v > p->tau_b[i] ? p->tau_b[i] : v;
    }
    if (sig) {
        /* d tau / d off = F'(xi): the interpolant of sigma_t, not below 0 */
        hrm__cheb_deriv((const hrm_real(*)[HRM__CH])co->e, p->deg, xi, sig);
        for (i = 0; i < HRM__CH; ++i) sig[i] = sig[i] > 0 ? sig[i] : 0;
    }
}

/* ---------------------------------------------------------------------- */
/* Warps: importance sampling as a change of variable (Munoz 2014 s.5)    */
/* ---------------------------------------------------------------------- */

/* The change of variable p -> s, as the offset s - t0 (full precision for
   short rays far from the origin) and ds/dp.
   none:        p = s - t0.
   distance:    p = 1 - exp(-sigma (s - t0)), the paper's u reflected so
                that p grows with s and keeps its precision near t0.
   equiangular: p = atan((s - delta) / D); s - t0 = D sin(p - pa) /
                (cos p cos pa), free of the cancellation in
                delta + D tan p - t0, with cos pa and sin pa exact.
   user:        the host's callbacks. */
static HRM_DEVICE void hrm__map(hrm__ctx *c, hrm_real p, hrm_real *off, hrm_real *J)
{
    hrm_real o, j;
    switch (c->warp) {
    case HRM_WARP_DISTANCE:
        o = -HRM_LOG1P(-p) / c->w_sigma;
        j = 1 / (c->w_sigma * (1 - p));
        break;
    case HRM_WARP_EQUIANGULAR: {
        /* cos p from the nearer end's exact cos and sin, moving away from
           +-pi/2, where cos p is small and a plain cos(p) imprecise. */
        /* the offset from the end nearer in t (D / cos(pa) = distance to
           t0, D / cos(pb) to t1): from t1, sin d near pi carries eps pi
           of d, eps pi r / D of T at the end (D = 1e-12 T: 1e-4 T); from
           t0, T - x near t0 keeps only eps T of the offset (a light's foot
           at t0, D 1e-17 of the ray: d ~ D where the offset read 0, L 5
           times the exact with HRM_OK). Each sine once. */
        hrm_real d = p - c->w_ua, e = c->w_ub - p, cp, sn;
        int from_a = !(c->w_rb > 0) || p <= c->w_umid;
        if (d <= e) {
            sn = HRM_SIN(d);
            cp = c->w_cos_a * HRM_COS(d) - c->w_sin_a * sn;
            o = from_a ? c->w_ra * sn / cp : c->T - c->w_rb * HRM_SIN(e) / cp;
        } else {
            sn = HRM_SIN(e);
            cp = c->w_cos_b * HRM_COS(e) + c->w_sin_b * sn;
            o = from_a ? c->w_ra * HRM_SIN(d) / cp : c->T - c->w_rb * sn / cp;
        }
        j = c->w_D / (cp * cp);
        break;
    }
    case HRM_WARP_USER:
        o = j = 0;
        if (c->status != HRM_OK) break;
        o = c->uw->t_of_u(c->uw->user, p) - c->t0;
        c->warp_calls++;
        if (HRM__FINITE(o)) {
            j = c->uw->dt_du(c->uw->user, p);
            c->warp_calls++;
        }
        if (!(HRM__FINITE(o) && HRM__FINITE(j) && j >= 0)) {
            if (c->status == HRM_OK) c->status = HRM_ERR_CALLBACK_VALUE;
            o = j = 0;
        }
        break;
    default:
        o = p;
        j = 1;
    }
    *off = o < 0 ? 0 : o < c->T ? o : c->T;
    *J = j;
}

/* The stream's level: the width w such that cutting each gap of the
   method's grid in t (M equal steps in the warp's variable) into pieces
   no wider than w takes at most the extra points allowed. Only the
   widest HRM__STREAM_EXTRA + 1 gaps can take a point: one pass keeps them,
   then each point in turn goes to the gap whose pieces are widest (water
   filling), and the level is the widest piece left. Not for a user warp,
   whose map is the host's to call (and may cost a Newton solve a node):
   there hrm__stream_to gives each gap its share of the points left by
   length. */
static HRM_DEVICE HRM__CALL void hrm__stream_level(hrm__ctx *c, long M)
{
    hrm_real top[HRM__STREAM_EXTRA + 1], J, a, b, g;
    int n[HRM__STREAM_EXTRA + 1], ntop = 0, e, i, j, best;
    long k;
    c->sm.level = 0; /* none: hrm__stream_to shares what is left */
    if (M < 1 || c->sm.extra < 1 || c->warp == HRM_WARP_USER) return;
    for (k = 0, a = 0; k < M; ++k, a = b) {
        hrm__map(c, c->pa + (c->pb - c->pa) * ((hrm_real)(k + 1) / (hrm_real)M), &b, &J);
        g = b - a;
        if (!(g > 0) || (ntop == HRM__STREAM_EXTRA + 1 && g <= top[ntop - 1])) continue;
        /* insert, widest first */
        for (i = ntop < HRM__STREAM_EXTRA + 1 ? ntop++ : ntop - 1; i > 0 && top[i - 1] < g; --i) top[i] = top[i - 1];
        top[i] = g;
    }
    if (ntop == 0) return;
    for (i = 0; i < ntop; ++i) n[i] = 0;
    for (e = 0; e < c->sm.extra; ++e) {
        for (j = 0, best = 0; j < ntop; ++j)
            if (top[j] / (hrm_real)(n[j] + 1) > top[best] / (hrm_real)(n[best] + 1)) best = j;
        n[best]++;
    }
    for (j = 0; j < ntop; ++j)
        if (top[j] / (hrm_real)(n[j] + 1) > c->sm.level) c->sm.level = top[j] / (hrm_real)(n[j] + 1);
}

/* How far the distance warp may reach: the offset x from t0 where the
   thinnest channel's tau reaches `reach` (or the end, x = T), and that tau
   there. Beyond x the medium's contribution is below exp(-reach) of the
   largest S / sigma_t there. A homogeneous medium in closed form; a
   transmittance callback by bisection; sigma callbacks by a coarse march
   of the transmittance layer where one is held, else hrm__reach_march
   (medium evaluations, no source call).
   lowest: the thinnest channel's lowest running mean tau(s)/s over the
   second half of that reach, a sigma_ref that an infinite ray's tail,
   which nobody measured, is least likely to be thinner than (a channel
   thinner than sigma_ref far out makes the warped integrand singular at
   u = 1). */
static HRM_DEVICE HRM__CALL void hrm__reach_march(hrm__ctx *c, hrm_real end, hrm_real reach, hrm_real *x,
                                                  hrm_real *tx, hrm_real *lowest);

static HRM_DEVICE HRM__CALL void hrm__tau_reach(hrm__ctx *c, hrm_real reach, hrm_real *x, hrm_real *tx,
                           hrm_real *lowest)
{
    hrm_real end = HRM__FINITE(c->T) ? c->T : HRM__R(1e30), tr[HRM__CH], least;
    int i, k;
    if (c->homog) {
        for (i = 0, least = c->st[0]; i < HRM__CH; ++i) least = c->st[i] < least ? c->st[i] : least;
        *x = least * end > reach ? reach / least : end;
        *tx = least * *x;
        *lowest = least;
        return;
    }
    if (c->m->transmittance) {
        /* the largest Tr over the channels at offset d (thinnest channel) */
#define HRM__TR_MOST(d, most)                                                 \
    do {                                                                      \
        hrm__tr_call(c, hrm__abscissa(c, d), tr);                             \
        for (i = 0, most = tr[0]; i < HRM__CH; ++i) most = tr[i] > most ? tr[i] : most; \
    } while (0)
        hrm_real lo = 0, hi = HRM__FINITE(c->T) ? c->T : 1, most, limit = HRM_EXP(-reach);
        HRM__TR_MOST(hi, most);
        /* an infinite ray: double until it is reached */
        for (k = 0; k < 100 && most > limit && !HRM__FINITE(c->T); ++k) {
            lo = hi;
            hi *= 2;
            HRM__TR_MOST(hi, most);
        }
        if (most > limit || c->status != HRM_OK) { /* never reached */
            *x = hi;
            *tx = most > 0 ? -HRM_LOG(most) : reach;
            *lowest = *tx / *x;
            return;
        }
        for (k = 0; k < 60 && hi - lo > HRM__R(1e-3) * hi && c->status == HRM_OK; ++k) {
            hrm_real mid = (lo + hi) / 2;
            HRM__TR_MOST(mid, most);
            if (most > limit) lo = mid;
            else hi = mid;
        }
        *x = hi;
        *tx = reach;
        *lowest = reach / hi;
        for (k = 2; k <= 3; ++k) { /* the running mean at x/2 and 3x/4 */
            hrm_real d = hi * (hrm_real)k / 4;
            HRM__TR_MOST(d, most);
            if (most > 0 && -HRM_LOG(most) / d < *lowest) *lowest = -HRM_LOG(most) / d;
        }
#undef HRM__TR_MOST
        return;
    }
    if (!c->tau) {
        hrm__reach_march(c, end, reach, x, tx, lowest);
        return;
    }
    {
        hrm__tau *L = c->tau;
        *lowest = -1;
        hrm__tau_init(L, end, HRM__R(1e-3));
        for (k = 0; k < 4 * HRM_TAU_PANELS; ++k) {
            const hrm__tpanel *p;
            hrm__tau_march(c, L, hrm__tcache_slot(L));
            p = &L->tab[(L->count - 1) % L->ntab];
            for (i = 0, least = p->tau_b[0]; i < HRM__CH; ++i)
                least = p->tau_b[i] < least ? p->tau_b[i] : least;
            *x = p->b;
            *tx = least;
            if (least >= reach / 2 && (*lowest < 0 || least / p->b < *lowest)) *lowest = least / p->b;
            if (c->status != HRM_OK) return;
            if (least >= reach) {
                /* where in the panel: bisection on its interpolant (its
                   coefficients are cached, no medium evaluation) */
                hrm_real lo = p->a, hi = p->b, tau[HRM__CH];
                int it;
                for (it = 0; it < 100 && hi - lo > 4 * HRM__EPS * hi; ++it) {
                    hrm_real mid = lo + (hi - lo) / 2;
                    hrm__tau_at(c, L, mid, tau, 0);
                    for (i = 0, least = tau[0]; i < HRM__CH; ++i) least = tau[i] < least ? tau[i] : least;
                    if (least >= reach) hi = mid;
                    else lo = mid;
                }
                *x = hi;
                *tx = reach;
                if (*lowest < 0 || reach / hi < *lowest) *lowest = reach / hi;
                return;
            }
            if (p->b >= end) break;
        }
        if (*lowest < 0) *lowest = *x > 0 ? *tx / *x : 0;
    }
}

/* Boole's rule over a width h on the samples f[0], f[s], .., f[4 s] of
   channel i (Abramowitz and Stegun 25.4.14). */
static HRM_DEVICE hrm_real hrm__boole(const hrm_real (*f)[HRM__CH], int s, int i, hrm_real h)
{
    return h / 90 * (7 * (f[0][i] + f[4 * s][i]) + 32 * (f[s][i] + f[3 * s][i]) + 12 * f[2 * s][i]);
}

/* hrm__tau_reach on sigma callbacks where no transmittance layer is held
   (tau from a fixed-step rule's own nodes, or the RTE form's state): a
   march of panels, each Boole's rule on its halves checked by Boole's on
   the whole, to 1e-3 of its tau or of the running mean's share (a thin
   panel), halved down to 1e-4 of the distance marched (a jump, whose
   panel's relative error does not shrink), a halved panel keeping its
   samples. The halves' error is taken as a 15th of the difference, not
   Romberg's 63rd, which holds for smooth sigma only: across a jump it
   accepted panels whose tau was 1.7 times the truth, and the ray past a
   reach found that early is not sampled. Where the thinnest channel's tau
   reaches `reach`, x is found on the broken line through the panel's
   ends and middle (a panel taken at the floor: its end). */
static HRM_DEVICE HRM__CALL void hrm__reach_march(hrm__ctx *c, hrm_real end, hrm_real reach, hrm_real *x,
                                                  hrm_real *tx, hrm_real *lowest)
{
    hrm_real a = 0, h = HRM__FINITE(c->T) ? c->T : 1, h0 = h, tau[HRM__CH], f[9][HRM__CH];
    int k, i, j, have = 0; /* f at even j already sampled (a halved panel) */
    *x = 0;
    *tx = 0;
    *lowest = -1;
    hrm__fill(tau, HRM__CH, 0);
    hrm__sigma_t_at(c, 0, 0, f[0]);
    for (k = 0; k < 4 * HRM_TAU_PANELS && c->status == HRM_OK && a < end; ++k) {
        hrm_real b, tb[HRM__CH], tm[HRM__CH], worst = 0, lo_a, lo_m, lo_b;
        if (h > end - a) h = end - a;
        b = a + h;
        for (j = 1; j <= 8; ++j)
            if (!have || (j & 1)) hrm__sigma_t_at(c, a + h * (hrm_real)j / 8, 0, f[j]);
        if (c->status != HRM_OK) return;
        for (i = 0; i < HRM__CH; ++i) {
            const hrm_real(*cf)[HRM__CH] = (const hrm_real(*)[HRM__CH])f;
            hrm_real whole = hrm__boole(cf, 2, i, h), l = hrm__boole(cf, 1, i, h / 2), r = hrm__boole(cf + 4, 1, i, h / 2);
            hrm_real e = HRM_FABS(l + r - whole) / 15, tol = HRM__R(1e-3) * (l + r > tau[i] * h / b ? l + r : tau[i] * h / b);
            if (e > 0 && !(e <= worst * tol)) worst = e / tol; /* (tol 0: e 0, or a reject) */
            tm[i] = tau[i] + l;
            tb[i] = tm[i] + r;
        }
        /* rejected: halved, its samples at the even eighths the new
           panel's at its even eighths, down to 1e-4 of the distance
           marched or of the first panel (a jump at t0 itself, sigma 0
           there and not after it, stays in every panel [0, h]: halved
           without end, the march gave up and the warp with it, an
           infinite ray's solve HRM_ERR_BAD_INTERVAL) */
        if (worst > 1 && h > HRM__R(1e-4) * (b > h0 ? b : h0)) {
            h /= 2;
            for (j = 8; j >= 2; j -= 2) memcpy(f[j], f[j / 2], sizeof f[j]);
            have = 1;
            continue;
        }
        have = 0;
        for (i = 0, lo_a = tau[0], lo_m = tm[0], lo_b = tb[0]; i < HRM__CH; ++i) {
            lo_a = tau[i] < lo_a ? tau[i] : lo_a;
            lo_m = tm[i] < lo_m ? tm[i] : lo_m;
            lo_b = tb[i] < lo_b ? tb[i] : lo_b;
        }
        *x = b;
        *tx = lo_b;
        if (lo_b >= reach) {
            /* (a panel taken at the floor, across a jump: its end, so that
               the reach is never placed before the truth) */
            if (worst <= 1)
                *x = lo_m >= reach ? a + h / 2 * (lo_m > lo_a ? (reach - lo_a) / (lo_m - lo_a) : 1)
                                   : a + h / 2 + h / 2 * (lo_b > lo_m ? (reach - lo_m) / (lo_b - lo_m) : 1);
            *tx = reach;
            if (*lowest < 0 || reach / *x < *lowest) *lowest = reach / *x;
            return;
        }
        if (lo_b >= reach / 2 && (*lowest < 0 || lo_b / b < *lowest)) *lowest = lo_b / b;
        memcpy(tau, tb, sizeof tau);
        memcpy(f[0], f[8], sizeof f[0]);
        a = b;
        if (worst < HRM__R(1.0) / 128) h *= 2;
    }
    if (*lowest < 0) *lowest = *x > 0 ? *tx / *x : 0;
}

/* The parameter range [pa, pb] of the warp, with its fallbacks. An
   infinite t1 maps to a finite end, pulled in by one rounding step so that
   no callback ever sees infinity (the part of u dropped has measure of
   order epsilon). */
/* The warp's parameters alone (no callback is called): HRM_ERR_BAD_WARP
   for an unknown kind, sigma_ref or D negative or not finite, delta not
   finite, a user warp without its callbacks. */
static HRM_DEVICE hrm_status hrm__warp_valid(const hrm_warp *w)
{
    switch (w->kind) {
    case HRM_WARP_NONE: return HRM_OK;
    case HRM_WARP_DISTANCE:
        return HRM__FINITE(w->sigma_ref) && w->sigma_ref >= 0 ? HRM_OK : HRM_ERR_BAD_WARP;
    case HRM_WARP_EQUIANGULAR:
        return HRM__FINITE(w->D) && w->D >= 0 && HRM__FINITE(w->delta) ? HRM_OK : HRM_ERR_BAD_WARP;
    case HRM_WARP_USER:
        return w->t_of_u && w->dt_du && w->u_of_t ? HRM_OK : HRM_ERR_BAD_WARP;
    default: return HRM_ERR_BAD_WARP;
    }
}

static HRM_DEVICE hrm_real hrm__mix_t_of_u(void *user, hrm_real u);

/* t's resolution where the ray [t0, t1] passes nearest a light whose foot
   is delta, D from the ray's line, over the light's distance there: eps
   |t| / r, t = t0 + the offset carrying eps of both (a foot at t1 = 0 on
   [-1, 0], D 1e-15: eps 1 / D, not 0; nested Simpson 12 rtol off with
   HRM_OK); hrm__finish warns past 2 rtol. */
static HRM_DEVICE double hrm__light_res(double delta, double D, double t0, double t1)
{
    double near = delta < t0 ? t0 : delta > t1 ? t1 : delta, x = delta - near, span = fabs(near);
    span = fabs(t0) > span ? fabs(t0) : span;
    span = near - t0 > span ? near - t0 : span;
    return (double)HRM__EPS * span / sqrt(D * D + x * x);
}

/* The D the equiangular map takes for a light D from the ray's line, its
   foot delta outside [t0, t1]: on the line (D = 0), or so near it that
   u's range is below sqrt(eps) of u (float: D under about 1e-3 of the
   light's distance from the nearer end), the map had been none, and 1/r^2
   is steep near that end all the same where the light is nearer it than
   the ray is long (float, a light 1e-6 of the ray before t0: Verner 14
   rtol off with HRM_OK). There the map of D = an eighth of that distance,
   whose density is 1/r^2's to within 1.6%, where t resolves r to sqrt(eps)
   (coarser, the pairs refined under the map to their budget, chasing
   round-off); D itself elsewhere. */
static HRM_DEVICE double hrm__line_D(double delta, double D, double t0, double t1)
{
    double near = delta < t0 ? t0 - delta : delta > t1 ? delta - t1 : 0, ua, ub, e = (double)HRM__EPS;
    if (!(near > 0 && near < t1 - t0 && D < near / 8 && hrm__light_res(delta, D, t0, t1) <= sqrt(e))) return D;
    ua = atan2(t0 - delta, D);
    ub = atan2(t1 - delta, D);
    return ub - ua > sqrt(e) * (fabs(ua) + fabs(ub)) ? D : near / 8;
}

static HRM_DEVICE HRM__CALL hrm_status hrm__setup_warp(hrm__ctx *c, const hrm_warp *w)
{
    int inf = !HRM__FINITE(c->T);
    hrm_real T = c->T; /* (w's parameters checked: hrm__validate) */
    c->warp = w->kind;
    c->pa = 0;
    c->pb = T;
    switch (w->kind) {
    case HRM_WARP_NONE:
        break;
    case HRM_WARP_DISTANCE: {
        /* u resolves t only while 1 - u is well above epsilon: past
           ln(2/eps) mean free paths of sigma_ref the ray is not sampled.
           So sigma_ref never exceeds what the ray's own optical depth
           allows: a finite ray that stays thinner than that is sampled to
           its end (the end resolved to sqrt(eps) in u), and only where the
           thinnest channel's Tr has fallen below eps/2 may the rest go.
           sigma_ref = 0 takes the thinnest channel's mean extinction over
           that reach. */
        hrm_real s = w->sigma_ref, reach = HRM_LOG(2 / HRM__EPS), x, tx, lowest;
        hrm_real tiny = HRM__TINY;
        if (s == 0 || inf || s * T > reach / 2) {
            hrm_real cap;
            hrm__tau_reach(c, reach, &x, &tx, &lowest);
            if (c->status != HRM_OK) return c->status;
            cap = tx >= reach ? reach / x : reach / 2 / x;
            if (inf && lowest < cap) cap = lowest;
            if (s == 0) s = x > 0 ? tx / x : 0;
            if (s > cap) s = cap;
        }
        /* zero or denormal, or the identity to round-off (u's range
           s T below eps underflows, its Jacobian 1 / s overflows): none */
        if (!(s >= tiny) || (!inf && s * T < HRM__EPS)) {
            c->warp = HRM_WARP_NONE;
            break;
        }
        /* an infinite ray's reach ln(2/eps) / s within the range (s just
           above the smallest normal number: the offsets overflowed, and
           callbacks saw t = +inf) */
        if (inf && !(reach / s <= hrm__range(1))) s = reach / hrm__range(1);
        c->w_sigma = s;
        c->pb = inf ? 1 : -HRM_EXPM1(-s * T);
        if (c->pb > 1 - HRM__EPS / 2) c->pb = 1 - HRM__EPS / 2;
        break;
    }
    case HRM_WARP_EQUIANGULAR: {
        hrm_real D = w->D, da = c->t0 - w->delta, db = c->t1 - w->delta, rb;
        /* A light closer to the ray than the resolution of t near it is on
           the ray as far as any abscissa can tell. */
        hrm_real res = 4 * HRM__EPS * (HRM_FABS(w->delta) > HRM_FABS(c->t0) ? HRM_FABS(w->delta)
                                                                             : HRM_FABS(c->t0));
        if (D <= res && w->delta >= c->t0 && w->delta <= c->t1) return HRM_ERR_SINGULAR;
        /* what t resolves near the light, warped or not (a light on the
           ray's line 8 ulps past t1, float: Gauss-Kronrod 6 700 rtol off
           with HRM_OK) */
        c->w_res = (hrm_real)hrm__light_res((double)w->delta, (double)D, (double)c->t0, (double)c->t1);
        D = (hrm_real)hrm__line_D((double)w->delta, (double)D, (double)c->t0, (double)c->t1);
        if (D == 0) {
            c->warp = HRM_WARP_NONE; /* on the ray's line where t does not resolve r */
            break;
        }
        /* A light far from the whole ray (|t - delta| below eps^(1/4) D):
           the warp's dt/du = D (1 + ((t - delta) / D)^2) varies by less
           than sqrt(eps), an affine map, and D itself may be past the
           range: none. */
        if (!inf && (HRM_FABS(da) > HRM_FABS(db) ? HRM_FABS(da) : HRM_FABS(db)) <=
                        HRM_SQRT(HRM_SQRT(HRM__EPS)) * D) {
            c->warp = HRM_WARP_NONE;
            break;
        }
        c->w_D = D;
        c->w_delta = w->delta;
        c->w_ra = HRM_HYPOT(da, D);
        c->w_cos_a = D / c->w_ra;
        c->w_sin_a = da / c->w_ra;
        c->pa = c->w_ua = HRM_ATAN2(da, D);
        c->w_rb = 0;
        if (inf) {
            c->w_cos_b = 0;
            c->w_sin_b = 1;
            c->w_ub = HRM__R(1.5707963267948966);
            c->pb = c->w_ub * (1 - HRM__EPS);
            /* a light behind t0 within an ulp of the line's angle (D 1e-12,
               1 behind: pa rounds to pi/2): no range in u to sample (it
               was reversed, L -16 391 with HRM_OK); hrm__setup takes the
               distance warp instead, with a warning */
            if (!(c->pb - c->pa > HRM_SQRT(HRM__EPS) * (HRM_FABS(c->pa) + HRM_FABS(c->pb))))
                c->warp = HRM_WARP_NONE;
        } else {
            c->w_rb = rb = HRM_HYPOT(db, D);
            c->w_cos_b = D / rb;
            c->w_sin_b = db / rb;
            c->pb = c->w_ub = HRM_ATAN2(db, D);
            c->w_umid = HRM_ATAN2(da + T / 2, D);
            /* A tiny angular range (a short segment far from the light)
               makes the warp nearly affine and p - pa imprecise: none. */
            if (!(c->pb - c->pa > HRM_SQRT(HRM__EPS) * (HRM_FABS(c->pa) + HRM_FABS(c->pb)))) {
                c->warp = HRM_WARP_NONE;
                c->pa = 0;
                c->pb = T;
            }
        }
        break;
    }
    case HRM_WARP_USER:
        c->uw = w;
        /* hrm_light_options' mixture: its lights' resolution (above) */
        if (w->t_of_u == hrm__mix_t_of_u && w->user) c->w_res = (hrm_real)((const hrm_ray_plan *)w->user)->res;
        c->pa = w->u_of_t(w->user, c->t0);
        c->pb = HRM__FINITE(c->pa) ? w->u_of_t(w->user, c->t1) : c->pa;
        if (!(HRM__FINITE(c->pa) && HRM__FINITE(c->pb) && c->pb > c->pa)) return HRM_ERR_BAD_WARP;
        if (inf) c->pb -= (HRM_FABS(c->pa) + HRM_FABS(c->pb)) * HRM__EPS;
        break;
    default:
        return HRM_ERR_BAD_WARP;
    }
    if (inf && c->warp == HRM_WARP_NONE) return HRM_ERR_BAD_INTERVAL;
    c->s_end = c->t1;
    if (inf) {
        hrm_real off, J;
        hrm__map(c, c->pb, &off, &J);
        c->s_end = c->t0 + off;
    }
    return HRM_OK;
}

/* |v| scaled by its largest component: no overflow or underflow where |v|
   itself is representable (a light 1e300 away, or 1e-310 off the ray).
   v finite. */
static HRM_DEVICE double hrm__norm3(const double v[3])
{
    double m = 0, q = 0, a;
    int i;
    for (i = 0; i < 3; ++i) m = fabs(v[i]) > m ? fabs(v[i]) : m;
    if (m == 0) return 0;
    for (i = 0; i < 3; ++i) {
        a = v[i] / m;
        q += a * a;
    }
    return m * sqrt(q);
}

/* A direction made unit length (in double whatever hrm_real is); its
   length in *len. Returns 0 where dir is zero or not finite. */
static HRM_DEVICE int hrm__unit3(const hrm_real dir[3], double d[3], double *len)
{
    int i;
    for (i = 0; i < 3; ++i) {
        d[i] = (double)dir[i];
        if (!HRM__FINITE(d[i])) return 0;
    }
    *len = hrm__norm3(d);
    if (!(*len > 0 && HRM__FINITE(*len))) return 0;
    for (i = 0; i < 3; ++i) d[i] /= *len;
    return 1;
}

HRM__DEF HRM_DEVICE hrm_status hrm_equiangular_warp(const hrm_real origin[3], const hrm_real dir[3],
                                         const hrm_real light[3], hrm_warp *warp)
{
    double v[3], d[3], x[3], len, vd = 0, delta, D;
    int i;
    if (warp) memset(warp, 0, sizeof *warp);
    if (!origin || !dir || !light || !warp) return HRM_ERR_NULL_ARGUMENT;
    if (!hrm__unit3(dir, d, &len)) return HRM_ERR_BAD_WARP;
    for (i = 0; i < 3; ++i) {
        v[i] = (double)light[i] - (double)origin[i];
        if (!HRM__FINITE(v[i])) return HRM_ERR_BAD_WARP;
        vd += v[i] * d[i];
    }
    /* |v x d| is the light's distance from the ray's line, without the
       cancellation of sqrt(|v|^2 - delta^2). */
    x[0] = v[1] * d[2] - v[2] * d[1];
    x[1] = v[2] * d[0] - v[0] * d[2];
    x[2] = v[0] * d[1] - v[1] * d[0];
    delta = vd / len;
    D = hrm__norm3(x) / len;
    if (!(HRM__FINITE((hrm_real)delta) && HRM__FINITE((hrm_real)D))) return HRM_ERR_BAD_WARP;
    warp->kind = HRM_WARP_EQUIANGULAR;
    warp->delta = (hrm_real)delta;
    warp->D = (hrm_real)D;
    return HRM_OK;
}

/* The real roots of A x^2 + B x + C in their stable form, into r (a double
   root or the linear case's one root twice); returns 0 or 2, or 1 for the
   linear case. */
static HRM_DEVICE int hrm__quad_roots(double A, double B, double C, double r[2])
{
    double disc, q;
    if (A == 0) {
        if (B == 0) return 0;
        r[0] = r[1] = -C / B;
        return 1;
    }
    disc = B * B - 4 * A * C;
    if (disc < 0) return 0;
    q = -(B + (B < 0 ? -sqrt(disc) : sqrt(disc))) / 2;
    r[0] = q / A;
    r[1] = q != 0 ? C / q : r[0];
    return 2;
}

/* Where the ray w + s d (d unit, s = t len) crosses the cone of apex 0,
   unit axis u and cos^2 of its half-angle k, on the part where (w + s d).u
   >= vmin: t in (t0, t1), ascending, into out[0..1]; returns how many. The
   roots of (v.u)^2 - k (v.v) = 0 in their stable form. */
static HRM_DEVICE HRM__CALL int hrm__cone_hits(const double w[3], const double d[3], double len, const double u[3], double k,
                          double vmin, hrm_real t0, hrm_real t1, hrm_real out[2])
{
    double wu = 0, du = 0, wd = 0, ww, A, B, C, r[2];
    int i, n, j, count = 0;
    for (i = 0; i < 3; ++i) {
        wu += w[i] * u[i];
        du += d[i] * u[i];
        wd += w[i] * d[i];
    }
    ww = hrm__norm3(w);
    A = du * du - k;
    B = 2 * (wu * du - k * wd);
    C = (wu - sqrt(k) * ww) * (wu + sqrt(k) * ww);
    n = hrm__quad_roots(A, B, C, r);
    for (j = 0; j < n; ++j) {
        double t = r[j] / len;
        if (!(t > (double)t0 && t < (double)t1)) continue;
        if (!(wu + r[j] * du >= vmin)) continue; /* the other nappe */
        out[count++] = (hrm_real)t;
    }
    if (count == 2) {
        if (out[0] > out[1]) {
            hrm_real x = out[0];
            out[0] = out[1];
            out[1] = x;
        }
        if (out[0] == out[1]) count = 1;
    }
    return count;
}

HRM__DEF HRM_DEVICE hrm_status hrm_sphere_breaks(const hrm_real origin[3], const hrm_real dir[3],
                                      const hrm_real light[3], const hrm_real center[3],
                                      hrm_real radius, hrm_real t0, hrm_real t1,
                                      hrm_real out[2], int *count)
{
    /* In double whatever hrm_real is, along the unit direction d (s = t
       len): v(s) = w + s d from the light, u the unit vector to the
       center, cos^2 of the cone's half-angle k = 1 - R^2 / |c - L|^2,
       beyond the circle of tangency: v.u >= |c - L| k. */
    double w[3], d[3], u[3], len, dist, k;
    int i;
    if (count) *count = 0;
    if (!origin || !dir || !light || !center || !out || !count) return HRM_ERR_NULL_ARGUMENT;
    if (!hrm__unit3(dir, d, &len)) return HRM_ERR_BAD_WARP;
    for (i = 0; i < 3; ++i) {
        w[i] = (double)origin[i] - (double)light[i];
        u[i] = (double)center[i] - (double)light[i];
        if (!(HRM__FINITE(w[i]) && HRM__FINITE(u[i]))) return HRM_ERR_BAD_WARP;
    }
    dist = hrm__norm3(u);
    if (!(HRM__FINITE(radius) && radius >= 0 && HRM__FINITE(t0) && t1 >= t0))
        return HRM_ERR_BAD_WARP;
    if (!(dist > (double)radius) || radius == 0) return HRM_OK; /* light inside, or no sphere */
    for (i = 0; i < 3; ++i) u[i] /= dist;
    k = 1 - ((double)radius / dist) * ((double)radius / dist);
    *count = hrm__cone_hits(w, d, len, u, k, dist * k, t0, t1, out);
    return HRM_OK;
}

/* The mixture warp of hrm_light_options: u = sum c_i (atan((t - delta_i)
   / D_i) - a0_i), a0_i its value at t0, du/dt = sum c_i D_i / (D_i^2 + (t -
   delta_i)^2) (c_i = power_i / D_i: the lights' irradiance on the ray); t
   from u by Newton's method kept inside a bracket, the last inversion kept
   (the solve asks dt_du at the u it has just mapped). */
static HRM_DEVICE double hrm__mix_u(const hrm_ray_plan *p, double t)
{
    double u = 0;
    int i;
    for (i = 0; i < p->nmix; ++i) u += p->c[i] * (atan((t - p->delta[i]) / p->D[i]) - p->a0[i]);
    return u;
}

/* Light i's irradiance on the ray at t, power / r^2: its part of du/dt. */
static HRM_DEVICE double hrm__mix_irr(const hrm_ray_plan *p, int i, double t)
{
    double x = (t - p->delta[i]) / p->D[i];
    return p->c[i] / (p->D[i] * (1 + x * x));
}

static HRM_DEVICE double hrm__mix_du(const hrm_ray_plan *p, double t)
{
    double g = 0;
    int i;
    for (i = 0; i < p->nmix; ++i) g += hrm__mix_irr(p, i, t);
    return g;
}

static HRM_DEVICE hrm_real hrm__mix_u_of_t(void *user, hrm_real t)
{
    return (hrm_real)hrm__mix_u((const hrm_ray_plan *)user, (double)t);
}

/* The secant through a bracket's ends (lo, flo), (hi, fhi): where it
   crosses 0. */
static HRM_DEVICE double hrm__falsi(double lo, double flo, double hi, double fhi)
{
    return lo - flo * (hi - lo) / (fhi - flo);
}

static HRM_DEVICE HRM__CALL double hrm__mix_invert(hrm_ray_plan *p, double want)
{
    double lo = p->t0, hi = p->t1, flo = -want, fhi, t, step, last;
    int it, side = 0;
    if (want == p->last_u) return p->last_t;
    if (!(want > 0)) {
        t = p->t0;
    } else if (!(want < p->u1)) {
        t = p->t1;
    } else {
        if (!(hi < HUGE_VAL)) {
            /* an infinite ray: the farthest light's foot plus 2^k of its
               reach */
            hi = p->t0;
            for (it = 0; it < p->nmix; ++it)
                if (p->delta[it] + p->D[it] > hi) hi = p->delta[it] + p->D[it];
            for (it = 0; (fhi = hrm__mix_u(p, hi) - want) < 0 && it < 2100; ++it) hi = p->t0 + 2 * (hi - p->t0) + 1;
        } else {
            fhi = p->u1 - want;
        }
        /* the solve's nodes come mostly in order: the last inversion
           bounds this one and its tangent gives the first guess */
        t = hrm__falsi(lo, flo, hi, fhi);
        if (p->last_u > 0 && p->last_u < p->u1) {
            double g = hrm__mix_du(p, p->last_t), nt = g > 0 ? p->last_t + (want - p->last_u) / g : t;
            if (want > p->last_u) {
                lo = p->last_t;
                flo = p->last_u - want;
            } else {
                hi = p->last_t;
                fhi = p->last_u - want;
            }
            t = nt > lo && nt < hi ? nt : hrm__falsi(lo, flo, hi, fhi);
        }
        if (!(t > lo && t < hi)) t = (lo + hi) / 2;
        step = last = hi - lo;
        for (it = 0; it < 200; ++it) {
            double f = hrm__mix_u(p, t) - want, g = hrm__mix_du(p, t), nt;
            if (f == 0) break;
            if (f < 0) {
                lo = t;
                flo = f;
                if (side == -1) fhi /= 2; /* the same end twice: Illinois */
                side = -1;
            } else {
                hi = t;
                fhi = f;
                if (side == 1) flo /= 2;
                side = 1;
            }
            /* Newton inside the bracket that at least halves the step
               before last, else the bracket's secant (regula falsi,
               Illinois): Newton alone can swing across the flat stretch
               between two lights without converging */
            if (g > 0 && fabs(f) <= 8 * DBL_EPSILON * fabs(t) * g) break; /* Newton's step below rounding */
            nt = g > 0 ? t - f / g : lo;
            if (!(nt > lo && nt < hi) || 2 * fabs(nt - t) > last) {
                nt = hrm__falsi(lo, flo, hi, fhi);
                if (!(nt > lo && nt < hi)) nt = (lo + hi) / 2;
            }
            last = step;
            step = fabs(nt - t);
            t = nt;
            if (hi - lo <= 4 * DBL_EPSILON * fabs(t)) break;
        }
    }
    p->last_u = want;
    p->last_t = t;
    return t;
}

static HRM_DEVICE hrm_real hrm__mix_t_of_u(void *user, hrm_real u)
{
    return (hrm_real)hrm__mix_invert((hrm_ray_plan *)user, (double)u);
}

static HRM_DEVICE hrm_real hrm__mix_dt_du(void *user, hrm_real u)
{
    hrm_ray_plan *p = (hrm_ray_plan *)user;
    double g = hrm__mix_du(p, hrm__mix_invert(p, (double)u));
    return g > 0 ? (hrm_real)(1 / g) : (hrm_real)HUGE_VAL;
}

/* A light's weight in the mixture: c times the angle the ray subtends
   from it (atan(+inf) is pi / 2: an infinite ray needs no case). */
static HRM_DEVICE double hrm__mix_mass(double c, double delta, double D, hrm_real t0, hrm_real t1)
{
    return c * (atan(((double)t1 - delta) / D) - atan(((double)t0 - delta) / D));
}

/* A breakpoint candidate into the plan's list (unsorted; deduplicated and
   sorted at the end; at most 2 HRM_MAX_BREAKS kept). */
static HRM_DEVICE void hrm__plan_add(hrm_real *list, int *n, hrm_real t, hrm_real t0, hrm_real t1)
{
    if (t > t0 && t < t1 && *n < 2 * HRM_MAX_BREAKS) list[(*n)++] = t;
}

/* Where light i's irradiance is e times light j's: s = t - delta_i for
   the roots of P_i (D_j^2 + (s - dl)^2) = e P_j (D_i^2 + s^2); how many. */
static HRM_DEVICE int hrm__mix_ratio_at(const hrm_ray_plan *p, int i, int j, double e, double s[2])
{
    double Pi = p->c[i] * p->D[i], Pj = p->c[j] * p->D[j], dl = p->delta[j] - p->delta[i];
    return hrm__quad_roots(Pi - e * Pj, -2 * Pi * dl,
                           Pi * (p->D[j] * p->D[j] + dl * dl) - e * Pj * p->D[i] * p->D[i], s);
}

/* Where the mixture passes from light i to light j: between two peaks the
   warp gives the ray little of u, and the source per unit of u, flat where
   one light's irradiance rules, changes there by what sets the two lights
   apart (the medium along their shadow rays, a spot's falloff) within a
   band of u that a rule's first nodes can straddle: two point lights,
   nested Simpson at rtol 1.4e-4, 21 evaluations, L 1.4e-3 off with HRM_OK.
   Where the two light the ray alike and most and their band (irradiance i
   over j from 4 to 1/4, to first order about the crossing) holds less than
   a third of the first nodes' spacing, 1/48 of u (nested Simpson's 4
   panels: 16 intervals), the band's edges are breakpoints. P_i / r_i^2 = e
   P_j / r_j^2 with r^2 = D^2 + x^2, x = t - delta: a quadratic in s = t -
   delta_i, for e = 1 (the crossing), 1/4 and 4 (the edges). */
static HRM_DEVICE void hrm__mix_transitions(const hrm_ray_plan *p, hrm_real t0, hrm_real t1, hrm_real *cand, int *n)
{
    int i, j, k, r, m, h;
    for (i = 0; i < p->nmix; ++i)
        for (j = i + 1; j < p->nmix; ++j) {
            double s[2], e;
            m = hrm__mix_ratio_at(p, i, j, 1, s);
            for (r = 0; r < m; ++r) {
                double t = p->delta[i] + s[r], xi = s[r], xj = t - p->delta[j];
                double ri = p->D[i] * p->D[i] + xi * xi, rj = p->D[j] * p->D[j] + xj * xj;
                double slope = fabs(2 * xj / rj - 2 * xi / ri); /* d/dt ln(I_i / I_j) */
                int top = HRM__FINITE(t) && t > (double)t0 && t < (double)t1;
                for (k = 0; k < p->nmix && top; ++k)
                    top = k == i || k == j || hrm__mix_irr(p, k, t) <= hrm__mix_irr(p, i, t);
                /* the band: ln 16 / slope of t, hrm__mix_du per unit of t;
                   its edges the breakpoints (the roots nearest the
                   crossing), so that the change is a piece of its own,
                   never at a piece's end, where Gauss-Kronrod has no node */
                if (!(top && slope > 0 && hrm__mix_du(p, t) * (2.7725887222397811 / slope) < p->u1 / 48)) continue;
                for (e = 0.25; e <= 4; e *= 16) {
                    double q[2], best = HUGE_VAL;
                    int nq = hrm__mix_ratio_at(p, i, j, e, q);
                    for (h = 0; h < nq; ++h)
                        if (HRM__FINITE(q[h]) && fabs(q[h] - xi) < fabs(best - xi)) best = q[h];
                    if (best < HUGE_VAL) hrm__plan_add(cand, n, (hrm_real)(p->delta[i] + best), t0, t1);
                }
            }
        }
}

static HRM_DEVICE int hrm__vec_ok(const hrm_real v[3])
{
    return HRM__FINITE(v[0]) && HRM__FINITE(v[1]) && HRM__FINITE(v[2]);
}

/* Whether w + s d (s = +inf: the direction d) lies inside the cone of
   apex 0, unit axis a and half-angle of cosine ca. */
static HRM_DEVICE int hrm__in_cone(const double w[3], const double d[3], double s, const double a[3], double ca)
{
    double v[3], va = 0;
    int j;
    for (j = 0; j < 3; ++j) {
        v[j] = s < HUGE_VAL ? w[j] + s * d[j] : d[j];
        va += v[j] * a[j];
    }
    return va >= hrm__norm3(v) * ca;
}

/* A spot whose cone leaves dark the point of the ray nearest it (its foot,
   or the ray's end nearest the foot): its equiangular density (eq, in t)
   moved to the lit point nearest that one, which the cone's edges
   edge[0..nedge) and the ray's ends bound (lit0, lit1: whether the ends
   are inside the cone, of cosine ca), D its distance from the light.
   Of the light's irradiance P / (D^2 + (t - delta)^2) only the lit part is
   seen, largest there and falling off at least as fast as the moved
   density (a mixture that kept the dark peak spent its samples where Li is
   0: Dormand-Prince 12.7 rtol off with HRM_OK in bench/sweep.c). */
static HRM_DEVICE void hrm__spot_peak(const double w[3], const double d[3], double len, const double a[3], double ca,
                                      hrm_real t0, hrm_real t1, int lit0, int lit1, const hrm_real edge[2], int nedge,
                                      hrm_warp *eq)
{
    double p = (double)eq->delta, best = 0, gap = HUGE_VAL, x[4];
    int j, nx = 0;
    if (p < (double)t0) p = (double)t0;
    if (p > (double)t1) p = (double)t1;
    if (hrm__in_cone(w, d, p * len, a, ca)) return;
    for (j = 0; j < nedge; ++j) x[nx++] = (double)edge[j];
    if (lit0) x[nx++] = (double)t0;
    if (lit1 && (double)t1 < HUGE_VAL) x[nx++] = (double)t1;
    for (j = 0; j < nx; ++j)
        if (fabs(x[j] - p) < gap) {
            gap = fabs(x[j] - p);
            best = x[j];
        }
    if (nx == 0) return;
    eq->D = (hrm_real)sqrt((double)eq->D * (double)eq->D + (best - (double)eq->delta) * (best - (double)eq->delta));
    eq->delta = (hrm_real)best;
}

/* A sphere's shadow under a directional light travelling along unit a:
   where the ray (w + s d from the center) crosses the cylinder of the
   sphere's radius behind it (w + s d).a > 0, into the list. */
static HRM_DEVICE void hrm__cylinder_hits(const double w[3], const double d[3], double len, const double a[3], double R,
                               hrm_real t0, hrm_real t1, hrm_real *list, int *n)
{
    double wa = 0, da = 0, A = 0, B = 0, C = -R * R, r[2];
    int j, m;
    for (j = 0; j < 3; ++j) {
        wa += w[j] * a[j];
        da += d[j] * a[j];
    }
    for (j = 0; j < 3; ++j) {
        double wp = w[j] - wa * a[j], dp = d[j] - da * a[j];
        A += dp * dp;
        B += 2 * wp * dp;
        C += wp * wp;
    }
    if (!(A > 0) || R == 0) return; /* the ray along the light: no edge */
    m = hrm__quad_roots(A, B, C, r);
    for (j = 0; j < m; ++j)
        if (wa + r[j] * da > 0) hrm__plan_add(list, n, (hrm_real)(r[j] / len), t0, t1);
}

HRM__DEF HRM_DEVICE hrm_status hrm_light_options(const hrm_light *lights, int nlights, const hrm_sphere *spheres,
                                      int nspheres, const hrm_real origin[3], const hrm_real dir[3],
                                      hrm_real t0, hrm_real t1, hrm_ray_plan *plan, hrm_options *options)
{
    hrm_real cand[2 * HRM_MAX_BREAKS];
    double d[3], len, pi = 3.14159265358979323846, line_res = -1;
    int n = 0, i, j, k;
    hrm_status st = HRM_ERR_BAD_WARP;
    hrm_warp line;
    if (!origin || !dir || !plan || !options || (nlights > 0 && !lights) || (nspheres > 0 && !spheres)) {
        if (plan) memset(plan, 0, sizeof *plan);
        return HRM_ERR_NULL_ARGUMENT;
    }
    /* the host's own breakpoints inside the ray (not this plan's of an
       earlier ray, where options are reused) */
    if (options->breaks != plan->breaks)
        for (i = 0; options->breaks && i < options->nbreaks && i < HRM_MAX_BREAKS; ++i)
            hrm__plan_add(cand, &n, options->breaks[i], t0, t1);
    memset(plan, 0, sizeof *plan);
    memset(&line, 0, sizeof line);
    if (!hrm__unit3(dir, d, &len) || !hrm__vec_ok(origin) || !HRM__FINITE(t0) || !(t1 >= t0) || nlights < 0 ||
        nspheres < 0)
        return HRM_ERR_BAD_WARP;
    /* every input checked before anything is written */
    for (i = 0; i < nlights; ++i) {
        const hrm_light *l = &lights[i];
        double a[3], alen;
        if (l->kind != HRM_LIGHT_POINT && l->kind != HRM_LIGHT_SPOT && l->kind != HRM_LIGHT_DIRECTIONAL)
            return HRM_ERR_BAD_WARP;
        if (!(HRM__FINITE(l->power) && l->power > 0)) return HRM_ERR_BAD_WARP;
        if (l->kind != HRM_LIGHT_DIRECTIONAL && !hrm__vec_ok(l->position)) return HRM_ERR_BAD_WARP;
        if (l->kind != HRM_LIGHT_POINT && !hrm__unit3(l->direction, a, &alen)) return HRM_ERR_BAD_WARP;
        if (l->kind == HRM_LIGHT_SPOT && !(l->cone > 0 && l->cone <= (hrm_real)pi && l->falloff >= 0 &&
                                           l->falloff <= l->cone))
            return HRM_ERR_BAD_WARP;
    }
    for (i = 0; i < nspheres; ++i)
        if (!hrm__vec_ok(spheres[i].center) || !(HRM__FINITE(spheres[i].radius) && spheres[i].radius >= 0))
            return HRM_ERR_BAD_WARP;
    for (i = 0; i < nlights; ++i) {
        const hrm_light *l = &lights[i];
        hrm_warp eq;
        hrm_real hit[2], edge[2];
        double w[3], a[3], alen, mass, ca = -1;
        int reach = 1, m, nedge = 0, lit0 = 1, lit1 = 1;
        if (l->kind != HRM_LIGHT_POINT) hrm__unit3(l->direction, a, &alen);
        if (l->kind == HRM_LIGHT_DIRECTIONAL) {
            for (k = 0; k < nspheres; ++k) {
                for (j = 0; j < 3; ++j) w[j] = (double)origin[j] - (double)spheres[k].center[j];
                hrm__cylinder_hits(w, d, len, a, (double)spheres[k].radius, t0, t1, cand, &n);
            }
            continue;
        }
        /* (a position 1e308 from the origin: its offset not finite) */
        if (hrm_equiangular_warp(origin, dir, l->position, &eq) != HRM_OK) goto fail;
        for (j = 0; j < 3; ++j) w[j] = (double)origin[j] - (double)l->position[j];
        if (l->kind == HRM_LIGHT_SPOT) {
            /* the cone's edges: the forward nappe of a cone narrower than
               a half-space, the back one's of a wider one (none for pi);
               the ray reaches the light where an end is inside or it
               crosses an edge */
            double cf = cos((double)l->falloff), ab[3], af[3];
            ca = cos((double)l->cone);
            for (j = 0; j < 3; ++j) {
                ab[j] = ca < 0 ? -a[j] : a[j];
                af[j] = cf < 0 ? -a[j] : a[j];
            }
            lit0 = hrm__in_cone(w, d, (double)t0 * len, a, ca);
            lit1 = hrm__in_cone(w, d, (double)t1 * len, a, ca);
            reach = lit0 || lit1;
            if (l->cone < (hrm_real)pi) {
                nedge = hrm__cone_hits(w, d, len, ab, ca * ca, 0, t0, t1, edge);
                for (j = 0; j < nedge; ++j) hrm__plan_add(cand, &n, edge[j], t0, t1);
                reach = reach || nedge > 0;
            }
            if (l->falloff > 0 && l->falloff < l->cone) {
                m = hrm__cone_hits(w, d, len, af, cf * cf, 0, t0, t1, hit);
                for (j = 0; j < m; ++j) hrm__plan_add(cand, &n, hit[j], t0, t1);
            }
        }
        for (k = 0; k < nspheres; ++k) {
            if (hrm_sphere_breaks(origin, dir, l->position, spheres[k].center, spheres[k].radius, t0, t1, hit, &m) !=
                HRM_OK)
                goto fail;
            for (j = 0; j < m; ++j) hrm__plan_add(cand, &n, hit[j], t0, t1);
        }
        if (!reach) continue;
        if (eq.D == 0 && eq.delta >= t0 && eq.delta <= t1) {
            st = HRM_ERR_SINGULAR;
            goto fail;
        }
        eq.D = (hrm_real)hrm__line_D((double)eq.delta, (double)eq.D, (double)t0, (double)t1);
        if (eq.D == 0) {
            /* on the ray's line, outside it, where t does not resolve r:
               no map, but where no other light gives one, the warp of D =
               0 (none), so that the solve weighs t's resolution there
               (the nearest such light's) as it does for that warp (float,
               a light 1e-6 of the ray past t1: Verner 10 rtol off with
               HRM_OK at rtol 1e-2) */
            double res = hrm__light_res((double)eq.delta, 0, (double)t0, (double)t1);
            if (res > line_res) {
                line_res = res;
                line = eq;
            }
            continue;
        }
        if (l->kind == HRM_LIGHT_SPOT) hrm__spot_peak(w, d, len, a, ca, t0, t1, lit0, lit1, edge, nedge, &eq);
        mass = hrm__mix_mass((double)l->power / (double)eq.D, (double)eq.delta, (double)eq.D, t0, t1);
        k = plan->nmix;
        if (plan->nmix == HRM_MAX_LIGHTS) {
            /* full: replace the lightest, where this one weighs more; the
               light left out has its peak a node (the warp resolves the
               others') */
            double least = HUGE_VAL;
            for (j = 0; j < plan->nmix; ++j) {
                double mj = hrm__mix_mass(plan->c[j], plan->delta[j], plan->D[j], t0, t1);
                if (mj < least) {
                    least = mj;
                    k = j;
                }
            }
            if (!(mass > least)) {
                hrm__plan_add(cand, &n, eq.delta, t0, t1);
                continue;
            }
            hrm__plan_add(cand, &n, (hrm_real)plan->delta[k], t0, t1);
        } else {
            plan->nmix++;
        }
        plan->delta[k] = (double)eq.delta;
        plan->D[k] = (double)eq.D;
        plan->c[k] = (double)l->power / (double)eq.D;
    }
    plan->t0 = (double)t0;
    plan->t1 = (double)t1;
    for (j = 0; j < plan->nmix; ++j) plan->a0[j] = atan(((double)t0 - plan->delta[j]) / plan->D[j]);
    if (plan->nmix > 1) {
        plan->u1 = hrm__mix_u(plan, plan->t1);
        hrm__mix_transitions(plan, t0, t1, cand, &n);
    }
    /* sorted, duplicates out, the first HRM_MAX_BREAKS along the ray */
    for (i = 1; i < n; ++i) {
        hrm_real x = cand[i];
        for (j = i; j > 0 && cand[j - 1] > x; --j) cand[j] = cand[j - 1];
        cand[j] = x;
    }
    for (i = 0; i < n && plan->nbreaks < HRM_MAX_BREAKS; ++i)
        if (plan->nbreaks == 0 || cand[i] > plan->breaks[plan->nbreaks - 1]) plan->breaks[plan->nbreaks++] = cand[i];
    options->breaks = plan->nbreaks ? plan->breaks : NULL;
    options->nbreaks = plan->nbreaks;
    memset(&options->warp, 0, sizeof options->warp);
    plan->last_u = -1; /* u >= 0: no inversion kept yet */
    if (plan->nmix == 0 && line_res >= 0) {
        options->warp = line;
    } else if (plan->nmix == 1) {
        options->warp.kind = HRM_WARP_EQUIANGULAR;
        options->warp.delta = (hrm_real)plan->delta[0];
        options->warp.D = (hrm_real)plan->D[0];
    } else if (plan->nmix > 1) {
        /* each light's resolution weighed by its share of u, which is
           about its share of L (the largest alone warned on 15% of a
           check's float answers, 10% of them within rtol) */
        for (j = 0; j < plan->nmix; ++j)
            plan->res += hrm__light_res(plan->delta[j], plan->D[j], (double)t0, (double)t1) *
                         hrm__mix_mass(plan->c[j], plan->delta[j], plan->D[j], t0, t1) / plan->u1;
        options->warp.kind = HRM_WARP_USER;
        options->warp.user = plan;
        options->warp.t_of_u = hrm__mix_t_of_u;
        options->warp.dt_du = hrm__mix_dt_du;
        options->warp.u_of_t = hrm__mix_u_of_t;
    }
    return HRM_OK;
fail:
    memset(plan, 0, sizeof *plan);
    return st;
}

/* ---------------------------------------------------------------------- */
/* Evaluation of one abscissa                                             */
/* ---------------------------------------------------------------------- */

/* Evaluate the medium and the source at parameter p: every callback at most
   once, absent terms never. */
/* exp(-tau) at a node: the closed form evaluated with the node, else from
   the tau the rule computed. */
static HRM_DEVICE hrm_real hrm__att(const hrm__ctx *c, const hrm__pt *pt, int i, hrm_real tau)
{
    return c->closed ? pt->tr[i] : HRM_EXP(-tau);
}

/* tau from the transmittance callback's Tr (an underflowed Tr counts as
   the smallest normal number's tau). */
static HRM_DEVICE void hrm__neg_log(const hrm_real tr[HRM__CH], hrm_real tau[HRM__CH])
{
    hrm_real tiny = HRM__TINY;
    int i;
    for (i = 0; i < HRM__CH; ++i) tau[i] = -HRM_LOG(tr[i] > tiny ? tr[i] : tiny);
}

static HRM_DEVICE void hrm__tau_of_tr(hrm__pt *pt) { hrm__neg_log(pt->tr, pt->tau); }

/* tau(t0, t0 + off) where it has a closed form (homogeneous, the
   transmittance callback) or the layer holds it. */
static HRM_DEVICE void hrm__tau_of(hrm__ctx *c, hrm_real off, hrm_real tau[HRM__CH])
{
    hrm_real tr[HRM__CH];
    int i;
    if (c->homog) {
        for (i = 0; i < HRM__CH; ++i) tau[i] = c->st[i] == 0 ? 0 : c->st[i] * off;
    } else if (c->decoupled) {
        hrm__tau_at(c, c->tau, off, tau, 0);
    } else {
        hrm__tr_call(c, hrm__abscissa(c, off), tr);
        hrm__neg_log(tr, tau);
    }
}

/* Tr and tau at a node from tau's closed form or the layer; with the
   medium check, sigma_t there too, at offset s_off (a node at a
   breakpoint is sampled on its piece's side: so is the layer's sigma_t,
   from the panel on that side). */
static HRM_DEVICE void hrm__node_tr(hrm__ctx *c, hrm__pt *pt, hrm_real s_off)
{
    int i;
    if (c->mcheck) {
        hrm__tau_at(c, c->tau, pt->off, pt->tau, s_off == pt->off ? pt->sg : 0);
        if (s_off != pt->off) {
            hrm_real tau[HRM__CH];
            hrm__tau_at(c, c->tau, s_off, tau, pt->sg);
        }
        for (i = 0; i < HRM__CH; ++i) {
            pt->sg[i] *= pt->J;
            if (!(pt->sg[i] <= c->range)) pt->sg[i] = 0; /* (a check only) */
        }
    } else {
        hrm__tau_of(c, pt->off, pt->tau);
    }
    for (i = 0; i < HRM__CH; ++i) pt->tr[i] = HRM_EXP(-pt->tau[i]);
}

/* The memo's bin of abscissa s: a multiplicative hash of its bits (0 and
   -0, which compare equal, in one bin). */
static HRM_DEVICE int hrm__memo_bin(hrm_real s)
{
    uint64_t x = 0;
    if (s != 0) memcpy(&x, &s, sizeof s);
    return (int)((x * 0x9E3779B97F4A7C15ull) >> 57) % HRM__MEMO_BINS;
}

/* hrm__eval, step 1: the memo. Where abscissa s was evaluated lately (or
   is the ray's end), its callbacks' values are taken again: 1. */
static HRM_DEVICE int hrm__memo_hit(hrm__ctx *c, hrm_real p, hrm_real s, hrm_real s_raw, hrm__pt *pt)
{
    int i, k;
    if (!c->use_memo) return 0;
    k = c->nmemo;
    if (s <= c->memo_max && c->memo_bin[hrm__memo_bin(s)])
        for (k = 0; k < c->nmemo && c->memo_s[k] != s; ++k) {}
    if (k == c->nmemo) {
        if (!(c->have_end && s == c->s_end)) return 0;
        k = HRM__MEMO;
    }
    /* A warp's node that t cannot tell from another (a ray farther from
       the origin than it is long): the integrand is sampled as a
       staircase in t, which no estimate sees (the equiangular map of a
       light 1e-12 from a ray 1e-6 long at 1e9: L 64% low with HRM_OK).
       hrm__finish warns. (Not one node computed twice, its p a few ulps
       apart: a pair's node reached by two sums, on a ray clipped to a
       cloud's bounds under a warp, warned for nothing; nor nodes moved
       inside their piece, 64 ulps from a breakpoint, onto one abscissa: a
       slab's face at t = 15, the distance warp, warned on answers within
       1e-3 rtol.) */
    if (k < HRM__MEMO && c->warp != HRM_WARP_NONE && HRM_FABS(c->t0) > c->T && s == s_raw &&
        HRM_FABS(c->memo[k].p - p) >
            8 * HRM__EPS * (HRM_FABS(p) > HRM_FABS(c->memo[k].p) ? HRM_FABS(p) : HRM_FABS(c->memo[k].p)))
        c->unresolved = 1;
    /* the callbacks' values at s again; Tr from the node's own offset (it
       resolves t0 + off finer than s does) */
    if (c->homog || c->decoupled) {
        hrm__node_tr(c, pt, pt->off + (s - s_raw));
    } else {
        memcpy(pt->tr, c->memo[k].tr, sizeof pt->tr);
        hrm__tau_of_tr(pt);
    }
    for (i = 0; i < HRM__CH; ++i) {
        pt->gq[i] = c->memo[k].q[i] * pt->J;
        pt->gs[i] = c->need_st ? c->memo[k].st[i] * pt->J : 0;
    }
    return 1;
}

/* All three coefficients at s: the constants, or the sigma callbacks;
   returns the medium evaluations made. */
static HRM_DEVICE int hrm__coeffs_all(hrm__ctx *c, hrm_real s, hrm_real sa[HRM__CH], hrm_real ss[HRM__CH],
                                      hrm_real st[HRM__CH])
{
    if (!c->homog) return hrm__coeffs(c, s, 1, 1, 1, sa, ss, st);
    memcpy(sa, c->sa, sizeof(hrm_real) * HRM__CH);
    memcpy(ss, c->ss, sizeof(hrm_real) * HRM__CH);
    memcpy(st, c->st, sizeof(hrm_real) * HRM__CH);
    return 0;
}

/* hrm__eval, step 2: the medium at s (sa, ss, st: the coefficients the
   source and tau need) and Tr at the node, from wherever tau comes. */
static HRM_DEVICE void hrm__medium_at(hrm__ctx *c, hrm_real s, hrm_real s_raw, hrm__pt *pt, hrm_real sa[HRM__CH],
                           hrm_real ss[HRM__CH], hrm_real st[HRM__CH])
{
    int i, medium, st_known;
    if (c->homog) {
        hrm__coeffs_all(c, s, sa, ss, st);
        if (c->tr_at_nodes) hrm__node_tr(c, pt, pt->off + (s - s_raw));
        return;
    }
    /* sigma_t too where the medium check runs: the layer's check below
       reads it (with sigma_a and sigma_s apart, one more call where the
       source wants only one of them) */
    st_known = c->need_st || c->mcheck;
    medium = hrm__coeffs(c, s, c->use_le && !c->per_length, c->use_li, st_known, sa, ss, st);
    if (c->decoupled) {
        const hrm__tpanel *tp;
        hrm__node_tr(c, pt, pt->off + (s - s_raw));
        /* sigma_t here above 1.5 times every sigma_t the layer's panel
           sampled (where only sigma_a or sigma_s is known, the larger of
           them): the panel missed something between its samples (a dense
           slab; a bump narrower than their spacing: nested Simpson, rtol
           1e-3, a Gaussian bump to 2.2 times the medium, 0.03 wide on a
           unit ray: L 44 rtol off with HRM_OK if sigma_s alone is held
           against twice the samples); hrm__dispatch samples it there and
           solves again */
        tp = &c->tau->tab[c->tau->hit % c->tau->ntab];
        /* (not at a breakpoint, whose sample is on the other panel's side;
           not at t0, where the first panel sampled sigma_t itself and
           hrm__tau_at names no panel: the panel asked for last, read
           instead, holds a dense start against a thin panel further on
           and solves the ray twice, Gauss-Kronrod 339 evaluations for
           173) */
        for (i = 0; i < HRM__CH && c->tau->count > 0 && !c->layer_miss && s == s_raw && pt->off > 0; ++i) {
            hrm_real lower = st_known ? st[i] : sa[i] > ss[i] ? sa[i] : ss[i];
            /* (nor a node the layer was taught after such a miss: its
               panel's fit holds the sample within tau's tolerance, weighed
               by Tr there, and a panel that did not sample above it says
               nothing new; a wisp behind a cloud's core would otherwise
               repeat the solve 8 times and warn) */
            if (lower > HRM__R(1.5) * tp->smax[i] + HRM__R(1e-30) && !hrm__tau_taught(c->tau, pt->off)) {
                c->layer_miss = 1;
                c->miss_off = pt->off;
                c->miss_s = s;
            }
        }
        /* the coefficients the source did not ask for read as zero again
           (sigma_t fetched for this check alone; decoupled tau needs it
           nowhere else) */
        if (c->mcheck) {
            if (!(c->use_le && !c->per_length)) hrm__fill(sa, HRM__CH, 0);
            if (!c->use_li) hrm__fill(ss, HRM__CH, 0);
        }
    } else if (c->src == HRM__TAU_STREAM) {
        hrm__stream_to(c, pt->off, 0, st);
        for (i = 0; i < HRM__CH; ++i) {
            pt->tau[i] = c->sm.tau[i];
            pt->tr[i] = HRM_EXP(-pt->tau[i]);
        }
    } else if (c->closed) {
        if (hrm__tr_call(c, s, pt->tr)) medium = 0; /* counted there: one per abscissa */
        hrm__tau_of_tr(pt);
        if (c->mcheck) {
            /* the medium check's sigma_t ds/dp: the node's own */
            for (i = 0; i < HRM__CH; ++i) {
                pt->sg[i] = st[i] * pt->J;
                if (!(pt->sg[i] <= c->range)) pt->sg[i] = 0; /* (a check only) */
            }
            if (!(c->use_le && !c->per_length)) hrm__fill(sa, HRM__CH, 0);
            if (!c->use_li) hrm__fill(ss, HRM__CH, 0);
        }
    }
    c->stats.medium_evals += medium;
}

/* hrm__eval, step 3: the source S = sigma_a Le + sigma_s Li at s into q
   (a term whose coefficient vanishes in every channel is not called: no
   shadow ray where nothing scatters), and the largest S / sigma_t seen
   (the weighted mean of Le and Li by sigma_a and sigma_s; where sigma_t
   is not known here, the larger of the two) for the bound on L. */
static HRM_DEVICE HRM__CALL void hrm__source(hrm__ctx *c, hrm_real s, const hrm_real sa[HRM__CH], const hrm_real ss[HRM__CH],
                        const hrm_real st[HRM__CH], hrm_real q[HRM__CH])
{
    const hrm_medium *m = c->m;
    hrm_real v[HRM__CH], vmax[HRM__CH], e[HRM__CH];
    /* sigma_t at the node: the constant, the nodes' own sample (coupled
       tau, the stream, the RTE form, or the medium check, which fetches
       it), or sigma_a + sigma_s where no sigma_t callback is given */
    int i, em = 0, sc = 0, called, st_node = c->need_st || (c->mcheck && m->sigma_t),
        sig_known = c->homog || st_node || !m->sigma_t;
    for (i = 0; i < HRM__CH; ++i) {
        em |= c->per_length || sa[i] > 0;
        sc |= ss[i] > 0;
        q[i] = 0;
        vmax[i] = 0;
    }
    em &= c->use_le && c->status == HRM_OK;
    sc &= c->use_li;
    called = em;
    if (em) {
        m->Le(m->user, s, v);
        hrm__check(c, v, 3);
        for (i = 0; i < HRM__CH; ++i) {
            e[i] = c->per_length ? v[i] : sa[i] * v[i];
            q[i] += e[i];
            vmax[i] = v[i];
        }
    }
    if (sc && c->status == HRM_OK) {
        called = 1;
        m->Li(m->user, s, v);
        hrm__check(c, v, 3);
        for (i = 0; i < HRM__CH; ++i) {
            q[i] += ss[i] * v[i];
            if (v[i] > vmax[i]) vmax[i] = v[i];
        }
    }
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real sig = c->homog ? c->st[i] : st_node ? st[i] : sa[i] + ss[i], b;
        if (!(HRM_FABS(q[i]) <= c->range)) {
            if (c->status == HRM_OK) c->status = HRM_ERR_RANGE;
            q[i] = 0;
        }
        b = sig_known && sig > 0 ? q[i] / sig : vmax[i];
        if (b > c->src_max[i]) c->src_max[i] = b;
        /* the emission's part (hrm__emission_miss) */
        if (em && sig_known && sig > 0 && e[i] > c->em_max[i] * sig) c->em_max[i] = e[i] / sig;
    }
    c->stats.evals += called;
}

/* hrm__eval, step 4: the node's values in the memo. */
static HRM_DEVICE void hrm__memo_store(hrm__ctx *c, hrm_real p, hrm_real s, const hrm_real q[HRM__CH],
                            const hrm_real st[HRM__CH], const hrm__pt *pt)
{
    int k = s == c->s_end ? HRM__MEMO : c->memo_next;
    c->memo[k].s = s;
    if (k < HRM__MEMO) {
        int b = hrm__memo_bin(s);
        if (c->nmemo == HRM__MEMO) c->memo_bin[c->memo_sbin[k]]--; /* (overwritten) */
        c->memo_s[k] = s;
        c->memo_sbin[k] = (unsigned char)b;
        c->memo_bin[b]++;
        if (!(s <= c->memo_max)) c->memo_max = s;
    }
    c->memo[k].p = p;
    memcpy(c->memo[k].q, q, sizeof c->memo[k].q);
    memcpy(c->memo[k].st, st, sizeof c->memo[k].st);
    memcpy(c->memo[k].tr, pt->tr, sizeof pt->tr);
    if (k < HRM__MEMO) {
        c->memo_next = (k + 1) % HRM__MEMO;
        if (c->nmemo < HRM__MEMO) c->nmemo++;
    } else {
        c->have_end = 1;
    }
}

/* One node at p: its abscissa s = t(p) (on its piece's side of a
   breakpoint), Tr there, and the source times dt/dp (gq) and sigma_t
   times dt/dp (gs, where the rules integrate tau), by the four steps
   above. */
static HRM_DEVICE HRM__CALL void hrm__eval(hrm__ctx *c, hrm_real p, hrm__pt *pt)
{
    hrm_real sa[HRM__CH], ss[HRM__CH], st[HRM__CH], q[HRM__CH], s, s_raw;
    int i;

    hrm__map(c, p, &pt->off, &pt->J);
    pt->p = p;
    s_raw = hrm__abscissa(c, pt->off);
    s = hrm__side(c, s_raw);
    if (hrm__memo_hit(c, p, s, s_raw, pt)) return;
    hrm__medium_at(c, s, s_raw, pt, sa, ss, st);
    if (c->coupled) {
        /* Coupled tau: the rules integrate sigma_t - sbar in the warped
           variable and sbar over the distance in t exactly, so a constant
           sigma_t is exact under any warp. */
        if (!c->have_sbar) {
            memcpy(c->sbar, st, sizeof st);
            c->have_sbar = 1;
        }
    }
    hrm__source(c, s, sa, ss, st, q);
    if (c->coupled)
        for (i = 0; i < HRM__CH; ++i) st[i] -= c->sbar[i];
    for (i = 0; i < HRM__CH; ++i) {
        pt->gq[i] = q[i] * pt->J;
        pt->gs[i] = c->need_st ? st[i] * pt->J : 0; /* a closed form has tau already */
        if (!(HRM_FABS(pt->gq[i]) <= c->range && HRM_FABS(pt->gs[i]) <= c->range)) {
            if (c->status == HRM_OK) c->status = HRM_ERR_RANGE; /* a warp's Jacobian */
            pt->gq[i] = pt->gs[i] = 0;
        }
    }
    if (c->use_memo) hrm__memo_store(c, p, s, q, st, pt);
}

/* Closed-form Tr(t0, t1): no callback for a homogeneous medium, one
   transmittance call otherwise. */
static HRM_DEVICE void hrm__closed_tr(hrm__ctx *c, hrm_real Tr[HRM__CH])
{
    int i;
    if (c->homog) {
        for (i = 0; i < HRM__CH; ++i)
            Tr[i] = c->st[i] == 0 ? 1 : HRM_EXP(-c->st[i] * c->T); /* no 0 * inf */
        return;
    }
    hrm__tr_call(c, c->s_end, Tr);
}

/* ---------------------------------------------------------------------- */
/* Fixed-step quadrature                                                   */
/* ---------------------------------------------------------------------- */

/* The rectangle rule and Monte Carlo: N increasing nodes of equal weight
   (pb - pa)/N. Without a closed form, tau at each node comes from the same
   sigma_t samples by the trapezoid rule between consecutive nodes (a
   constant one-sided piece before the first and after the last): second
   order, as the midpoint rule itself. kind: 0 rectangle, 1 stratified,
   2 uniform Monte Carlo. Uniform samples are generated already sorted
   (the minimum of n uniforms is 1 - U^(1/n), and the rest are uniform
   above it), so tau accumulates without storing them. */
/* *s += x, compensated (Neumaier 1974): *e holds what the rounding of
   *s lost and is fed back with the next term, so that *s stays within an
   ulp or two of the exact sum however many terms it takes (float sums of
   N = 1.6e7 samples stagnated: L 13% low with HRM_OK). A few additions a
   sample; the fixed-step rules' sums of L and tau. */
static HRM_DEVICE void hrm__sum(hrm_real *s, hrm_real *e, hrm_real x)
{
    hrm_real d = x + *e, t = *s + d;
    *e = HRM_FABS(*s) >= HRM_FABS(d) ? (*s - t) + d : (d - t) + *s;
    *s = t;
}

static HRM_DEVICE HRM__CALL void hrm__nodes(hrm__ctx *c, int N, int kind, hrm_real xi,
                       hrm_real L[HRM__CH], hrm_real tau[HRM__CH])
{
    hrm_real eL[HRM__CH] = {0}, eT[HRM__CH] = {0}, ex = 0; /* hrm__sum's */
    hrm_real w = (c->pb - c->pa) / (hrm_real)N, x = 0, prev_p = c->pa, prev_off = 0, end_off = 0, J;
    hrm_real prev_gs[HRM__CH];
    hrm__pt pt;
    int k, i;

    /* coupled tau: the piece's ends (breakpoints cut the ray into
       pieces), so that sbar's distance runs from the piece's start to its
       end, not from t0 or to t1 (which counted the ray before and after
       the piece again) */
    if (c->coupled) {
        hrm__map(c, c->pa, &prev_off, &J);
        hrm__map(c, c->pb, &end_off, &J);
    }
    hrm__fill(prev_gs, HRM__CH, 0);
    for (k = 0; k < N; ++k) {
        hrm_real p;
        if (kind == 2) {
            hrm_real u = 1 - hrm__uniform(&c->rng); /* (0, 1] */
            hrm__sum(&x, &ex, (1 - x) * -HRM_EXPM1(HRM_LOG(u) / (hrm_real)(N - k)));
            p = c->pa + (c->pb - c->pa) * x;
        } else {
            if (kind == 1) xi = hrm__uniform(&c->rng);
            p = c->pa + (c->pb - c->pa) * (((hrm_real)k + xi) / (hrm_real)N);
        }
        hrm__eval(c, p, &pt);
        for (i = 0; i < HRM__CH; ++i) {
            if (c->coupled) {
                hrm_real mean = k ? (prev_gs[i] + pt.gs[i]) / 2 : pt.gs[i];
                hrm__sum(&tau[i], &eT[i], mean * (p - prev_p) + c->sbar[i] * (pt.off - prev_off));
                if (tau[i] < 0) tau[i] = eT[i] = 0;
                prev_gs[i] = pt.gs[i];
            }
            hrm__sum(&L[i], &eL[i], w * hrm__att(c, &pt, i, tau[i]) * pt.gq[i]);
        }
        prev_p = p;
        prev_off = pt.off;
        c->stats.steps++;
        if (c->status != HRM_OK) return;
    }
    for (i = 0; i < HRM__CH; ++i) L[i] += eL[i];
    if (c->coupled)
        for (i = 0; i < HRM__CH; ++i) {
            hrm__sum(&tau[i], &eT[i], prev_gs[i] * (c->pb - prev_p) + c->sbar[i] * (end_off - prev_off));
            tau[i] += eT[i];
            if (tau[i] < 0) tau[i] = 0;
        }
}

/* (1 - exp(-x)) / x for x >= 0, without cancellation near 0 and 0 at
   x = inf: the fraction of a step's length that a constant extinction
   leaves effective. */
static HRM_DEVICE hrm_real hrm__phi1(hrm_real x)
{
    if (!(x > 0)) return 1;
    if (x < HRM__R(1e-5)) return 1 - x / 2 + x * x / 6;
    return -HRM_EXPM1(-x) / x;
}

/* ---------------------------------------------------------------------- */
/* Exponentially fitted rules                                              */
/* ---------------------------------------------------------------------- */

static HRM_DEVICE void hrm__warn(hrm__ctx *c, hrm_status w);

/* The inverse of the Legendre Vandermonde matrix V[j][k] = P_k(y_j) of
   nodes y[0..n) (ascending, in [-1, 1]) by Gauss-Jordan with partial
   pivoting (n <= 15; near-Gauss nodes, and a pair's at most 8, keep it
   well conditioned), into I (row k: P_k's coefficient in each node's
   Lagrange polynomial, so that sum_j I[k][j] f_j is the k-th Legendre
   coefficient of the polynomial through f). V and I are n x n arrays of
   row length ld; V is overwritten. The exponential fits (hrm__efit_init)
   and the pairs' kink test (hrm__ivp_adaptive) share it. */
static HRM_DEVICE HRM__CALL void hrm__legendre_inverse(const hrm_real *y, int n, int ld, hrm_real *V, hrm_real *I)
{
    int j, k, r;
    for (j = 0; j < n; ++j) {
        hrm_real p0 = 1, p1 = y[j];
        for (k = 0; k < n; ++k) {
            hrm_real pk = k == 0 ? 1 : k == 1 ? y[j] : ((2 * (hrm_real)k - 1) * y[j] * p1 -
                                                       ((hrm_real)k - 1) * p0) / (hrm_real)k;
            if (k >= 2) {
                p0 = p1;
                p1 = pk;
            }
            V[j * ld + k] = pk;
            I[j * ld + k] = j == k ? 1 : 0;
        }
    }
    for (k = 0; k < n; ++k) {
        int piv = k;
        hrm_real d;
        for (r = k + 1; r < n; ++r)
            if (HRM_FABS(V[r * ld + k]) > HRM_FABS(V[piv * ld + k])) piv = r;
        for (j = 0; j < n; ++j) {
            hrm_real t = V[k * ld + j];
            V[k * ld + j] = V[piv * ld + j];
            V[piv * ld + j] = t;
            t = I[k * ld + j];
            I[k * ld + j] = I[piv * ld + j];
            I[piv * ld + j] = t;
        }
        d = V[k * ld + k];
        for (j = n - 1; j >= 0; --j) I[k * ld + j] /= d;
        for (j = n - 1; j >= k; --j) V[k * ld + j] /= d;
        for (r = 0; r < n; ++r) {
            hrm_real f = V[r * ld + k];
            if (r == k || f == 0) continue;
            for (j = k; j < n; ++j) V[r * ld + j] -= f * V[k * ld + j];
            for (j = 0; j < n; ++j) I[r * ld + j] -= f * I[k * ld + j];
        }
    }
}

/* The fit on nodes y[0..n) (ascending, in [-1, 1]): F->A the Legendre
   Vandermonde matrix's inverse (hrm__legendre_inverse; V alone in the
   frame). */
static HRM_DEVICE HRM__CALL HRM__NOINLINE void hrm__efit_init(hrm__efit *F, const hrm_real *y, int n)
{
    hrm_real V[HRM__EFIT_MAX * HRM__EFIT_MAX];
    int j;
    HRM_ASSERT(n * n <= F->cap);
    F->n = n;
    for (j = 0; j < n; ++j) F->y[j] = y[j];
    hrm__legendre_inverse(y, n, n, V, F->A);
}

/* s_k = exp(-b) i_k(b), k = 0..n-1, b >= 0 (i_k the modified spherical
   Bessel functions of the first kind): int_-1^1 P_k(y) exp(-b (y + 1)) dy
   = 2 (-1)^k s_k. The power series for b <= 1, Miller's backward
   recurrence i_(k-1) = i_(k+1) + (2k + 1) / b i_k from well above n for
   b < 100, the forward one (stable once b > n^2 / 2) above; s_0 =
   (1 - exp(-2b)) / (2b) without cancellation, no overflow at any b. */
static HRM_DEVICE HRM__CALL void hrm__msb(hrm_real b, int n, hrm_real s[HRM__EFIT_MAX])
{
    int k;
    if (!(b > 0)) {
        for (k = 0; k < n; ++k) s[k] = k == 0 ? 1 : 0;
        return;
    }
    if (b <= 1) {
        hrm_real e = HRM_EXP(-b), lead = 1;
        for (k = 0; k < n; ++k) {
            hrm_real term = 1, sum = 1, x = b * b / 2;
            int m;
            if (k > 0) lead *= b / (2 * (hrm_real)k + 1);
            for (m = 1; m < 40; ++m) {
                term *= x / ((hrm_real)m * (2 * (hrm_real)k + 2 * (hrm_real)m + 1));
                sum += term;
                if (term < HRM__EPS * sum) break;
            }
            s[k] = e * lead * sum;
        }
        return;
    }
    s[0] = -HRM_EXPM1(-2 * b) / (2 * b);
    if (b < 100) {
        int top = n + 20 + (int)(5 * HRM_SQRT(b)), j;
        hrm_real next = 0, cur = HRM__R(1e-20), scale;
        hrm_real keep[HRM__EFIT_MAX];
        for (j = top; j >= 1; --j) {
            hrm_real prev = next + (2 * (hrm_real)j + 1) / b * cur;
            next = cur;
            cur = prev; /* i_(j-1) */
            if (j - 1 < n) keep[j - 1] = cur;
            if (cur > HRM__R(1e20)) {
                int q;
                for (q = j - 1; q < n; ++q) keep[q] *= HRM__R(1e-20);
                cur *= HRM__R(1e-20);
                next *= HRM__R(1e-20);
            }
        }
        scale = s[0] / keep[0];
        for (k = 1; k < n; ++k) s[k] = keep[k] * scale;
        return;
    }
    if (n > 1) s[1] = ((1 + HRM_EXP(-2 * b)) * b / 2 + HRM_EXPM1(-2 * b) / 2) / (b * b);
    for (k = 1; k + 1 < n; ++k) s[k + 1] = s[k - 1] - (2 * (hrm_real)k + 1) / b * s[k];
}

/* Under a warp the fit runs in the warp's variable, where tau bends and
   ds/dp varies: the bound by the fitted values (S ds/dp) does not bound
   the step in t (an equiangular step measured 15 times above sup(S /
   sigma_t) (1 - Tr)). So the step is also kept within the nodes' least
   and largest S times the integral of Tr over the step in t, Tr taken
   exponential between neighbouring nodes (and beyond the outer nodes at
   their neighbours' rate, for Gauss nodes): exact in a homogeneous
   medium, where it gives L <= sup(S / sigma_t) (1 - Tr); widened by the
   spread of those rates elsewhere, so that it never cuts a good value
   where sigma_t varies. What it cuts is added to un. */
static HRM_DEVICE HRM__CALL void hrm__efit_bound_t(const hrm__efit *F, const hrm__pt *pt, hrm_real hl, int last, int i,
                              hrm_real *out, hrm_real *un)
{
    hrm_real smin = 0, smax = 0, mt = 0, rmin = 0, rmax = 0, d, lo, hi;
    int j, any = 0;
    for (j = 0; j < F->n; ++j) {
        hrm_real S = pt[j].J > 0 ? pt[j].gq[i] / pt[j].J : 0;
        if (j == 0 || S < smin) smin = S;
        if (j == 0 || S > smax) smax = S;
    }
    for (j = -1; j <= last; ++j) {
        /* the piece from node j to j + 1; -1 and last: the outer pieces */
        int k = j < 0 ? 0 : j == last ? last - 1 : j;
        hrm_real dt = pt[k + 1].off - pt[k].off, rate, len, tl;
        rate = dt > 0 ? (pt[k + 1].tau[i] - pt[k].tau[i]) / dt : 0;
        if (!(rate > 0)) rate = 0;
        if (j < 0) {
            len = pt[0].J * hl * (F->y[0] + 1);
            tl = pt[0].tau[i] - rate * len;
            if (tl < 0) tl = 0; /* tau >= 0 (exp(137) overflowed float) */
        } else if (j == last) {
            len = pt[last].J * hl * (1 - F->y[last]);
            tl = pt[last].tau[i];
        } else {
            len = dt;
            tl = pt[j].tau[i];
        }
        if (!(len > 0)) continue;
        mt += HRM_EXP(-tl) * len * hrm__phi1(rate * len);
        if (!any || rate < rmin) rmin = rate;
        if (!any || rate > rmax) rmax = rate;
        any = 1;
    }
    d = rmin > 0 ? (rmax - rmin) / rmin : rmax > 0 ? 1 : 0;
    if (d > 1) d = 1;
    lo = smin * mt * (1 - d);
    hi = smax * mt * (1 + d);
    if (*out < lo) {
        *un += lo - *out;
        *out = lo;
    } else if (*out > hi) {
        *un += *out - hi;
        *out = hi;
    }
}

/* One panel of half-width hl (in p) by the fit on its nodes pt[0..n):
   per channel, b is the slope of tau across the nodes per unit y, the
   source times Tr / exp(-b (y + 1)) is interpolated by the nodes'
   polynomial and integrated against exp(-b (y + 1)) exactly. A
   homogeneous medium (tau linear in p) with a polynomial source of degree
   n - 1 is exact at any width and depth. The sum is kept within the
   nodes' least and largest value times the weight's integral: never
   negative, never above the bound however thick. Also mass: the weight's
   integral times exp(-tau at y = -1) (the scale of the embedded
   estimates). g receives the fitted values. Where a transmittance
   callback's Tr underflowed already at the second node, tau's slope is
   only bounded below and the step's sum an upper bound (the true one lies
   in [0, out]): un receives it, else 0. The adaptive rules count it as
   error (they refine there until the nodes see tau), the fixed ones in
   c->unsure (hrm__finish warns where it matters). */
static HRM_DEVICE HRM__CALL void hrm__efit_panel(const hrm__ctx *c, const hrm__efit *F, const hrm__pt *pt, hrm_real hl,
                            hrm_real out[HRM__CH], hrm_real mass[HRM__CH],
                            hrm_real (*g)[HRM__CH], hrm_real un[HRM__CH])
{
    int n = F->n, i, j, k;
    hrm_real s[HRM__EFIT_MAX] = {0};
    hrm_real w[HRM__EFIT_MAX], b_prev = -1;
    /* hrm__neg_log's cap, where tau comes from the callback's Tr */
    hrm_real under = c->tau_from_tr ? -HRM_LOG(HRM__TINY) : HRM__R(HUGE_VAL);
    for (i = 0; i < HRM__CH; ++i) {
        /* the slope from the first and the last node whose tau is known: a
           transmittance callback's Tr that underflowed says only that tau
           is at least -ln(smallest normal); such nodes are taken on the
           line (their Tr S is below the smallest normal number anyway) */
        int last = n - 1;
        hrm_real b, tref, acc = 0, lo = 0, hi = 0, m, scale, lf[HRM__EFIT_MAX];
        int unsure, whole = 0;
        while (last > 1 && pt[last].tau[i] >= under) --last;
        /* known only as a lower bound: the slope, and so the result */
        unsure = pt[last].tau[i] >= under && pt[0].tau[i] < under;
        /* the least slope between neighbouring nodes: tau over the nodes
           then lies on or above the line, so no fitted value exceeds its
           node's source (a chord's slope, where tau bends, would multiply
           the values below the chord by up to exp(what tau bends) and the
           polynomial through them with it). Linear tau: its slope. */
        b = HRM__R(HUGE_VAL);
        for (j = 0; j < last; ++j) {
            hrm_real sl = (pt[j + 1].tau[i] - pt[j].tau[i]) / (F->y[j + 1] - F->y[j]);
            if (sl < b) b = sl;
        }
        if (!(b > 0) || !(b < HRM__R(HUGE_VAL))) b = 0;
        if (c->expo == 2) {
            /* the whole integrand's decay: the least slope of -ln(Tr S)
               between neighbours, where the source is positive at every
               node and falls faster than Tr alone (a light seen through
               the medium); a source of the form C exp(-mu t) is then
               factored out with Tr, exactly */
            hrm_real bf = HRM__R(HUGE_VAL);
            for (j = 0; j <= last && bf > b; ++j) {
                if (!(pt[j].gq[i] > 0)) break;
                lf[j] = HRM_LOG(pt[j].gq[i]) - pt[j].tau[i];
                if (j > 0) {
                    hrm_real sl = (lf[j - 1] - lf[j]) / (F->y[j] - F->y[j - 1]);
                    if (sl < bf) bf = sl;
                }
            }
            whole = last == n - 1 && j > last && bf > b && bf < HRM__R(HUGE_VAL);
            /* the fitted exponential at y = -1 (the scale below) within
               1 / TINY: with a slope of 1e17 it was exp(5e14), infinite,
               while every sample had underflowed (0 times inf: NaN) */
            if (whole && !(lf[0] + bf * (F->y[0] + 1) < -HRM_LOG(HRM__TINY))) whole = 0;
            if (whole) b = bf;
        }
        /* tau at y = -1 on the line not below 0 (exp(-tref) <= 1): the
           least slope can overshoot where tau bends before the first node */
        if (!whole && b * (F->y[0] + 1) > pt[0].tau[i]) b = pt[0].tau[i] / (F->y[0] + 1);
        tref = pt[0].tau[i] - b * (F->y[0] + 1);
        if (tref < 0) tref = 0; /* its rounding: an ulp of tau 1e77 is 1e61 */
        if (b != b_prev) { /* the weights, once per slope (grey media: once) */
            hrm__msb(b, n, s);
            for (j = 0; j < n; ++j) {
                w[j] = 0;
                for (k = 0; k < n; ++k) w[j] += F->A[k * n + j] * (k % 2 ? -2 : 2) * s[k];
            }
            b_prev = b;
        }
        for (j = 0; j < n; ++j) {
            /* relative to the first node, where x = 0 exactly (tref's
               rounding at tau ~ 1e21 was 1e5: exp of it overflowed) */
            hrm_real x = j > last ? 0 : -((pt[j].tau[i] - pt[0].tau[i]) - b * (F->y[j] - F->y[0]));
            /* in logarithms where the source is factored too, relative to
               the first node: at most 1, never overflowing */
            if (whole) g[j][i] = HRM_EXP(lf[j] - lf[0] + b * (F->y[j] - F->y[0]));
            /* x <= 0 exactly (b is the least slope); its rounding, at a
               slope of 1e33, was +6e17 */
            else g[j][i] = pt[j].gq[i] * HRM_EXP(x < 0 ? x : 0);
            acc += w[j] * g[j][i];
            if (j == 0 || g[j][i] < lo) lo = g[j][i];
            if (j == 0 || g[j][i] > hi) hi = g[j][i];
        }
        m = 2 * s[0];
        scale = (whole ? HRM_EXP(lf[0] + b * (F->y[0] + 1)) : HRM_EXP(-tref)) * hl;
        /* what the limit takes off is an error the estimates must see */
        un[i] = acc < lo * m ? (lo * m - acc) * scale : acc > hi * m ? (acc - hi * m) * scale : 0;
        if (acc < lo * m) acc = lo * m;
        if (acc > hi * m) acc = hi * m;
        out[i] = acc * scale;
        mass[i] = m * scale;
        if (c->warp != HRM_WARP_NONE) hrm__efit_bound_t(F, pt, hl, last, i, &out[i], &un[i]);
        if (unsure) un[i] += out[i];
    }
}

/* The analytic march, what renderers ship (Hillaire 2015): N steps, one
   sample each (the midpoint, or one random offset per ray with jitter);
   over a step the source is taken constant and the extinction integrated
   exactly: dL = Tr(a) S dt (1 - exp(-dtau)) / dtau. dtau is sigma_t at
   the sample times dt (tau coupled, the default), or tau's closed form or
   the layer's between the step's ends. S dt is the sample's S times dt
   (no warp, distance and user warps: exact for a constant S / sigma_t,
   never above sup(S / sigma_t) (1 - Tr)), or under the equiangular warp
   gq du, S dt/du held constant over the step in u (Kulla and Fajardo
   2012). */
static HRM_DEVICE HRM__CALL void hrm__march(hrm__ctx *c, int N, hrm_real xi, hrm_real L[HRM__CH],
                       hrm_real tau[HRM__CH])
{
    hrm_real span = c->pb - c->pa, off_l, off_r, J, tl[HRM__CH];
    hrm_real under = -HRM_LOG(HRM__TINY); /* hrm__neg_log's cap */
    hrm_real eL[HRM__CH] = {0}, eT[HRM__CH] = {0}; /* hrm__sum's */
    hrm__pt pt;
    int k, i;

    hrm__map(c, c->pa, &off_l, &J);
    for (i = 0; i < HRM__CH; ++i) tl[i] = 0;
    if (c->closed) hrm__tau_of(c, off_l, tl);
    for (k = 0; k < N && c->status == HRM_OK; ++k) {
        hrm_real pl = c->pa + span * ((hrm_real)k / (hrm_real)N);
        hrm_real pr = k + 1 == N ? c->pb : c->pa + span * ((hrm_real)(k + 1) / (hrm_real)N);
        hrm_real dt, tr[HRM__CH];
        hrm__eval(c, pl + (pr - pl) * xi, &pt);
        hrm__map(c, pr, &off_r, &J);
        dt = off_r - off_l;
        if (dt < 0) dt = 0;
        if (c->closed) hrm__tau_of(c, off_r, tr);
        for (i = 0; i < HRM__CH; ++i) {
            /* the source times the step's width in t: under the
               equiangular warp S dt/du (gq) held constant over the step in
               u, as its sampling weighs a point light (Kulla and Fajardo
               2012): gq du, a mean source over the step of gq du / dt.
               Otherwise S at the sample times dt: exact for a constant
               S / sigma_t wherever the steps lie, where gq du would be
               first order under the distance warp (its dt/du, the 1 / Tr
               of sigma_ref, is what the step's extinction integrates) */
            hrm_real Sdt = c->warp != HRM_WARP_EQUIANGULAR ? (pt.J > 0 ? pt.gq[i] / pt.J : 0) * dt
                           : dt > 0                        ? pt.gq[i] * (pr - pl)
                                                           : 0;
            hrm_real dtau, dL;
            if (c->closed) {
                dtau = tr[i] - tl[i];
            } else {
                /* sigma_t at the sample (the rules' sigma_t - sbar, plus sbar) */
                hrm_real st = (pt.J > 0 ? pt.gs[i] / pt.J : 0) + c->sbar[i];
                dtau = (st > 0 ? st : 0) * dt;
                tr[i] = tau[i];
                hrm__sum(&tr[i], &eT[i], dtau);
            }
            if (!(dtau > 0)) dtau = 0;
            dL = Sdt * HRM_EXP(-(c->closed ? tl[i] : tau[i])) * hrm__phi1(dtau);
            hrm__sum(&L[i], &eL[i], dL);
            /* Tr underflowed within the step (transmittance callback):
               dtau only bounded below, dL above */
            if (c->tau_from_tr && tr[i] >= under && tl[i] < under) c->unsure[i] += dL;
            if (!c->closed) tau[i] = tr[i];
            tl[i] = tr[i];
        }
        off_l = off_r;
        c->stats.steps++;
    }
    for (i = 0; i < HRM__CH; ++i) {
        L[i] += eL[i];
        if (!c->closed) tau[i] += eT[i];
    }
}

/* Composite Simpson over N panels. Without a closed form, tau at the panel
   ends comes from Simpson's rule on the sigma_t samples, and at each panel's
   midpoint from the integral of the same parabola over the panel's first
   half, H/24 (5 f_a + 8 f_m - f_b): fourth order overall, no extra samples.
   tau is nondecreasing, so the midpoint value is kept between its
   neighbours (a thick, sharply varying medium could otherwise overshoot). */
/* One Simpson panel's parabola against the exact local exponential, added
   to L: a frame of its own, which a solve without a fit never holds. */
static HRM_DEVICE HRM__CALL HRM__NOINLINE void hrm__simpson_fit(hrm__ctx *c, const hrm__pt q[3], hrm_real H,
                                                                hrm_real L[HRM__CH], hrm_real eL[HRM__CH])
{
    hrm_real out[HRM__CH], mass[HRM__CH], g[3][HRM__CH], un[HRM__CH];
    int i;
    hrm__efit_panel(c, &c->ef[0], q, H / 2, out, mass, g, un);
    for (i = 0; i < HRM__CH; ++i) {
        hrm__sum(&L[i], &eL[i], out[i]);
        c->unsure[i] += un[i];
    }
}

static HRM_DEVICE HRM__CALL void hrm__simpson(hrm__ctx *c, int N, hrm_real L[HRM__CH], hrm_real tau[HRM__CH])
{
    hrm__pt q[3]; /* the panel's nodes, in a row for the fit */
    hrm__pt *const a = &q[0], *const mid = &q[1], *const b = &q[2];
    hrm_real ea[HRM__CH]; /* exp(-tau) * gq at the panel's left end */
    hrm_real span = c->pb - c->pa;
    hrm_real eL[HRM__CH] = {0}, eT[HRM__CH] = {0}; /* hrm__sum's */
    int k, i;

    hrm__eval(c, c->pa, a);
    for (i = 0; i < HRM__CH; ++i) ea[i] = hrm__att(c, a, i, 0) * a->gq[i];
    for (k = 0; k < N; ++k) {
        hrm_real pl = c->pa + span * ((hrm_real)k / (hrm_real)N);
        hrm_real pr = k + 1 == N ? c->pb : c->pa + span * ((hrm_real)(k + 1) / (hrm_real)N);
        hrm_real H = pr - pl;
        hrm__eval(c, pl + H / 2, mid);
        hrm__eval(c, pr, b);
        if (c->expo) {
            hrm__simpson_fit(c, q, H, L, eL);
            *a = *b;
            c->stats.steps++;
            if (c->status != HRM_OK) break;
            continue;
        }
        for (i = 0; i < HRM__CH; ++i) {
            hrm_real tm = 0, tb = 0, eb;
            if (c->coupled) {
                hrm_real e = eT[i];
                tb = tau[i];
                hrm__sum(&tb, &e, c->sbar[i] * (b->off - a->off) + H / 6 * (a->gs[i] + 4 * mid->gs[i] + b->gs[i]));
                tm = tau[i] + c->sbar[i] * (mid->off - a->off) +
                     H / 24 * (5 * a->gs[i] + 8 * mid->gs[i] - b->gs[i]);
                if (tb < tau[i]) {
                    tb = tau[i];
                    e = 0;
                }
                if (tm < tau[i]) tm = tau[i];
                if (tm > tb) tm = tb;
                eT[i] = e;
            }
            eb = hrm__att(c, b, i, tb) * b->gq[i];
            hrm__sum(&L[i], &eL[i], H / 6 * (ea[i] + 4 * hrm__att(c, mid, i, tm) * mid->gq[i] + eb));
            ea[i] = eb;
            tau[i] = tb;
        }
        *a = *b;
        c->stats.steps++;
        if (c->status != HRM_OK) break;
    }
    for (i = 0; i < HRM__CH; ++i) {
        L[i] += eL[i];
        tau[i] += eT[i];
    }
}

/* ---------------------------------------------------------------------- */
/* IVP steppers                                                            */
/* ---------------------------------------------------------------------- */

/* The right-hand side of either form at one evaluated abscissa.
   Optical depth: y = (tau, A), tau' = sigma_t, A' = exp(-tau) S.
   RTE (marched from t1 toward t0): y = (Tr, L), Tr' = sigma_t Tr,
   L' = sigma_t L - S, in p, so that stepping toward t0 gives Munoz eq. 1. */
static HRM_DEVICE void hrm__deriv(const hrm__ctx *c, const hrm__pt *pt, const hrm_real *y, hrm_real *k)
{
    int i;
    for (i = 0; i < HRM__CH; ++i) {
        if (c->rte) {
            k[i] = pt->gs[i] * y[i];
            k[HRM__CH + i] = pt->gs[i] * y[HRM__CH + i] - pt->gq[i];
        } else {
            k[i] = pt->gs[i];
            k[HRM__CH + i] = hrm__att(c, pt, i, y[i]) * pt->gq[i];
        }
    }
}

/* One explicit RK step from p to p_end = p + h from the sample at p.
   Stages sharing a node share one evaluation; the sample at p_end (a node
   c = 1) is returned in *end so that the next step reuses it: the result
   says whether it did. err (optional) receives h * sum (b_i - bh_i) k_i. */
/* The distinct nodes of a tableau in ascending order (the first stage at
   each), and W = the integral over [0, 1] of |prod (c - c_i)| over all but
   the last of them: the weight of the top term of the Newton series of
   the stage values (see hrm__rk_step). */
typedef struct hrm__nodes_info {
    int m, stage[HRM__MAX_STAGES];
    hrm_real c[HRM__MAX_STAGES], W;
    hrm_real bw[HRM__MAX_STAGES], ew[HRM__MAX_STAGES]; /* quadrature weights */
    /* rows m - 1 .. m - 4 of the nodes' Legendre Vandermonde inverse
       (hrm__legendre_inverse, on 2 c - 1): the top four Legendre
       coefficients on the step of the polynomial through values at the
       distinct nodes, row r at leg[r * m] (the kink test, hrm__leg_tail;
       set by hrm__nodes_legendre where m >= 6, in the adaptive pair
       driver's frame; NULL in a fixed step's) */
    const hrm_real *leg;
} hrm__nodes_info;

/* ni->leg (an adaptive pair's kink test, hrm__pair_tail): the four
   rows it reads of the inverse, pairs of 6 distinct nodes or more (a
   frame of its own: the inverse's 1 KiB is gone before the solve). */
static HRM_DEVICE HRM__NOINLINE void hrm__nodes_legendre(hrm__nodes_info *ni, hrm_real leg[4 * HRM__MAX_STAGES])
{
    hrm_real y[HRM__MAX_STAGES], V[HRM__MAX_STAGES * HRM__MAX_STAGES], I[HRM__MAX_STAGES * HRM__MAX_STAGES];
    int m = ni->m, j, r;
    if (m < 6) return;
    for (j = 0; j < m; ++j) y[j] = 2 * ni->c[j] - 1;
    hrm__legendre_inverse(y, m, HRM__MAX_STAGES, V, I);
    for (r = 0; r < 4; ++r)
        for (j = 0; j < m; ++j) leg[r * m + j] = I[(m - 1 - r) * HRM__MAX_STAGES + j];
    ni->leg = leg;
}

static HRM_DEVICE HRM__CALL void hrm__nodes_init(const hrm__tableau *tb, hrm__nodes_info *ni)
{
    int i, j, k;
    ni->m = 0;
    ni->leg = NULL;
    for (i = 0; i < tb->s; ++i) {
        for (j = 0; j < ni->m && ni->c[j] != tb->c[i]; ++j) {}
        if (j < ni->m) continue;
        for (k = ni->m; k > 0 && ni->c[k - 1] > tb->c[i]; --k) {
            ni->c[k] = ni->c[k - 1];
            ni->stage[k] = ni->stage[k - 1];
        }
        ni->c[k] = tb->c[i];
        ni->stage[k] = i;
        ni->m++;
    }
    /* When nothing feeds back (the optical-depth form with Tr known at
       every node) a step is a quadrature: the weights of the tableau's
       b and of b - bh gathered on the distinct nodes. */
    for (j = 0; j < ni->m; ++j) {
        ni->bw[j] = ni->ew[j] = 0;
        for (i = 0; i < tb->s; ++i)
            if (tb->c[i] == ni->c[j]) {
                ni->bw[j] += tb->b[i];
                if (tb->bh) ni->ew[j] += tb->b[i] - tb->bh[i];
            }
    }
    ni->W = 0;
    for (i = 0; i < 256; ++i) { /* midpoint rule: W needs no precision */
        hrm_real x = ((hrm_real)i + HRM__R(0.5)) / 256, pr = 1;
        for (k = 0; k + 1 < ni->m; ++k) pr *= x - ni->c[k];
        ni->W += HRM_FABS(pr) / 256;
    }
}

/* The fits a method's rules use: Simpson's three nodes; Gauss-Kronrod's
   Kronrod nodes and its Gauss nodes; a pair's distinct nodes. */
static HRM_DEVICE HRM__CALL void hrm__efit_setup(hrm__ctx *c, const hrm_options *o)
{
    hrm_real y[HRM__EFIT_MAX];
    int j, n = 0;
    if (hrm__methods[o->method].driver == HRM__DRV_SIMPSON) {
        y[0] = -1;
        y[1] = 0;
        y[2] = 1;
        hrm__efit_init(&c->ef[0], y, 3);
    } else if (hrm__methods[o->method].driver == HRM__DRV_GK) {
        const hrm__gk_pair *R = o->gk_rule == HRM_GK_K7 ? &hrm__k7 : &hrm__k15;
        hrm__efit_init(&c->ef[0], R->x, R->n);
        for (j = 0; j < R->n; ++j)
            if (R->wg[j] != 0) y[n++] = R->x[j];
        hrm__efit_init(&c->ef[1], y, n);
    } else {
        hrm__nodes_info ni;
        hrm__nodes_init(hrm__methods[o->method].tb, &ni);
        for (j = 0; j < ni.m; ++j) y[j] = 2 * ni.c[j] - 1;
        hrm__efit_init(&c->ef[0], y, ni.m);
    }
}

/* The top term of the Newton interpolation series of the values d at the
   distinct nodes, integrated over a step of length h (d is overwritten
   with the divided differences). */
static HRM_DEVICE hrm_real hrm__newton_top(const hrm__nodes_info *ni, hrm_real *d, hrm_real h)
{
    int i, j;
    for (j = 1; j < ni->m; ++j)
        for (i = ni->m - 1; i >= j; --i) d[i] = (d[i] - d[i - 1]) / (ni->c[i] - ni->c[i - j]);
    return HRM_FABS(h * d[ni->m - 1]) * ni->W;
}

/* exp(-(tau - delta)) from a node's Tr = exp(-tau): delta, the layer's
   tau at the node less the homogeneous medium's line over the interval,
   is small once intervals resolve the medium; there a Taylor polynomial
   to delta^7 (its remainder below 1e-19 for |delta| <= 2^-6) spares the
   exponential the medium check paid at every node (a tenth of nested
   Simpson's instructions with sigma callbacks). */
static HRM_DEVICE hrm_real hrm__tr_near(hrm_real tr, hrm_real delta)
{
    hrm_real x = delta, p;
    if (!(HRM_FABS(x) <= HRM__R(0.015625))) return tr * HRM_EXP(x);
    /* Horner on 1/k!, k = 7 down to 0 */
    p = HRM__R(1.0) / 5040;
    p = p * x + HRM__R(1.0) / 720;
    p = p * x + HRM__R(1.0) / 120;
    p = p * x + HRM__R(1.0) / 24;
    p = p * x + HRM__R(1.0) / 6;
    p = p * x + HRM__R(0.5);
    p = p * x + 1;
    p = p * x + 1;
    return tr * p;
}

/* Emission, which no light's warp flattens: the rule applied to sigma_t
   Tr (dt/du in the weights) against its exact integral over [a, b], Tr(a)
   - Tr(b), times the largest emission per extinction sampled, into em
   where larger (hrm__medium_miss compares the rule with itself on the
   homogeneous medium instead, so that dt/du alone never refines a
   constant medium for the light's sake; Le between a light's foot and t1,
   where dt/du grew 6 000-fold within one interval, was missed whole:
   every adaptive method 8-9% off with HRM_OK at rtol 1e-2, on constants
   and sigma callbacks alike). sigma_t dt/du at the nodes: the layer's
   (the medium check) or the constant's; not with a fit (hrm__rk_exp_miss
   holds steps many optical depths thick). */
/* The emission's miss in channel i from the rule's h MT against A = Tr(a)
   - Tr(b) = tra (1 - e^-d), dd what rounding leaves of the comparison
   (hrm__medium_miss), into em where larger. */
static HRM_DEVICE void hrm__emission_part(const hrm__ctx *c, int i, hrm_real MT, hrm_real A, hrm_real tra,
                                          hrm_real dd, hrm_real em[HRM__CH])
{
    hrm_real me = HRM_FABS(MT - A) - tra * dd;
    me = me > 0 ? c->em_max[i] * me : 0;
    if (me > em[i]) em[i] = me;
}

/* The same, channel i, from the nodes. */
static HRM_DEVICE void hrm__emission_one(const hrm__ctx *c, int i, const hrm__pt *const *pt, const hrm_real *w,
                                         int n, hrm_real h, const hrm_real *tau_a, const hrm_real *tau_b,
                                         hrm_real em[HRM__CH])
{
    hrm_real d = tau_b[i] - tau_a[i], tra, MT = 0, Mabs = 0;
    int j;
    if (c->expo || !(c->em_max[i] > 0 && d > 0)) return;
    tra = pt[0]->tau[i] == tau_a[i] ? pt[0]->tr[i] : HRM_EXP(-tau_a[i]);
    for (j = 0; j < n; ++j) {
        hrm_real g = c->mcheck ? pt[j]->sg[i] : c->st[i] * pt[j]->J;
        MT += w[j] * g * pt[j]->tr[i];
        Mabs += HRM_FABS(w[j]) * g;
    }
    hrm__emission_part(c, i, h * MT, tra * -HRM_EXPM1(-d), tra, 32 * HRM__EPS * (tau_b[i] + 8 + Mabs * HRM_FABS(h)),
                       em);
}

static HRM_DEVICE HRM__CALL void hrm__emission_miss(const hrm__ctx *c, const hrm__pt *const *pt, const hrm_real *w,
                                                    int n, hrm_real h, const hrm_real *tau_a, const hrm_real *tau_b,
                                                    hrm_real em[HRM__CH])
{
    int i;
    for (i = 0; i < HRM__CH; ++i) hrm__emission_one(c, i, pt, w, n, h, tau_a, tau_b, em);
}

/* Whether a rule's nodes resolve the medium. The layer knows tau along
   the ray to tau_tol; the nodes know only their own samples, and a medium
   that varies between them (sigma = max(0, sin 3t) under two panels of
   nested Simpson: every node where sigma is 0, L 48% low with HRM_OK) is
   invisible to an estimate built from them alone. The same rule applied
   to sigma_t Tr, whose integral over the interval the layer gives exactly
   (A = Tr(a) - Tr(b), the light it absorbs), measures the miss: where the
   source per extinction S / sigma_t is R, the light the nodes miss is
   R |rule - A|. (With the host's Tr callback and sigma callbacks, A
   from its Tr and the rule on the nodes' own sigma_t: a gross miss
   only, see below; bench/sweep.c's media with the exact Tr: silent
   answers 82/87/55/23/23/18 of 4 000 -> 18/70/14/6/8/3 for nested
   Simpson, Gauss-Kronrod, Dormand-Prince, Cash-Karp, Verner, Bogacki-
   Shampine.) R is the largest S / sigma_t at the nodes (at least
   their rule of S Tr over that of sigma_t Tr): what the nodes miss of
   the medium lies somewhere in the interval, and where S / sigma_t
   varies over it (a light's peak) the miss counts at the largest
   (fBm smoke under a spot light, nested Simpson at rtol 1e-3: a pixel
   7 rtol off with HRM_OK where the ratio of the rules weighed it); where
   the rule missed half of A or more, the nodes' ratio is in doubt too
   and the largest S / sigma_t seen so far bounds it; none seen yet
   (every node where sigma is 0), the source is taken as 1 per unit
   extinction, so that the interval is refined until a node samples the
   medium. With an exponential fit (expo: intervals many
   optical depths thick, where a polynomial rule of Tr cannot be exact)
   the rule is applied to sigma_t alone against tau's increment, and its
   relative miss weighs A. The rule runs in the warp's variable, where
   dt/du (steep at a strong warp's ends) is no polynomial even for a
   constant medium: the rule is compared not with the layer's exact
   integral but with itself applied to the homogeneous medium of the
   same increment of tau over [a, b] (whose exact integral is the same),
   so that what dt/du alone costs the rule cancels and a constant medium
   is never refined for it (nested Simpson, a light 1e-3 from the ray:
   2.9 times the source evaluations of the closed form where the rule
   was compared with the exact integral). em
   receives the miss in L's units, per channel; w are the weights of the
   rule on [a, b] (length h in p), pt its nodes, tau_a and tau_b the
   layer's tau at the interval's ends, off_a and off_b their offsets. */
static HRM_DEVICE HRM__CALL void hrm__medium_miss(const hrm__ctx *c, const hrm__pt *const *pt, const hrm_real *w,
                             int n, hrm_real h, const hrm_real *tau_a, const hrm_real *tau_b,
                             hrm_real off_a, hrm_real off_b, hrm_real em[HRM__CH])
{
    int i, j;
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real d = tau_b[i] - tau_a[i], A, M = 0, MT = 0, Q = 0, Mabs = 0, M0 = 0, rel, R, dd, Rn = 0;
        hrm_real sbar = off_b > off_a ? d / (off_b - off_a) : 0, e0, tra;
        int dev = 0;
        em[i] = 0;
        if (!(d > 0)) continue;
        /* (a first node at the interval's start knows Tr there) */
        tra = pt[0]->tau[i] == tau_a[i] ? pt[0]->tr[i] : HRM_EXP(-tau_a[i]);
        A = tra * -HRM_EXPM1(-d);
        if (!(A > 64 * HRM__EPS)) { /* Tr is 0 there: no light to miss */
            if (!c->tau_from_tr) hrm__emission_one(c, i, pt, w, n, h, tau_a, tau_b, em);
            continue;
        }
        for (j = 0; j < n; ++j) {
            /* the homogeneous medium's sigma_t (Tr) ds/dp at the node */
            hrm_real f0 = sbar * pt[j]->J;
            hrm_real fj = c->expo ? pt[j]->sg[i] : pt[j]->sg[i] * pt[j]->tr[i];
            if (!c->expo) f0 *= hrm__tr_near(pt[j]->tr[i], pt[j]->tau[i] - tau_a[i] - sbar * (pt[j]->off - off_a));
            if (HRM_FABS(fj - f0) > HRM__SQRT_EPS * f0) dev = 1;
            M += w[j] * pt[j]->sg[i];
            MT += w[j] * pt[j]->sg[i] * pt[j]->tr[i];
            Q += w[j] * pt[j]->gq[i] * pt[j]->tr[i];
            Mabs += HRM_FABS(w[j]) * pt[j]->sg[i];
            M0 += w[j] * f0;
            if (pt[j]->sg[i] > 0 && HRM_FABS(pt[j]->gq[i]) > Rn * pt[j]->sg[i]) Rn = HRM_FABS(pt[j]->gq[i]) / pt[j]->sg[i];
        }
        M *= h;
        MT *= h;
        Q *= h;
        M0 *= h;
        Mabs *= HRM_FABS(h);
        /* What rounding leaves of the comparison, in units of tau: the
           layer's tau at a point is its panel's start plus a Chebyshev sum
           of the panel's increment (a first panel spans 8 mean free
           paths), each to a few epsilons, and the rule's own sum; only a
           miss beyond it counts (steps of 1e-14 missed by 1%). */
        dd = 32 * HRM__EPS * (tau_b[i] + 8 + Mabs);
        /* where the rule misses even the homogeneous medium's integral
           by half, it cannot tell a medium from it: unless the nodes saw
           that medium itself, the layer's exact integral is the measure */
        if (c->expo) {
            e0 = HRM_FABS(M0 - d);
            rel = (e0 < d / 2 || !dev ? HRM_FABS(M - M0) : HRM_FABS(M - d)) - dd;
            rel = rel > 0 ? rel / d : 0;
        } else {
            e0 = HRM_FABS(M0 - A);
            rel = (e0 < A / 2 || !dev ? HRM_FABS(MT - M0) : HRM_FABS(MT - A)) - tra * dd;
            rel = rel > 0 ? rel / A : 0;
        }
        /* against the host's Tr, a gross miss only, on an interval wider
           than the medium's feature (or 1/64 of the ray), and the
           emission's miss only with it: a callback off its sigma's
           integral is no feature (0.1% off in tau, nested Simpson,
           Gauss-Kronrod and Dormand-Prince spent their whole budget
           where every miss counted, the emission's too; 30% off costs
           nothing here) */
        if (c->tau_from_tr &&
            (rel < HRM__R(0.25) || !(off_b - off_a > (c->m->feature > 0 ? c->m->feature : c->off_end / 64))))
            rel = 0;
        R = MT > 0 ? HRM_FABS(Q) / MT : 0;
        if (Rn > R) R = Rn;
        if (rel >= HRM__R(0.5)) {
            if (c->src_max[i] > R) R = c->src_max[i];
            if (R == 0) R = 1;
        }
        em[i] = R * A * rel;
        /* the emission's miss from the same sums (hrm__emission_miss) */
        if (!c->expo && c->em_max[i] > 0 && (!c->tau_from_tr || rel > 0))
            hrm__emission_part(c, i, MT, A, tra, dd, em);
    }
}

/* A step many optical depths thick: Tr falls by exp(-d) over it, which
   no polynomial through the nodes follows, and the embedded estimate,
   the difference of two such rules, stops measuring either (Bogacki-
   Shampine, rtol 0.1, a step of d = 6.4 where Tr starts at 1: its value
   53% high, the estimate 27%, HRM_OK). The rule applied to the
   homogeneous medium of the same d (the medium check's yardstick, its
   exact integral 1 - exp(-d)) gives its relative miss of the exponential;
   times the step's value it is the step's miss where the source per
   extinction is flat (em, where larger). Only where d > 1 and ds/dp
   varies by less than 2 over the step: under a light's warp S ds/dp is
   flat where ds/dp is not, and the homogeneous medium's miss is no
   measure. */
static HRM_DEVICE HRM__CALL void hrm__rk_exp_miss(const hrm__nodes_info *ni, const hrm__pt *const *qs, int endj,
                                                  hrm_real h, const hrm_real (*f)[HRM__CH], hrm_real em[HRM__CH])
{
    int i, j;
    hrm_real jmin = qs[0]->J, jmax = qs[0]->J, doff = qs[endj]->off - qs[0]->off;
    for (j = 1; j < ni->m; ++j) {
        jmin = qs[j]->J < jmin ? qs[j]->J : jmin;
        jmax = qs[j]->J > jmax ? qs[j]->J : jmax;
    }
    if (!(jmin > 0 && jmax <= 2 * jmin && doff > 0)) return;
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real d = qs[endj]->tau[i] - qs[0]->tau[i], sbar = d / doff, M0 = 0, Q = 0, e;
        if (!(d > 1) || !HRM__FINITE(d)) continue;
        for (j = 0; j < ni->m; ++j) {
            M0 += ni->bw[j] * sbar * qs[j]->J * HRM_EXP(-sbar * (qs[j]->off - qs[0]->off));
            Q += ni->bw[j] * f[j][i];
        }
        M0 *= h;
        if (!(M0 > 0)) continue;
        e = HRM_FABS(M0 + HRM_EXPM1(-d)) / M0 * HRM_FABS(h * Q);
        if (e > em[i]) em[i] = e;
    }
}

/* Which ends of the step [p, p_end] are its piece's ends (bit 0 its
   start, bit 1 its end): a breakpoint, where the medium scan puts a
   medium's edge, or the ray's end. */
static HRM_DEVICE int hrm__step_edges(const hrm__ctx *c, hrm_real p, hrm_real p_end)
{
    return (p == c->pa || p == c->pb) | (p_end == c->pa || p_end == c->pb) << 1;
}

/* One channel's gap between two neighbouring nodes of a rule (x, ascending,
   in units of hl): where what the rule interpolates (r: L' itself, or with
   an exponential fit, which follows the decay of Tr, the fitted values,
   Tr's local exponential divided out) falls by more than factor times
   between them, the polynomial through the nodes follows the fall no
   better than a chord (65% over its integral at 20 times), and the
   estimate, another such rule leaning on the same nodes, does not measure
   it. Counted where both are above 0 and the smaller not at a piece's end
   (edges, hrm__step_edges: bit 0 x[0]'s end, bit 1 x[n - 1]'s; there is
   the medium's edge, located to a bracket of 1/64 of tau's tolerance,
   whose rise from 0 a polynomial follows: float's edge of a blob, 0.004
   against 0.85, sent the pairs' steps down to round-off), or, given tau
   at the nodes (NULL: not), where they are more than one optical depth
   apart. Half of what the gap can hold, its width times the larger of
   L' (f) at its ends over 2, is a miss (*m, where larger; never scaled,
   as the medium's): the interval is refined until such a gap holds no
   light that matters. The cases that set it:
   - the pairs (factor 20, tau given): an Li whose slope jumps, a host's
     shadow ray of a few fixed steps crossing a cloud's edge,
     Dormand-Prince 17-19 rtol off with HRM_OK at rtol 1e-2 in 161 of
     3000 such scenes, 39 with both above 0 counted; under the equiangular
     warp, thick fog past the light puts its whole decay
     e^-(sigma_t (t + r)) between a step's last two nodes (Verner: nodes
     at t 3.4 and 11.6, tau 8.6 apart, estimate 0.36 rtol, error 5.1 rtol,
     HRM_OK; 3 optical depths as the condition left a float ray 6.3 rtol
     off, its shadow ray doubling the decay). (Under the distance warp the
     integrand is flat in u however far apart in tau its nodes are.)
   - the fitted pairs (factor 8 on the fitted values): make render's
     cloud, fitted Dormand-Prince at rtol 1e-2, one step of 0.1 over the
     peak behind the cloud's edge, its fitted values 9 times apart between
     the nodes at 0.3 and 0.8 of it, 16 rtol off with HRM_OK; an Li whose
     slope jumps, 280 of 3000 such scenes silent at rtol 1e-2, 25 with
     this.
   - nested Simpson and Gauss-Kronrod (factor 8, edges 0): an Li with three
     slope jumps on one K15 interval, |K - G| 1.1e-6, K 5.4e-3 off, 85
     rtol with HRM_OK at rtol 1e-4. Nested Simpson's five samples, 1/16
     of its first panels apart, at factor 6: an Li falling 1172 times over
     one of them behind two slope jumps (samples 1.17, 0.63, 0.24, 0.035,
     0.001: the largest fall short of 8 inside the bulk of the light),
     S2 - S1 1.1e-3 of L, S2 1.03e-2 off, 3.9 rtol with HRM_OK at rtol
     2.6e-3 (bench/sweep.c's kinks: its one silent answer; with 6 none,
     fog and lights +1% and +0.4% evaluations, the bench's +0.02%). */
static HRM_DEVICE void hrm__gap_miss(const hrm_real *x, const hrm_real *r, const hrm_real *f, const hrm_real *tau,
                                     int n, hrm_real hl, hrm_real factor, int edges, hrm_real *m)
{
    int j;
    if (!tau) {
        /* no neighbours more than factor apart if no two values are (the
           common case, decided at once) */
        hrm_real mn = r[0], mx = r[0];
        for (j = 1; j < n; ++j) {
            mn = r[j] < mn ? r[j] : mn;
            mx = r[j] > mx ? r[j] : mx;
        }
        if (!(mx > 0) || (mn > 0 && factor * mn >= mx)) return;
    }
    for (j = 0; j + 1 < n; ++j) {
        hrm_real hi = r[j] > r[j + 1] ? r[j] : r[j + 1], lo = r[j] > r[j + 1] ? r[j + 1] : r[j], gap;
        int at_edge = r[j] < r[j + 1] ? j == 0 && (edges & 1) : j + 2 == n && (edges & 2);
        if (!(hi > 0 && factor * lo < hi && ((lo > 0 && !at_edge) || (tau && tau[j + 1] - tau[j] > 1)))) continue;
        gap = (x[j + 1] - x[j]) * HRM_FABS(hl) * (f[j] > f[j + 1] ? f[j] : f[j + 1]) / 2;
        if (gap > *m) *m = gap;
    }
}

/* The kink test of Gauss-Kronrod (hrm__gk_tail) and the pairs
   (hrm__pair_tail): four rows of Legendre coefficients of the polynomial
   through the n values f (rows[r * n + j]: the top two, then the two the
   test holds them against); the larger of the top two where it keeps
   more than 1 / ratio of the larger of the other two and stands above
   round-off (a few ulps of the values need not fall: an exponential
   fitted exactly), else 0. */
static HRM_DEVICE hrm_real hrm__leg_tail(const hrm_real *rows, int n, const hrm_real *f, hrm_real ratio)
{
    hrm_real co[4], big = 0;
    int r, j;
    for (r = 0; r < 4; ++r) {
        co[r] = 0;
        for (j = 0; j < n; ++j) co[r] += rows[r * n + j] * f[j];
        co[r] = HRM_FABS(co[r]);
    }
    for (j = 0; j < n; ++j) big = HRM_FABS(f[j]) > big ? HRM_FABS(f[j]) : big;
    co[0] = co[0] > co[1] ? co[0] : co[1];
    co[2] = co[2] > co[3] ? co[2] : co[3];
    return co[0] > co[2] / ratio && co[0] > 64 * HRM__EPS * big ? co[0] : 0;
}

/* A pair's step over a kink (an Li whose slope jumps between its nodes): the
   embedded estimate, another rule through the same nodes, can agree by
   chance (Dormand-Prince's widest gap, 0.3 to 0.8 of the step: a knot at
   0.62 of it, estimate 0.63 rtol, error 22 rtol, HRM_OK). The polynomial
   through the nodes then stops converging: in Legendre's basis on the step,
   its top two coefficients keep more than 1/16 of the two below them, where
   a smooth integrand's fall by more (an exponential over a step of 1.5 decay
   lengths: 1/64; over that kink: 1/7). There a quarter of their size over
   the step, |h| max(|a_m-1|, |a_m-2|) / 4, is a miss (em, where larger;
   where the estimate already holds it, as on a steep smooth step, nothing
   changes), above 64 epsilons of the values. Pairs of 6 distinct nodes or
   more (not Bogacki-Shampine's 4); not on a step within twice h_min, which
   cannot shrink and is judged by the jump's share without it (a shadow's
   edge in float with one channel at rtol 3e-5: the pairs warned
   HRM_WARN_H_MIN there with it). Measured on bench/sweep.c: silent of 4000
   kinks rays Dormand-Prince 21 -> 0, Cash-Karp 4 -> 0, Verner 5 -> 0
   (lights: Dormand-Prince and Verner 1 -> 0), evaluations +5.6%, +4.0%,
   +1.1% (fog +4.7%, +3.9%, +0.2%; lights +4.0%, +1.2%, 0%); the bench's
   geometric mean +1.9% (Dormand-Prince), +1.6% (Cash-Karp), +1.4%
   (Fehlberg), -0.1% (Verner). Half their size as the miss cost
   Dormand-Prince +12% (fog) to +14% (kinks); with it, 1/8 as the threshold
   left Verner 1 silent. */
static HRM_DEVICE void hrm__pair_tail(const hrm__nodes_info *ni, const hrm_real *f, hrm_real h, hrm_real *em)
{
    hrm_real tail;
    if (ni->m < 6 || !ni->leg) return;
    tail = hrm__leg_tail(ni->leg, ni->m, f, 16) * HRM_FABS(h) / 4;
    if (tail > *em) *em = tail;
}

/* The quadrature form of a step (see hrm__nodes_info): the distinct nodes
   in ascending order, L' = Tr S at each, no stage sums. An adaptive step
   (err), or a fixed one with a fit; a fixed step without one takes
   hrm__rk_quad_fixed. */
static HRM_DEVICE HRM__CALL HRM__NOINLINE int hrm__rk_quad(hrm__ctx *c, const hrm__nodes_info *ni, const hrm__pt *start,
                        hrm__pt *end, hrm_real p, hrm_real p_end, const hrm_real *y,
                        hrm_real *ynew, hrm_real *err, hrm_real *both)
{
    hrm__pt pn[HRM__MAX_STAGES]; /* the nodes (with an exponential fit, the
                                    start's copy too: the fit's array) */
    const hrm__pt *qs[HRM__MAX_STAGES];
    hrm_real f[HRM__MAX_STAGES][HRM__CH], h = p_end - p, em[HRM__CH];
    int i, j, endj = -1, edges;
    if (c->expo) memset(pn, 0, sizeof pn);
    for (j = 0; j < ni->m; ++j) {
        const hrm__pt *q = start;
        hrm_real cj = ni->c[j];
        if (cj != 0) {
            hrm__eval(c, cj == 1 ? p_end : p + cj * h, &pn[j]);
            q = &pn[j];
            if (cj == 1) endj = j;
        } else if (c->expo) {
            pn[j] = *start;
        }
        for (i = 0; i < HRM__CH; ++i) f[j][i] = q->tr[i] * q->gq[i];
        qs[j] = q;
    }
    hrm__fill(em, HRM__CH, 0);
    HRM_ASSERT(!(err && c->mcheck) || endj >= 0); /* every pair has a node at c = 1 */
    if (err && c->mcheck && endj >= 0)
        hrm__medium_miss(c, qs, ni->bw, ni->m, h, start->tau, pn[endj].tau, start->off, pn[endj].off, em);
    else if (err && c->homog && endj >= 0) /* constants: their emission alone */
        hrm__emission_miss(c, qs, ni->bw, ni->m, h, start->tau, pn[endj].tau, em);
    if (err && !c->expo && endj >= 0 && ni->c[0] == 0) hrm__rk_exp_miss(ni, qs, endj, h, (const hrm_real(*)[HRM__CH])f, em);
    edges = hrm__step_edges(c, p, p_end);
    if (err && !c->expo)
        for (i = 0; i < HRM__CH; ++i) {
            hrm_real tc[HRM__MAX_STAGES] = {0}, fc[HRM__MAX_STAGES] = {0};
            for (j = 0; j < ni->m; ++j) {
                tc[j] = qs[j]->tau[i];
                fc[j] = f[j][i];
            }
            hrm__gap_miss(ni->c, fc, fc, tc, ni->m, h, 20, edges, &em[i]);
            if (HRM_FABS(h) > 2 * c->h_min) hrm__pair_tail(ni, fc, h, &em[i]);
        }
    if (c->expo) {
        /* the nodes' polynomial against the exact local exponential; the
           embedded estimates are those of the fitted values g (what is
           interpolated) times the exponential's mass over the step */
        hrm_real out[HRM__CH], mass[HRM__CH], g[HRM__EFIT_MAX][HRM__CH], un[HRM__CH];
        hrm__efit_panel(c, &c->ef[0], pn, h / 2, out, mass, g, un);
        for (i = 0; err && i < HRM__CH; ++i) {
            hrm_real gc[HRM__MAX_STAGES] = {0}, fc[HRM__MAX_STAGES] = {0};
            for (j = 0; j < ni->m; ++j) {
                gc[j] = g[j][i];
                fc[j] = f[j][i];
            }
            hrm__gap_miss(ni->c, gc, fc, NULL, ni->m, h, 8, edges, &em[i]);
        }
        for (i = 0; i < HRM__CH; ++i) {
            hrm_real eacc = 0, d[HRM__MAX_STAGES];
            for (j = 0; j < ni->m; ++j) {
                eacc += ni->ew[j] * g[j][i];
                d[j] = g[j][i];
            }
            ynew[i] = y[i];
            ynew[HRM__CH + i] = y[HRM__CH + i];
            if (err) ynew[HRM__CH + i] += out[i];
            else hrm__sum(&ynew[HRM__CH + i], &c->ksum[HRM__CH + i], out[i]); /* fixed steps */
            if (err) {
                err[i] = 0;
                hrm_real e = eacc * mass[i]; /* an unsure step adds its bound */
                e = e < 0 ? e - un[i] : e + un[i];
                err[HRM__CH + i] = HRM_FABS(e) >= em[i] ? e : e < 0 ? -em[i] : em[i];
            }
            if (err && both) {
                hrm_real top = hrm__newton_top(ni, d, h) * mass[i] / h;
                both[i] = 0;
                both[HRM__CH + i] = HRM_FABS(err[HRM__CH + i]) > top ? HRM_FABS(err[HRM__CH + i]) : top;
            }
        }
        if (endj >= 0) *end = pn[endj];
        return endj >= 0;
    }
    HRM_ASSERT(err);
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real acc = 0, eacc = 0;
        for (j = 0; j < ni->m; ++j) {
            acc += ni->bw[j] * f[j][i];
            eacc += ni->ew[j] * f[j][i];
        }
        hrm_real e = h * eacc;
        ynew[i] = y[i];
        ynew[HRM__CH + i] = y[HRM__CH + i] + h * acc;
        err[i] = 0;
        err[HRM__CH + i] = HRM_FABS(e) >= em[i] ? e : e < 0 ? -em[i] : em[i];
    }
    if (both) {
        memcpy(both, err, sizeof(hrm_real) * HRM__NY);
        for (i = 0; i < HRM__CH; ++i) {
            hrm_real d[HRM__MAX_STAGES], top;
            for (j = 0; j < ni->m; ++j) d[j] = f[j][i];
            top = hrm__newton_top(ni, d, h);
            if (top > HRM_FABS(both[HRM__CH + i])) both[HRM__CH + i] = top;
        }
    }
    if (endj >= 0) *end = pn[endj];
    return endj >= 0;
}

/* The stage form of a step: each stage's derivative from the stage sum
   of those before it. pts and k: a point and a derivative per stage
   (tb->s of each, in the caller's frame: hrm__rk_stages). */
static HRM_DEVICE HRM__CALL int hrm__rk_stages_in(hrm__ctx *c, const hrm__tableau *tb, const hrm__pt *start,
                        hrm__pt *end, hrm_real p, hrm_real p_end,
                        const hrm_real *y, hrm_real *ynew, hrm_real *err,
                        const hrm__nodes_info *ni, hrm_real *both, hrm__pt *pts, hrm_real (*k)[HRM__NY])
{
    const hrm__pt *sp[HRM__MAX_STAGES];
    hrm_real Y[HRM__NY], ts[HRM__MAX_STAGES][HRM__CH]; /* coupled tau at each stage */
    hrm_real h = p_end - p;
    int i, j, n, end_stage = -1;

    HRM_ASSERT(tb->s <= HRM__MAX_STAGES);
    hrm__fill(Y, HRM__NY, 0);
    for (i = 0; i < tb->s; ++i) {
        hrm_real ci = tb->c[i];
        sp[i] = 0;
        if (ci == 0) sp[i] = start;
        for (j = 0; j < i && !sp[i]; ++j)
            if (tb->c[j] == ci) sp[i] = sp[j];
        if (!sp[i]) {
            hrm__eval(c, ci == 1 ? p_end : p + ci * h, &pts[i]);
            sp[i] = &pts[i];
            if (ci == 1) end_stage = i;
        }
        /* Stage values: the RTE form reads all of them, the optical-depth
           form only tau, and only when tau is coupled (else Tr at the node
           is known). */
        for (n = 0; n < (c->rte ? HRM__NY : c->coupled ? HRM__CH : 0); ++n) {
            hrm_real acc = 0;
            for (j = 0; j < i; ++j) acc += tb->a[i * tb->s + j] * k[j][n];
            Y[n] = y[n] + h * acc;
            if (!c->rte) {
                /* sbar over the distance exactly; tau never decreases along
                   the march, whatever signs the tableau's a hold */
                Y[n] += c->sbar[n] * (sp[i]->off - start->off);
                if (Y[n] < y[n]) Y[n] = y[n];
                ts[i][n] = Y[n];
            }
        }
        hrm__deriv(c, sp[i], Y, k[i]);
    }
    for (n = 0; n < HRM__NY; ++n) {
        hrm_real acc = 0, eacc = 0;
        for (i = 0; i < tb->s; ++i) {
            acc += tb->b[i] * k[i][n];
            if (err) eacc += (tb->b[i] - tb->bh[i]) * k[i][n];
        }
        ynew[n] = y[n];
        if (err) ynew[n] += h * acc;
        else hrm__sum(&ynew[n], &c->ksum[n], h * acc); /* fixed steps */
        if (err) err[n] = h * eacc;
    }
    if (err && c->coupled && !c->rte) {
        /* coupled tau: its stage values at the nodes (hrm__gap_miss), and
           the kink test on L' there (hrm__pair_tail), as in the
           quadrature form */
        int edges = hrm__step_edges(c, p, p_end);
        for (n = 0; n < HRM__CH; ++n) {
            hrm_real tc[HRM__MAX_STAGES] = {0}, fc[HRM__MAX_STAGES] = {0}, em = 0;
            for (i = 0; i < ni->m; ++i) {
                tc[i] = ts[ni->stage[i]][n];
                fc[i] = k[ni->stage[i]][HRM__CH + n];
            }
            hrm__gap_miss(ni->c, fc, fc, tc, ni->m, h, 20, edges, &em);
            if (HRM_FABS(h) > 2 * c->h_min) hrm__pair_tail(ni, fc, h, &em);
            if (em > HRM_FABS(err[HRM__CH + n])) err[HRM__CH + n] = err[HRM__CH + n] < 0 ? -em : em;
        }
    }
    if (err && both) {
        /* A second opinion on the step, which an embedded pair cannot
           give where both of its solutions are wrong alike (a step over a
           light's peak): the stage values of L' at the distinct nodes have
           a Newton interpolation series whose top term, integrated over
           the step, must be small if the step resolves the integrand.
           both: the larger of it and the pair's estimate. (At a jump the
           series does not converge, but its top term falls like h, as the
           pair's estimate does: it judges rough steps too.) */
        memcpy(both, err, sizeof(hrm_real) * HRM__NY);
        for (n = HRM__CH; n < HRM__NY; ++n) {
            hrm_real d[HRM__MAX_STAGES], top;
            for (i = 0; i < ni->m; ++i) d[i] = k[ni->stage[i]][n];
            top = hrm__newton_top(ni, d, h);
            if (top > HRM_FABS(both[n])) both[n] = top;
        }
    }
    if (c->coupled) {
        hrm_real off_end, J;
        if (end_stage >= 0) off_end = pts[end_stage].off;
        else hrm__map(c, p_end, &off_end, &J);
        for (n = 0; n < HRM__CH; ++n) {
            if (err) ynew[n] += c->sbar[n] * (off_end - start->off);
            else hrm__sum(&ynew[n], &c->ksum[n], c->sbar[n] * (off_end - start->off));
            /* tau nondecreasing (a fixed step updates y in place: its
               caller keeps tau at the start and holds it there) */
            if (ynew[n] < y[n]) ynew[n] = y[n];
        }
    }
    if (end_stage >= 0) *end = pts[end_stage];
    return end_stage >= 0;
}

/* The stages' storage in a frame of its own, sized for the tableau: the
   largest's, or that of one of at most 4 stages (Euler, RK4 and so
   Adams-Bashforth's start, Bogacki-Shampine), half of it. */
#define HRM__FEW_STAGES 4
#define HRM__RK_STAGES_FRAME(name, n)                                                                       \
    static HRM_DEVICE HRM__NOINLINE int name(hrm__ctx *c, const hrm__tableau *tb, const hrm__pt *start,     \
                                             hrm__pt *end, hrm_real p, hrm_real p_end, const hrm_real *y,   \
                                             hrm_real *ynew, hrm_real *err, const hrm__nodes_info *ni,      \
                                             hrm_real *both)                                                \
    {                                                                                                       \
        hrm__pt pts[n];                                                                                     \
        hrm_real k[n][HRM__NY];                                                                             \
        HRM_ASSERT(tb->s <= n);                                                                             \
        return hrm__rk_stages_in(c, tb, start, end, p, p_end, y, ynew, err, ni, both, pts, k);              \
    }
HRM__RK_STAGES_FRAME(hrm__rk_stages, HRM__MAX_STAGES)
HRM__RK_STAGES_FRAME(hrm__rk_stages_few, HRM__FEW_STAGES)
#undef HRM__RK_STAGES_FRAME

/* hrm__rk_quad for a fixed step (no error estimate) without a fit: no
   node is read again but the step's end, so the nodes inside are
   evaluated in turn into one point and the end into *end (the same sums
   in the same order). */
static HRM_DEVICE HRM__CALL HRM__NOINLINE int hrm__rk_quad_fixed(hrm__ctx *c, const hrm__nodes_info *ni,
                                                                const hrm__pt *start, hrm__pt *end, hrm_real p,
                                                                hrm_real p_end, const hrm_real *y, hrm_real *ynew)
{
    hrm__pt pt;
    hrm_real f[HRM__MAX_STAGES][HRM__CH], h = p_end - p;
    int i, j, have_end = 0;
    for (j = 0; j < ni->m; ++j) {
        const hrm__pt *q = start;
        hrm_real cj = ni->c[j];
        if (cj != 0) {
            hrm__pt *at = cj == 1 ? end : &pt;
            hrm__eval(c, cj == 1 ? p_end : p + cj * h, at);
            q = at;
            if (cj == 1) have_end = 1;
        }
        for (i = 0; i < HRM__CH; ++i) f[j][i] = q->tr[i] * q->gq[i];
    }
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real acc = 0;
        for (j = 0; j < ni->m; ++j) acc += ni->bw[j] * f[j][i];
        ynew[i] = y[i];
        ynew[HRM__CH + i] = y[HRM__CH + i];
        hrm__sum(&ynew[HRM__CH + i], &c->ksum[HRM__CH + i], h * acc);
    }
    return have_end;
}

/* One step: its quadrature form where the step needs no stage sums (the
   optical-depth form, tau not coupled), else its stages; each in a frame
   of its own, so that the one not taken reserves no stack (a fixed step
   without a fit, the most common, holds one node instead of the largest
   tableau's). */
static HRM_DEVICE int hrm__rk_step(hrm__ctx *c, const hrm__tableau *tb, const hrm__pt *start, hrm__pt *end,
                                   hrm_real p, hrm_real p_end, const hrm_real *y, hrm_real *ynew, hrm_real *err,
                                   const hrm__nodes_info *ni, hrm_real *both)
{
    if (!c->rte && !c->coupled && !err && !c->expo)
        return hrm__rk_quad_fixed(c, ni, start, end, p, p_end, y, ynew);
    if (!c->rte && !c->coupled) return hrm__rk_quad(c, ni, start, end, p, p_end, y, ynew, err, both);
    if (tb->s <= HRM__FEW_STAGES) return hrm__rk_stages_few(c, tb, start, end, p, p_end, y, ynew, err, ni, both);
    return hrm__rk_stages(c, tb, start, end, p, p_end, y, ynew, err, ni, both);
}

/* Initial state: (tau, A) = 0 at t0, or (Tr, L) = (1, 0) at t1. */
static HRM_DEVICE void hrm__ivp_init(const hrm__ctx *c, hrm_real y[HRM__NY])
{
    hrm__fill(y, HRM__CH, c->rte ? 1 : 0);
    hrm__fill(y + HRM__CH, HRM__CH, 0);
}

/* Coupled tau held nondecreasing over a fixed step: below its value at
   the step's start (tau_p), it is that value, and the compensated sum's
   lost part goes with the clamped one. */
static HRM_DEVICE void hrm__tau_floor(hrm__ctx *c, hrm_real *y, const hrm_real tau_p[HRM__CH])
{
    int i;
    for (i = 0; i < HRM__CH; ++i)
        if (y[i] < tau_p[i]) {
            y[i] = tau_p[i];
            c->ksum[i] = 0;
        }
}

/* Fixed-step IVP driver: Euler, RK4 and Adams-Bashforth 4 (three RK4 steps
   to start, then one new evaluation per step). The optical-depth form
   marches from t0 to t1, the RTE form from t1 to t0. */
static HRM_DEVICE HRM__CALL void hrm__ivp_fixed(hrm__ctx *c, const hrm__tableau *tb, int ab4, int N,
                           hrm_real y[HRM__NY])
{
    hrm_real from = c->rte ? c->pb : c->pa, to = c->rte ? c->pa : c->pb;
    hrm_real f[4][HRM__NY]; /* Adams-Bashforth history, f[n % 4] = f_n */
    hrm_real tau_p[HRM__CH]; /* tau at the step's start */
    hrm__nodes_info ni;
    hrm__pt start, end;
    int have = 0, n, i;

    hrm__nodes_init(tb, &ni);
    hrm__ivp_init(c, y);
    hrm__fill(c->ksum, HRM__NY, 0);
    for (n = 0; n < N; ++n) {
        hrm_real p = from + (to - from) * ((hrm_real)n / (hrm_real)N);
        hrm_real q = n + 1 == N ? to : from + (to - from) * ((hrm_real)(n + 1) / (hrm_real)N);
        hrm_real h = q - p;
        if (!ab4 || n < 3) {
            if (ab4) {
                if (!have) hrm__eval(c, p, &start);
                have = 1;
                hrm__deriv(c, &start, y, f[n % 4]);
            }
            if (!have) hrm__eval(c, p, &start);
            memcpy(tau_p, y, sizeof tau_p);
            have = hrm__rk_step(c, tb, &start, &end, p, q, y, y, 0, &ni, 0);
            if (c->coupled) hrm__tau_floor(c, y, tau_p);
            if (have) start = end;
        } else {
            if (!have) hrm__eval(c, p, &start);
            have = 0;
            hrm__deriv(c, &start, y, f[n % 4]);
            memcpy(tau_p, y, sizeof tau_p);
            for (i = 0; i < HRM__NY; ++i) {
                /* f_n, f_(n-1), f_(n-2), f_(n-3): the history's slots */
                hrm_real h0 = h * f[n % 4][i], h1 = h * f[(n + 3) % 4][i];
                hrm_real h2 = h * f[(n + 2) % 4][i], h3 = h * f[(n + 1) % 4][i], inc = 0;
                int pos = h0 >= 0 && h1 >= 0 && h2 >= 0 && h3 >= 0;
                int neg = h0 <= 0 && h1 <= 0 && h2 <= 0 && h3 <= 0;
                inc += hrm__ab4_beta[0] * h0;
                inc += hrm__ab4_beta[1] * h1;
                inc += hrm__ab4_beta[2] * h2;
                inc += hrm__ab4_beta[3] * h3;
                /* Positivity limiter (optical-depth form): when every history
                   value agrees on the increment's sign, so does the
                   increment. Extrapolating a sharply decaying exp(-tau) S
                   can otherwise go negative in thick media. (tau's history
                   holds sigma_t - sbar, whose sign means nothing: tau is
                   kept nondecreasing below instead.) */
                if (!c->rte && i >= HRM__CH && ((pos && inc < 0) || (neg && inc > 0))) inc = 0;
                hrm__sum(&y[i], &c->ksum[i], inc);
            }
            if (c->coupled) {
                hrm_real off_q, J;
                hrm__map(c, q, &off_q, &J);
                for (i = 0; i < HRM__CH; ++i) hrm__sum(&y[i], &c->ksum[i], c->sbar[i] * (off_q - start.off));
                hrm__tau_floor(c, y, tau_p);
            }
        }
        c->stats.steps++;
        hrm__state_check(c, y, HRM__NY);
        if (c->status != HRM_OK) return;
    }
    for (i = 0; i < HRM__NY; ++i) y[i] += c->ksum[i];
}

/* New evaluations of one step: the distinct nonzero nodes. */
static HRM_DEVICE int hrm__stage_cost(const hrm__tableau *tb)
{
    int i, j, n = 0;
    for (i = 0; i < tb->s; ++i) {
        int dup = tb->c[i] == 0;
        for (j = 0; j < i && !dup; ++j) dup = tb->c[j] == tb->c[i];
        n += !dup;
    }
    return n;
}

/* ---------------------------------------------------------------------- */
/* Error control shared by every adaptive method                           */
/* ---------------------------------------------------------------------- */

/* The tolerance of one step or interval, per component of y = (tau, L):
   atol * frac + rtol * max(|y1 - y0|, frac * |y1|), frac being the step's
   share of the parameter range (p0 to p1). Summed over the steps this is at most
   atol + rtol * (|L| + sum of |increments|) = atol + 2 rtol |L| for a
   nonnegative source, which is what makes rtol a bound on the global error
   (the optical-depth form adds local errors without amplifying them). The
   result is the largest error / tolerance: <= 1 accepts. Muñoz's and
   Gonterman's rules measure the error their own way (Munoz 2014 eq. 11-12:
   relative to |y1|; Gonterman 2010 eq. 3.4: per unit step). */
#define HRM__JUMP 16 /* a step with an O(h) error may take rtol/16 of the
                        scale, and at most 16 such steps per solve */

static HRM_DEVICE HRM__CALL hrm_real hrm__ratio(hrm__ctx *c, int control, hrm_real p0, hrm_real p1,
                           const hrm_real *y0, const hrm_real *y1, const hrm_real *err)
{
    hrm_real worst = 0, frac = HRM_FABS((p1 - p0) / (c->pb - c->pa));
    /* Nodes are placed to within an ulp of p: no estimate resolves the
       relative error |p| eps / h this misplacement causes (it bites when a
       warp packs a boundary layer against an end far from p = 0). Without
       a warp the callbacks see t0 + p, placed to within an ulp of t0. */
    hrm_real pos = HRM_FABS(p0) > HRM_FABS(p1) ? HRM_FABS(p0) : HRM_FABS(p1);
    hrm_real noise, noise_p = 8 * HRM__EPS * (pos / HRM_FABS(p1 - p0) + 1);
    int n;
    /* (a ray farther from the origin than it is long: there t's own
       resolution limits what any step can achieve) */
    if (c->warp == HRM_WARP_NONE && HRM_FABS(c->t0) > pos && HRM_FABS(c->t0) > c->pb - c->pa)
        pos = HRM_FABS(c->t0);
    noise = 8 * HRM__EPS * (pos / HRM_FABS(p1 - p0) + 1);
    /* Near a light t places the nodes, and so samples its profile, to
       w_res of its distance; a pair's kink test, a high difference of its
       stages, carries that rounding several times over: below 4 w_res no
       estimate tells the rule's error from it. Where w_res passes 2 rtol
       (hrm__finish warns HRM_WARN_ROUNDOFF), steps within it are taken,
       not refined (double, t0 = 2, a light 1e-11 before it, D 1e-13, rtol
       1e-5: Dormand-Prince 63 271 evaluations chasing it, Verner 17 425;
       below 2 rtol the floor warned on answers within rtol, float) */
    if (c->w_res > 2 * c->rtol && 4 * c->w_res > noise) noise = 4 * c->w_res;
    if (control != HRM__JUMP) c->noise_only = 0;
    for (n = 0; n < HRM__NY; ++n) {
        hrm_real atol = n >= HRM__CH ? c->atol : 0, tol, e = HRM_FABS(err[n]);
        hrm_real inc = HRM_FABS(y1[n] - y0[n]), Y = HRM_FABS(y1[n]);
        /* An error in tau matters through exp(-tau) only: weigh it by the
           transmittance at the step's start (no effort where Tr is 0). */
        if (n < HRM__CH && !c->rte && e > 0) e *= HRM_EXP(-y0[n]);
        if (control == HRM_CONTROL_MUNOZ) {
            tol = atol + c->rtol * Y;
        } else if (control == HRM_CONTROL_GONTERMAN) {
            tol = frac * (atol + c->rtol * Y);
        } else {
            Y = Y > c->scale[n] ? Y : c->scale[n];
            if (control == HRM__JUMP)
                tol = atol + c->rtol * Y / HRM__JUMP;
            else
                tol = atol * frac + c->rtol * (inc > frac * Y ? inc : frac * Y);
        }
        if (tol < noise * inc) {
            /* only the resolution of t far from the origin lets this step
               through: say so if it is taken */
            if (control != HRM__JUMP && e > tol && e > noise_p * inc && e <= noise * inc)
                c->noise_only = 1;
            tol = noise * inc;
        }
        if (e > 0) {
            hrm_real r = tol > 0 ? e / tol : HRM__R(1e30);
            if (r > worst) worst = r;
        }
    }
    return worst;
}

/* A refinement that did not at least halve the error ratio while the step
   at least halved: the error is O(h) (a jump, such as a shadow edge) or
   noise, which no per-unit-step share can accept. Such a step is judged
   against a fixed share of the scale instead, so a jump costs a few
   refinements, not a descent to h_min. */
static HRM_DEVICE int hrm__rough(hrm_real ratio, hrm_real parent_ratio)
{
    return parent_ratio > 1 && ratio > parent_ratio / 2;
}

/* A rough interval within its fixed share, while the solve has shares left:
   at most HRM__JUMP of them, so that together they stay within rtol. */
static HRM_DEVICE int hrm__rough_ok(hrm__ctx *c, hrm_real ratio, hrm_real parent, hrm_real p0,
                         hrm_real p1, const hrm_real *y0, const hrm_real *y1, const hrm_real *err)
{
    if (c->rough_left <= 0 || !hrm__rough(ratio, parent) ||
        hrm__ratio(c, HRM__JUMP, p0, p1, y0, y1, err) > 1)
        return 0;
    c->rough_left--;
    return 1;
}

/* The scale of the solution from a coarse estimate of the whole integral
   (a pilot that costs no extra evaluation): relative tolerances then
   mean a share of the total even where the integral starts at zero. */
static HRM_DEVICE void hrm__set_scale(hrm__ctx *c, const hrm_real *total)
{
    int n;
    if (c->scale_fixed) return; /* solving again at the scale found */
    for (n = 0; n < HRM__NY; ++n) c->scale[n] = HRM_FABS(total[n]) / 2;
}

static HRM_DEVICE hrm_real hrm__clamp(hrm_real x, hrm_real lo, hrm_real hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

/* An accepted step or interval adds its estimate of L's error. */
static HRM_DEVICE void hrm__warn(hrm__ctx *c, hrm_status w);

static HRM_DEVICE void hrm__accepted(hrm__ctx *c, const hrm_real *err)
{
    int i;
    if (c->noise_only) hrm__warn(c, HRM_WARN_ROUNDOFF);
    for (i = 0; i < HRM__CH; ++i) c->err_acc[i] += HRM_FABS(err[HRM__CH + i]);
}

static HRM_DEVICE void hrm__warn(hrm__ctx *c, hrm_status w)
{
    if (c->warning == HRM_OK || c->warning == HRM_WARN_RTOL_CLIPPED) c->warning = w;
}

/* What a refusal at h_min means: the floor the caller or the range set
   (HRM_WARN_H_MIN), or t's own resolution far from the origin
   (HRM_WARN_ROUNDOFF). */
static HRM_DEVICE hrm_status hrm__h_min_status(const hrm__ctx *c)
{
    return c->h_min <= c->h_res ? HRM_WARN_ROUNDOFF : HRM_WARN_H_MIN;
}

/* The pair's estimate is of its lower-order solution, O(h^(k+1)) per
   step, but the higher-order one is returned, O(h^(k+2)): their ratio is
   about h / l, l the length over which the integrand changes, and
   (e / M)^(1 / (k + 1)) measures h / l, M the step's own size (its
   increment, or its share of the scale). So the error of what is returned
   is about e (e / M)^(1 / (k + 1)); 4 times that is kept, never more than
   e (a step that does not resolve the integrand, e ~ M, keeps the whole
   estimate). Without it the tolerance bounds the lower order's error and
   the returned error falls faster than rtol (Bogacki-Shampine: 2e-5 rtol
   at rtol 1e-9, 0.03 at 1e-2). Measured on the bench's smooth scenes,
   rtol 1e-2..1e-10, both warps: median achieved/rtol 0.014-0.031, worst
   HRM_OK run 2.3 (with 2 instead of 4: 3.9). Bogacki-Shampine keeps 16
   times it: its e (e / M)^(1/3) is the furthest from e, and behind a
   dense front under a light's warp (a random search of 3 000 such rays,
   rtol 1e-2..1e-4) its steps about the light's foot and the ray's end
   missed 2-9 times what 4 kept, 18 answers 3.0-5.7 rtol off with HRM_OK
   (none with 16; 8 left 3). Fehlberg and Cash-Karp return the order
   their estimate is of: unchanged. */
static HRM_DEVICE void hrm__pair_calibrate(const hrm__ctx *c, const hrm__tableau *tb, hrm_real hs,
                                const hrm_real *y0, const hrm_real *y1, hrm_real *e)
{
    hrm_real frac = HRM_FABS(hs / (c->pb - c->pa));
    int n;
    if (tb->order <= tb->k) return; /* the estimate is of what is returned */
    for (n = 0; n < HRM__NY; ++n) {
        hrm_real inc = HRM_FABS(y1[n] - y0[n]), M = frac * c->scale[n], E = HRM_FABS(e[n]), r;
        M = inc > M ? inc : M;
        if (!(E > 0) || !(M > 0) || E >= M) continue;
        r = (tb->k == 2 ? 16 : 4) * HRM_POW(E / M, 1 / (hrm_real)(tb->k + 1));
        if (r < 1) e[n] *= r;
    }
}

/* Adaptive Runge-Kutta driver. The last step lands exactly on the end; a
   budget about to run out finishes the ray in even unchecked steps
   (HRM_WARN_MAX_EVALS); a step refused at h_min is taken anyway
   (HRM_WARN_H_MIN). */
static HRM_DEVICE HRM__CALL void hrm__ivp_adaptive(hrm__ctx *c, const hrm__tableau *tb, hrm_control control,
                              hrm_real h0, hrm_real y[HRM__NY])
{
    hrm_real from = c->rte ? c->pb : c->pa, to = c->rte ? c->pa : c->pb;
    hrm_real P = HRM_FABS(to - from), dir = to > from ? 1 : -1, p = from;
    hrm_real ynew[HRM__NY], err[HRM__NY], both[HRM__NY], r_prev = 1, r_parent = 0, h;
    hrm_real kk = (hrm_real)tb->k;
    hrm__pt start, end;
    int cost = hrm__stage_cost(tb), have = 0, after_reject = 0, first = 1, n;
    hrm__nodes_info ni;
    hrm_real leg[4 * HRM__MAX_STAGES]; /* ni.leg */
    /* the RTE form: h sigma_t at most the tableau's zmax */
    hrm_real zmax = c->rte ? tb->zmax : 0, hz = HRM__R(HUGE_VAL);

    hrm__nodes_init(tb, &ni);
    hrm__nodes_legendre(&ni, leg);
    hrm__ivp_init(c, y);
    /* The first attempt is the pilot that sets the scale. */
    h = h0 > 0 ? h0 : P * HRM__R(0.5) * HRM_POW(c->rtol, 1 / (kk + 1));
    h = hrm__clamp(h, c->h_min, c->h_max);
    while (p != to) {
        hrm_real rem = HRM_FABS(to - p), hs, q, ratio, fac;
        /* Steps the budget still pays for (counting a fresh start sample):
           when the last 64 of them cannot cover the rest at the current
           size, the rest is spread evenly over them, unchecked. */
        long left = (c->max_evals - hrm__spent(c)) / (cost + 1);
        int forced = left <= 1 || (left <= 64 && rem > h * (hrm_real)left), accept;
        if (forced) hrm__warn(c, HRM_WARN_MAX_EVALS);
        hs = forced ? (left > 1 ? rem / (hrm_real)left : rem)
                    : h * HRM__R(1.1) >= rem ? rem : h; /* no sliver at the end */
        if (hs * HRM__R(1.1) >= rem) hs = rem;
        q = hs == rem ? to : p + dir * hs;
        if (!have) hrm__eval(c, p, &start);
        have = 1;
        if (hrm__rk_step(c, tb, &start, &end, p, q, y, ynew, err, &ni,
                         control == HRM_CONTROL_PI ? both : 0) == 0)
            have = 0;
        hrm__state_check(c, ynew, HRM__NY);
        if (c->status != HRM_OK) return;
        if (first) {
            /* The first attempt's increment: a part of the total, not
               extrapolated (a thin layer near t0 holds all of a thick
               medium's light, and extrapolation would overstate it). */
            hrm_real part[HRM__NY];
            for (n = 0; n < HRM__NY; ++n) part[n] = ynew[n] - y[n];
            if (control != HRM_CONTROL_MUNOZ && control != HRM_CONTROL_GONTERMAN)
                hrm__set_scale(c, part);
            first = 0;
        } else if (control == HRM_CONTROL_PI && !c->scale_fixed) {
            /* A pilot that saw nothing (the source 0 over the first
               attempt: a cloud's blob further on) left no scale, and a
               step at the edge of what follows, where the source rises
               from 0 (a kink of sigma), misses by a fixed fraction of its
               own increment however small it is: it would descend to
               h_min (Dormand-Prince: 236 evaluations and
               HRM_WARN_ROUNDOFF on a blob 0.09 wide). The first attempt
               that sees something sets the scale instead, its increment
               extrapolated over the ray (too large a scale is caught by
               the verification: VERIFIED). */
            for (n = 0; n < HRM__NY; ++n)
                if (c->scale[n] == 0 && ynew[n] != y[n])
                    c->scale[n] = HRM_FABS(ynew[n] - y[n]) * (P / hs) / 2;
        }
        if (control == HRM_CONTROL_PI) hrm__pair_calibrate(c, tb, hs, y, ynew, both);
        ratio = hrm__ratio(c, (int)control, p, q, y, ynew, control == HRM_CONTROL_PI ? both : err);
        if (c->rte) {
            /* a step past the stability limit (h sigma_t, in p, beyond
               zmax at its ends) is refused whatever its estimate says
               (Fehlberg at sigma_t 1e11: L = -584, Tr = 974 from steps
               that passed), and none is tried past it; at h_min, or
               forced, hrm__finish judges the result */
            hrm_real g = 0;
            for (n = 0; n < HRM__CH; ++n) {
                if (start.gs[n] > g) g = start.gs[n];
                if (have && end.gs[n] > g) g = end.gs[n];
            }
            hz = g > 0 ? zmax / g : HRM__R(HUGE_VAL);
            if (hs > hz && hs > c->h_min && ratio <= 2) ratio = 2;
        }
        accept = ratio <= 1 || forced;
        if (!accept && control == HRM_CONTROL_PI && c->rough_left > 0 &&
            hrm__rough(ratio, r_parent) && hrm__ratio(c, HRM__JUMP, p, q, y, ynew, both) <= 1) {
            accept = 2;
            c->rough_left--;
        }
        /* (h_min's step stretched to the rest of the ray by the sliver
           rule above, up to 1.1 h_min, counts as h_min: refused, it was
           tried again the same until the budget ran out - float, the
           distance warp's end, 99 962 rejections) */
        if (!accept && hs <= c->h_min * HRM__R(1.1)) {
            /* within the share of a rough step, h_min is no failure */
            accept = 1;
            if (hrm__ratio(c, HRM__JUMP, p, q, y, ynew, err) > 1) hrm__warn(c, hrm__h_min_status(c));
        }
        if (control == HRM_CONTROL_MUNOZ) {
            /* Munoz 2014 eq. 12 with e_i the relative error. */
            fac = HRM__R(0.99) * c->rtol / (ratio * c->rtol + HRM__R(0.01));
        } else if (control == HRM_CONTROL_GONTERMAN) {
            fac = ratio > 0 ? HRM__R(0.9) * HRM_POW(ratio, -1 / kk) : HRM__R(1e30);
        } else if (accept == 2) {
            fac = 1; /* past the jump: let the next step find its size */
        } else if (accept) {
            /* PI control (Gustafsson 1991), exponents 0.7/k and 0.4/k. */
            hrm_real r = ratio > HRM__R(1e-10) ? ratio : HRM__R(1e-10);
            fac = HRM__R(0.9) * HRM_POW(r, -HRM__R(0.7) / kk) * HRM_POW(r_prev, HRM__R(0.4) / kk);
            fac = hrm__clamp(fac, HRM__R(0.2), after_reject ? 1 : 5);
            r_prev = r > HRM__R(1e-4) ? r : HRM__R(1e-4);
        } else {
            fac = hrm__clamp(HRM__R(0.9) * HRM_POW(ratio, -1 / kk), HRM__R(0.2), HRM__R(0.5));
        }
        if (accept) {
            memcpy(y, ynew, sizeof ynew);
            /* the larger estimate counts for a rough step too: at a
               spike on a node both embedded solutions are wrong alike
               (a light's peak at the ray's start: Dormand-Prince 71%
               too high with HRM_OK when the pair alone judged it) */
            hrm__accepted(c, control == HRM_CONTROL_PI && hs > c->h_min ? both : err);
            p = q;
            if (have) start = end;
            c->stats.steps++;
            after_reject = 0;
            r_parent = accept == 2 ? ratio : 0; /* noise persists; a jump does not */
        } else {
            have = 1; /* the start sample stands */
            c->stats.rejected++;
            after_reject = 1;
            r_parent = ratio;
        }
        /* an estimate that is not finite (stiff stages in float) gives no
           size: shrink as on a rejection (a NaN size called the warp at
           NaN) */
        if (!(fac >= 0)) fac = HRM__R(0.2);
        h = hrm__clamp(hs * fac, c->h_min, c->h_max);
        if (h > hz) h = hz > c->h_min ? hz : c->h_min;
    }
}

/* ---------------------------------------------------------------------- */
/* Adaptive quadrature                                                     */
/* ---------------------------------------------------------------------- */


/* Nested Simpson: each interval's three samples and its two quarter
   points give Simpson on the whole (S1) and on the halves (S2), whose
   difference estimates the halves' error (Lyness 1969); the Richardson-
   corrected halves S2 + (S2 - S1) / 15 are returned. A refined interval
   is split into its halves, which keep all five samples: every interval
   costs its two quarter points. (Munoz 2014 eq. 7 compares Simpson with
   the trapezoid rule, two orders too pessimistic.) Refinement is worst
   first (hrm__worst_first) while the intervals fit in HRM_NS_INTERVALS;
   the rest is finished left to right (hrm__ns_local). */
typedef struct hrm__ns_iv {
    hrm__pt a, m, b;
    hrm_real parent; /* the error ratio of the interval it was split from */
    int depth;
} hrm__ns_iv;

/* A right half waiting on the finish's stack: its start is the end of
   the last interval accepted before it (the left half's), so only its
   centre and end are kept. */
typedef struct hrm__ns_half {
    hrm__pt m, b;
    hrm_real parent;
    int depth;
} hrm__ns_half;

/* Simpson and trapezoid on one interval given tau at its left end:
   val = the increments of (tau, L), err = Simpson - trapezoid; f (NULL:
   not wanted) the L integrand at a, m, b. */
static HRM_DEVICE HRM__CALL void hrm__ns_rule(const hrm__ctx *c, const hrm__pt *a, const hrm__pt *m,
                         const hrm__pt *b, const hrm_real *tau_a,
                         hrm_real *val, hrm_real *err, hrm_real (*f)[HRM__CH])
{
    hrm_real H = b->p - a->p;
    int i;
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real ta = tau_a[i], tm = ta, tb = ta, fa, fm, fb;
        if (c->coupled) {
            tb = ta + c->sbar[i] * (b->off - a->off) + H / 6 * (a->gs[i] + 4 * m->gs[i] + b->gs[i]);
            tm = ta + c->sbar[i] * (m->off - a->off) + H / 24 * (5 * a->gs[i] + 8 * m->gs[i] - b->gs[i]);
            tb = tb < ta ? ta : tb;
            tm = hrm__clamp(tm, ta, tb);
        }
        fa = hrm__att(c, a, i, ta) * a->gq[i];
        fm = hrm__att(c, m, i, tm) * m->gq[i];
        fb = hrm__att(c, b, i, tb) * b->gq[i];
        val[i] = c->closed ? 0 : tb - ta;
        /* sbar's part is exact in both rules: compare the rest */
        err[i] = c->closed ? 0 : val[i] - c->sbar[i] * (b->off - a->off) -
                                     H / 4 * (a->gs[i] + 2 * m->gs[i] + b->gs[i]);
        val[HRM__CH + i] = H / 6 * (fa + 4 * fm + fb);
        err[HRM__CH + i] = val[HRM__CH + i] - H / 4 * (fa + 2 * fm + fb);
        if (f) {
            f[0][i] = fa;
            f[1][i] = fm;
            f[2][i] = fb;
        }
    }
}

/* Five equally spaced samples f[0..4][ch]: their largest second
   difference (returned) and their two third differences. */
static HRM_DEVICE hrm_real hrm__diffs5(const hrm_real (*f)[HRM__CH], int ch, hrm_real *t0, hrm_real *t1)
{
    hrm_real d[5], d2 = 0;
    int k;
    for (k = 0; k < 5; ++k) d[k] = f[k][ch];
    for (k = 0; k < 4; ++k) d[k] = d[k + 1] - d[k];
    for (k = 0; k < 3; ++k) {
        d[k] = d[k + 1] - d[k];
        d2 = HRM_FABS(d[k]) > d2 ? HRM_FABS(d[k]) : d2;
    }
    *t0 = d[1] - d[0];
    *t1 = d[2] - d[1];
    return d2;
}

/* Two third differences that agree in sign and to within a factor 5/3:
   a smooth trend the samples see whole (noise's are unrelated). */
static HRM_DEVICE int hrm__coherent(hrm_real t0, hrm_real t1)
{
    return t0 * t1 > 0 && HRM_FABS(t0 - t1) <= HRM__R(0.25) * HRM_FABS(t0 + t1);
}

/* hrm__fourth_pred from the samples' differences (hrm__diffs5), without
   the coherence test. */
static HRM_DEVICE hrm_real hrm__fourth_from(hrm_real d2, hrm_real t0, hrm_real t1, hrm_real w)
{
    hrm_real d3 = HRM_FABS(t0) > HRM_FABS(t1) ? HRM_FABS(t0) : HRM_FABS(t1);
    return d2 > 0 ? HRM_FABS(w) / 12 * (d3 / d2) * d3 : 0;
}

/* The fourth difference that five equally spaced samples f[0..4][ch]
   over a width w predict, as an error of Simpson's rule: S2 - S1 (on the
   halves, on the whole) is w / 12 times their fourth difference. Where
   the function is resolved the differences fall geometrically, the
   fourth about the third's square over the second; far below that S1 and
   S2 agreed by chance, and w / 12 times that prediction is their error's
   size instead. coherent: only where the third differences are coherent
   (hrm__coherent; noise is left to its own estimate). 0: no prediction. */
static HRM_DEVICE hrm_real hrm__fourth_pred(const hrm_real (*f)[HRM__CH], int ch, hrm_real w, int coherent)
{
    hrm_real t0, t1, d2 = hrm__diffs5(f, ch, &t0, &t1);
    if (coherent && !hrm__coherent(t0, t1)) return 0;
    return hrm__fourth_from(d2, t0, t1, w);
}

/* Whether five equally spaced samples f[0..4][ch] look resolved, so that
   their S2 - S1 may be trusted to fall as a smooth function's
   (hrm__wf_trust): of one sign within a factor 8 (no decay of more than
   two e-folds across them), and third differences coherent or below an
   eighth of the largest second difference. An Li whose slope jumps
   between them fails (a host's shadow ray of a few fixed steps, its
   nodes crossing a cloud's edge one by one: Li's slope 5 times steeper
   twice in 0.01), and so does a decay they do not resolve: a kink 0.003
   past a sample, the four after it on an exponential they cannot tell
   from a smooth one. d2, t0, t1: their differences (hrm__diffs5). */
static HRM_DEVICE int hrm__resolved5(const hrm_real (*f)[HRM__CH], int ch, hrm_real d2, hrm_real t0, hrm_real t1)
{
    hrm_real lo = f[0][ch], hi = f[0][ch];
    int k;
    for (k = 1; k < 5; ++k) {
        lo = f[k][ch] < lo ? f[k][ch] : lo;
        hi = f[k][ch] > hi ? f[k][ch] : hi;
    }
    if (!(lo > 0 ? hi <= 8 * lo : hi < 0 && lo >= 8 * hi)) return 0;
    return hrm__coherent(t0, t1) || (HRM_FABS(t0) <= d2 / 8 && HRM_FABS(t1) <= d2 / 8);
}

/* The interval [a, b] from its samples at a, a + h/4, a + h/2, a + 3h/4, b
   given tau at a: V the returned increments of (tau, L), E = S2 - S1 (the
   callers divide it: hrm__wf_split, hrm__ns_local). (S2 - S1) / 15 is
   S2's error once the halves are in the asymptotic regime; an oscillation
   that a few samples alias can make S1 and S2 agree before it. A divisor
   of 5 keeps a factor 3 of margin: on the bench's smooth scenes (rtol
   1e-2..1e-10) the worst HRM_OK run was at 1.0 rtol, 11 with 15. M: the
   medium check's miss, and where two neighbouring samples differ by more
   than 6 times, theirs (hrm__gap_miss: an Li whose slope jumps twice,
   falling 13 times between two samples of a first interval whose S1 and
   S2 agreed to 1/21 of their error, 7.7 rtol off with HRM_OK at rtol
   1e-3 on 17 samples). tau stays the halves' sum: nondecreasing. */
static HRM_DEVICE HRM__CALL void hrm__ns_five(const hrm__ctx *c, const hrm__pt *a, const hrm__pt *ql,
                         const hrm__pt *m, const hrm__pt *qr, const hrm__pt *b,
                         const hrm_real *tau_a, hrm_real *V, hrm_real *E, hrm_real *M, char *resolved)
{
    hrm_real s1[HRM__NY], e1[HRM__NY], vl[HRM__NY], vr[HRM__NY], tm[HRM__NY], f[5][HRM__CH];
    int i, k;
    hrm__ns_rule(c, a, m, b, tau_a, s1, e1, NULL);
    hrm__ns_rule(c, a, ql, m, tau_a, vl, e1, f);
    for (i = 0; i < HRM__NY; ++i) tm[i] = tau_a[i] + vl[i];
    hrm__ns_rule(c, m, qr, b, tm, vr, e1, f + 2);
    for (i = 0; i < HRM__NY; ++i) {
        hrm_real s2 = vl[i] + vr[i];
        V[i] = s2 + (i >= HRM__CH ? (s2 - s1[i]) / 15 : 0);
        E[i] = s2 - s1[i];
    }
    for (i = 0; i < HRM__CH; ++i) {
        /* a thick medium past an equiangular light's foot: the warp
           squeezes its tail into the last samples, where S1 and S2 agreed
           to 1/20 of their error */
        hrm_real t0, t1, d2 = hrm__diffs5((const hrm_real(*)[HRM__CH])f, i, &t0, &t1);
        hrm_real pred = hrm__fourth_from(d2, t0, t1, b->p - a->p);
        if (pred > HRM_FABS(E[HRM__CH + i])) E[HRM__CH + i] = E[HRM__CH + i] < 0 ? -pred : pred;
        if (resolved) resolved[i] = (char)hrm__resolved5((const hrm_real(*)[HRM__CH])f, i, d2, t0, t1);
    }
    hrm__fill(M, HRM__CH, 0);
    if (c->mcheck || c->homog) {
        /* V is Boole's rule on the five samples (Abramowitz and Stegun
           25.4.14): the medium is checked with it (constants: their
           emission alone) */
        static const hrm_real boole[5] = {HRM__R(7.0) / 90, HRM__R(32.0) / 90,
                                          HRM__R(12.0) / 90, HRM__R(32.0) / 90,
                                          HRM__R(7.0) / 90};
        const hrm__pt *nodes[5];
        nodes[0] = a;
        nodes[1] = ql;
        nodes[2] = m;
        nodes[3] = qr;
        nodes[4] = b;
        if (c->mcheck) hrm__medium_miss(c, nodes, boole, 5, b->p - a->p, a->tau, b->tau, a->off, b->off, M);
        else hrm__emission_miss(c, nodes, boole, 5, b->p - a->p, a->tau, b->tau, M);
    }
    for (i = 0; i < HRM__CH; ++i) {
        static const hrm_real x5[5] = {-1, HRM__R(-0.5), 0, HRM__R(0.5), 1};
        hrm_real fc[5];
        for (k = 0; k < 5; ++k) fc[k] = f[k][i];
        hrm__gap_miss(x5, fc, fc, NULL, 5, (b->p - a->p) / 2, 6, 0, &M[i]);
    }
}

/* An interval's estimate of L's error: the rule's, or the medium check's
   (hrm__medium_miss) where that is larger. */
static HRM_DEVICE void hrm__with_miss(hrm_real *E, const hrm_real *M)
{
    int i;
    for (i = 0; i < HRM__CH; ++i)
        if (HRM_FABS(E[HRM__CH + i]) < M[i]) E[HRM__CH + i] = M[i];
}

/* Nested Simpson left to right from one interval: tau at an interval's
   left end (acc) is final when it is judged, and its nodes' tau come from
   its own sigma_t samples as in hrm__simpson. */
static HRM_DEVICE HRM__CALL void hrm__ns_local_run(hrm__ctx *c, const hrm__pt *a, const hrm__pt *m, const hrm__pt *b,
                              hrm_real acc[HRM__NY], hrm__ns_half *stack)
{
    hrm__ns_iv cur;
    hrm_real val[HRM__NY], err[HRM__NY], miss[HRM__CH];
    int top = 0, i;

    cur.a = *a;
    cur.m = *m;
    cur.b = *b;
    cur.depth = 0;
    cur.parent = 0;
    for (;;) {
        hrm_real H = cur.b.p - cur.a.p, y1[HRM__NY], ratio;
        hrm__pt ql, qr;
        int split, last = cur.depth >= HRM_MAX_DEPTH || HRM_FABS(H) / 4 < c->h_min;
        if (last || hrm__spent(c) + 2 > c->max_evals) {
            /* no quarter points: the interval as it is, judged by
               Simpson against the trapezoid on its three points */
            hrm__ns_rule(c, &cur.a, &cur.m, &cur.b, acc, val, err, NULL);
            for (i = 0; i < HRM__NY; ++i) y1[i] = acc[i] + val[i];
            if (!last) hrm__warn(c, HRM_WARN_MAX_EVALS);
            else if (hrm__ratio(c, HRM__JUMP, cur.a.p, cur.b.p, acc, y1, err) > 1)
                hrm__warn(c, cur.depth >= HRM_MAX_DEPTH ? HRM_WARN_STORAGE : hrm__h_min_status(c));
            split = 0;
        } else {
            hrm__eval(c, (cur.a.p + cur.m.p) / 2, &ql);
            hrm__eval(c, (cur.m.p + cur.b.p) / 2, &qr);
            hrm__ns_five(c, &cur.a, &ql, &cur.m, &qr, &cur.b, acc, val, err, miss, NULL);
            for (i = 0; i < HRM__NY; ++i) {
                y1[i] = acc[i] + val[i];
                err[i] /= 5;
            }
            hrm__with_miss(err, miss);
            ratio = hrm__ratio(c, HRM_CONTROL_PI, cur.a.p, cur.b.p, acc, y1, err);
            split = ratio > 1 && !hrm__rough_ok(c, ratio, cur.parent, cur.a.p, cur.b.p, acc, y1, err);
            if (split && (cur.depth + 1 >= HRM_MAX_DEPTH || HRM_FABS(H) / 8 < c->h_min)) {
                /* its halves could not be refined further either */
                if (hrm__ratio(c, HRM__JUMP, cur.a.p, cur.b.p, acc, y1, err) > 1)
                    hrm__warn(c, cur.depth + 1 >= HRM_MAX_DEPTH ? HRM_WARN_STORAGE : hrm__h_min_status(c));
                split = 0;
            }
            if (split) {
                hrm__ns_half *right = &stack[top++];
                right->m = qr;
                right->b = cur.b;
                right->depth = cur.depth + 1;
                right->parent = ratio;
                cur.b = cur.m;
                cur.m = ql;
                cur.depth++;
                cur.parent = ratio;
                c->stats.rejected++;
            }
        }
        if (c->status != HRM_OK) return;
        if (!split) {
            memcpy(acc, y1, sizeof y1);
            hrm__accepted(c, err);
            c->stats.steps++;
            if (top == 0) return;
            --top;
            cur.a = cur.b; /* where the right half starts */
            cur.m = stack[top].m;
            cur.b = stack[top].b;
            cur.depth = stack[top].depth;
            cur.parent = stack[top].parent;
        }
    }
}

/* Its stack: in the caller's workspace, or else in a frame of its own,
   held only while a finish runs (a storage-full solve: rare). */
static HRM_DEVICE HRM__NOINLINE void hrm__ns_local_on_stack(hrm__ctx *c, const hrm__pt *a, const hrm__pt *m,
                                                 const hrm__pt *b, hrm_real acc[HRM__NY])
{
    hrm__ns_half stack[HRM_MAX_DEPTH + 1];
    hrm__ns_local_run(c, a, m, b, acc, stack);
}

static HRM_DEVICE void hrm__ns_local(hrm__ctx *c, const hrm__pt *a, const hrm__pt *m, const hrm__pt *b,
                          hrm_real acc[HRM__NY])
{
    if (c->finish) hrm__ns_local_run(c, a, m, b, acc, c->finish);
    else hrm__ns_local_on_stack(c, a, m, b, acc);
}


/* What a Gauss-Kronrod interval knows of its surroundings and returns
   for its halves: the source at its ends where sampled (the ray's ends,
   the centre node of the interval it was split from), and a check sample
   (a node of that interval inside this one, with its g); out, the source
   at its centre node, its node of the largest source and whether the
   check sample was left unexplained. */
typedef struct hrm__gk_io {
    hrm_real Sa[HRM__CH], Sb[HRM__CH], Sm[HRM__CH];
    hrm_real xc, gqc[HRM__CH], xm, gqm[HRM__CH];
    hrm_real M[HRM__CH]; /* out: the medium check's miss (hrm__medium_miss) */
    int ha, hb;         /* Sa, Sb known: 1, or 2 where a jump alone counts
                           (hrm__gk_ends_miss) */
    int hc, unexplained;
} hrm__gk_io;

/* Whether the halves of [a, b] would place their nodes apart, at t's
   resolution (without a warp, 2 eps |t0|), from every node of the
   intervals they descend from, which are not nested: over ten generations
   of bisection the closest pair is 1.8e-4 of the half's width for K15 and
   1.4e-2 for K7 (gap, in hrm__gk_pair). Closer, two nodes would round to
   one t and be evaluated twice. */
static HRM_DEVICE int hrm__gk_resolved(const hrm__ctx *c, hrm_real a, hrm_real b)
{
    /* (it matters on a ray farther from the origin than it is long;
       nearer, h_min stops the bisection long before) */
    return HRM_FABS(c->t0) <= c->T || HRM_FABS(b - a) / 2 * c->gk->gap >= c->h_res;
}

/* The source S at a sample (per unit length: its g divided by ds/dp). */
static HRM_DEVICE void hrm__source_of(const hrm__pt *pt, int ch, hrm_real *S)
{
    *S = pt->J > 0 ? pt->gq[ch] / pt->J : 0;
}

/* Gauss-Kronrod's checks of an interval [mid - hl, mid + hl] beyond
   |K - G|, channel ch, from its nodes pt (f: their values Tr S dt/dp as
   the rule weighs them). */

/* An interval whose end was sampled (an end of the ray, or the centre of
   the interval it was split from; io->ha, io->hb) sees the sample there:
   S at the end against its linear extrapolation from the two nearest
   nodes; a mismatch over the unsampled stretch (a thin layer at the
   camera or at the surface, a shadow's edge between the end and the first
   node) counts as error. Where the sample is a half's end in the left-to-
   right finish (ha or hb 2, hrm__gk_local_one) only a mismatch that a
   smooth S cannot make counts: S there off the parabola through three
   nodes by more than 4 times the line's distance from it, which is what
   the line misses of a smooth S (K's degree makes that no error of K's;
   counted at every split point, it had split smooth intervals to 0.01 of
   what K needed: the bench's local Gauss-Kronrod 10 times its
   evaluations). */
static HRM_DEVICE HRM__CALL hrm_real hrm__gk_ends_miss(const hrm__ctx *c, const hrm__gk_pair *R, const hrm__pt *pt,
                                  const hrm_real *f, hrm_real hl, const hrm__gk_io *io, int ch)
{
    hrm_real eend = 0;
    int e, N = R->n;
    for (e = 0; e < 2; ++e) {
        int j0 = e ? N - 1 : 0, j1 = e ? N - 2 : 1, j2 = e ? N - 3 : 2, kind = e ? io->hb : io->ha;
        hrm_real xe = e ? 1 : -1, s0, s1, s2, se, gap, att, r, pred, line;
        if (!kind) continue;
        hrm__source_of(&pt[j0], ch, &s0);
        hrm__source_of(&pt[j1], ch, &s1);
        se = (e ? io->Sb : io->Sa)[ch];
        gap = HRM_FABS(xe - R->x[j0]) * HRM_FABS(hl);
        /* weighed by the attenuation at the nearest node, as that node's
           own value is (absolute in closed form, relative to the
           interval's start when coupled) */
        att = pt[j0].gq[ch] != 0 ? f[j0] / pt[j0].gq[ch] : c->closed ? pt[j0].tr[ch] : 1;
        r = (xe - R->x[j0]) / (R->x[j0] - R->x[j1]);
        line = s0 + (s0 - s1) * r;
        /* fitted to the source's decay too: extrapolated as an
           exponential, which the fit integrates exactly */
        pred = c->expo == 2 && s0 > 0 && s1 > 0 ? s0 * HRM_EXP(HRM_LOG(s0 / s1) * r) : line;
        if (kind == 2) {
            hrm_real x0 = R->x[j0], x1 = R->x[j1], x2 = R->x[j2], q;
            hrm__source_of(&pt[j2], ch, &s2);
            q = s0 * (xe - x1) * (xe - x2) / ((x0 - x1) * (x0 - x2)) +
                s1 * (xe - x0) * (xe - x2) / ((x1 - x0) * (x1 - x2)) +
                s2 * (xe - x0) * (xe - x1) / ((x2 - x0) * (x2 - x1));
            if (HRM_FABS(se - q) <= 4 * HRM_FABS(q - line)) continue;
        }
        eend += HRM_FABS(se - pred) * pt[j0].J * gap * att;
    }
    return eend;
}

/* Tr unresolved before the first node: past an optical depth of 1
   between a and that node, the light of the stretch between them (a
   thick medium's, all of it) is in no node, and K and G agree on
   whatever the nodes see, 0 where Tr underflowed at all of them (L = 0
   with HRM_OK at sigma_t T = 1e6). Its integral of Tr, at the first
   node's source, is the error (ta: tau at a). */
static HRM_DEVICE hrm_real hrm__gk_deep_start(const hrm__ctx *c, const hrm__gk_pair *R, const hrm__pt *pt,
                                   const hrm_real *f, hrm_real hl, const hrm_real *Sa, hrm_real ta, int ch)
{
    hrm_real tx = c->coupled ? -HRM_LOG(pt[0].gq[ch] != 0 && f[0] > 0 ? f[0] / pt[0].gq[ch] : HRM__TINY)
                             : pt[0].tau[ch];
    hrm_real dt0 = tx - ta, src = HRM_FABS(pt[0].gq[ch]);
    if (Sa && HRM_FABS(Sa[ch]) * pt[0].J > src) src = HRM_FABS(Sa[ch]) * pt[0].J;
    return dt0 > 1 ? src * HRM_EXP(-ta) * (R->x[0] + 1) * HRM_FABS(hl) * -HRM_EXPM1(-dt0) / dt0 : 0;
}

/* A sample of the interval this one was split from, inside it (io->xc,
   io->gqc; lw: the nodes' Lagrange weights there): the nodes' interpolant
   there against the sample, over a node's share of the interval. Smooth,
   it misses by less than |K - G| (by h / l of it); a peak that the
   parent's node sat on and these nodes straddle misses by the peak: then
   K itself is in doubt, and the halves check it again. */
static HRM_DEVICE hrm_real hrm__gk_check_miss(const hrm__ctx *c, const hrm__gk_pair *R, const hrm__pt *pt,
                                   const hrm_real *f, hrm_real hl, const hrm_real *lw, const hrm__gk_io *io,
                                   int ch)
{
    hrm_real p_at = 0, lp = 0, att;
    int j, jn = 0, pos = c->expo == 2, N = R->n;
    for (j = 0; j < N; ++j) {
        p_at += lw[j] * pt[j].gq[ch];
        if (pos && pt[j].gq[ch] > 0) lp += lw[j] * HRM_LOG(pt[j].gq[ch]);
        else pos = 0;
        if (HRM_FABS(pt[j].p - io->xc) < HRM_FABS(pt[jn].p - io->xc)) jn = j;
    }
    /* fitted to the source's decay too: its logarithm interpolated */
    if (pos) p_at = HRM_EXP(lp);
    att = pt[jn].gq[ch] != 0 ? f[jn] / pt[jn].gq[ch] : c->closed ? pt[jn].tr[ch] : 1;
    return HRM_FABS(io->gqc[ch] - p_at) * att * 2 * HRM_FABS(hl) / (hrm_real)N;
}

/* What the nodes miss of the warp itself: the rule applied to ds/dp
   against the interval's length in s. A warp whose ds/dp peaks at an end
   within the gap to the first node (the equiangular warp's D / cos^2 p,
   1e-12 T wide at D = 1e-12 T) puts the light of a whole side of the ray
   there, and K and G agree on the little the nodes see (K7 and K15, light
   0.4 T from t0: L 52% low with HRM_OK; nested Simpson and the pairs
   sample the ends). Returns that miss in s beyond round-off (the
   offsets' and the rule's), 0 under no
   warp or the distance warp (whose ds/dp peaks where Tr has fallen with
   it); *je: the node nearest the end where ds/dp is larger, whose S Tr
   weighs the miss. (pt not const: g++ under nvcc took a const pointer
   to the caller's array for a read before its nodes were filled.) */
static HRM_DEVICE HRM__CALL hrm_real hrm__gk_warp_miss(hrm__ctx *c, const hrm__gk_pair *R, hrm__pt *pt,
                                   hrm_real a, hrm_real b, hrm_real oa, hrm_real ob, int *je)
{
    hrm_real rj = 0, rabs = 0, hl = (b - a) / 2, fl;
    int j, N = R->n;
    *je = pt[0].J >= pt[N - 1].J ? 0 : N - 1;
    if (c->warp != HRM_WARP_EQUIANGULAR && c->warp != HRM_WARP_USER) return 0;
    for (j = 0; j < N; ++j) {
        rj += R->wk[j] * pt[j].J;
        rabs += HRM_FABS(R->wk[j]) * pt[j].J;
    }
    fl = HRM__EPS * (4 * (HRM_FABS(oa) + HRM_FABS(ob)) + 50 * rabs * HRM_FABS(hl));
    fl = HRM_FABS(rj * hl - (ob - oa)) - fl;
    return fl > 0 ? fl : 0;
}

/* A kink between the nodes (an Li whose slope jumps: a host's shadow ray
   of a few fixed steps whose nodes cross a cloud's edge): K and G can
   agree by chance (Li = e^-g, g's slope rising by 9.3 at 0.36 of the one
   interval over the ray: |K - G| 1e-5 of K, K 4.4e-3 off, HRM_OK 186 rtol
   off at rtol 2.3e-5), but the polynomial through the nodes (f, over
   [mid - hl, mid + hl]) shows it: its Legendre coefficients stop falling,
   the highest two (c_n-1, c_n-2) more than 1/8 of the larger of
   c_n-5, c_n-6 (K7, of 7 nodes: 1/20 of c_n-3, c_n-4), where a smooth
   integrand's fall geometrically (1/20 for K15 too: evaluations on the
   bench's scenes +9% against +3%, silent kinks 3 against 4). Those
   two then bound K's error: over a random kink (slope rising 0..60 at
   0.02..0.98 of the interval), K's error was at most 0.89 of hl times
   the larger (0.3 typically). Returns hl times the larger of the highest
   two, where they do not fall and stand above round-off, else 0.
   hrm__gk takes half of it, or |K - G| where larger, as a miss, which
   the halves' trust never scales down (trusted, a kink's estimate fell
   32 times in one split and was believed: 37 rtol off; K7 under a warp,
   8 rtol). bench/sweep.c's
   kinks: 64 of 4000 solves silent (worst 186 rtol) -> 4 (5.0);
   evaluations there +10%, fog and lights +4% and +5%; over the bench's
   scenes (geometric mean of each configuration's ratio) K15 +3%, K7 +18%
   (13 times at rtol 1e-10 on the thin scene: a smooth integrand whose
   7 nodes' coefficients fall slowly). With a fit, in the fitted values
   times the exponential's mass. */
static HRM_DEVICE hrm_real hrm__gk_tail(const hrm__gk_pair *R, const hrm_real *f, hrm_real hl)
{
    return hrm__leg_tail(R->leg, R->n, f, R->n == 15 ? 8 : 20) * HRM_FABS(hl);
}

/* The Kronrod rule (c->gk) over [a, b] of y = (tau, L) given tau at a
   (tau_a; ignored when Tr at the nodes is known). K receives the
   increments; ek |K - G| (Munoz's estimate, G's error), at least 50
   epsilons of the integral of |f| (QUADPACK's floor of round-off), plus
   what the checks above and the medium check (hrm__medium_miss) find. The
   callers turn it into an estimate of K's (hrm__wf_split). */
static HRM_DEVICE HRM__CALL void hrm__gk(hrm__ctx *c, hrm_real a, hrm_real b, const hrm_real *tau_a,
                    hrm_real *K, hrm_real *ek, hrm__gk_io *io)
{
    const hrm__gk_pair *R = c->gk;
    const hrm_real *Sa = io->ha ? io->Sa : 0;
    hrm__pt pt[15];
    hrm_real hl = (b - a) / 2, mid = (a + b) / 2, off_a = 0, off_b = 0, J, lw[15], big = -1;
    hrm_real eK[HRM__CH], eG[HRM__CH], uK[HRM__CH], uG[HRM__CH], ta_at[HRM__CH];
    hrm_real gfit[HRM__EFIT_MAX][HRM__CH]; /* with a fit, its fitted values at the nodes */
    hrm_real mass[HRM__CH];                /* and its exponential's mass */
    hrm_real wmiss;
    int j, l, n, N = R->n, chk = io->hc && (io->xc - a) * (io->xc - b) < 0, ta_known = 0, je;

    for (j = 0; j < N; ++j) hrm__eval(c, 2 * j + 1 == N ? mid : mid + hl * R->x[j], &pt[j]);
    hrm__fill(io->M, HRM__CH, 0);
    /* the ends' offsets, mapped once for every use below, within the
       piece (a breakpoint's offset mapped to p and back may land an ulp
       past it, where the layer's tau holds that ulp of the next piece's
       sigma_t: a vacuum's interval at a slab's face at t = 15 kept a
       medium miss of 1e-13 that no split reduced, and refined to t's
       resolution) */
    hrm__map(c, a, &off_a, &J);
    hrm__map(c, b, &off_b, &J);
    off_a = off_a < c->o_lo ? c->o_lo : off_a;
    off_b = off_b > c->o_hi ? c->o_hi : off_b;
    wmiss = hrm__gk_warp_miss(c, R, pt, a, b, off_a, off_b, &je);
    if (c->mcheck || c->homog) {
        /* the nodes against the layer's tau at the interval's ends
           (constants: their emission alone) */
        const hrm__pt *nodes[15];
        hrm_real tea[HRM__CH], teb[HRM__CH];
        hrm__tau_of(c, off_a, tea);
        hrm__tau_of(c, off_b, teb);
        for (j = 0; j < N; ++j) nodes[j] = &pt[j];
        if (c->mcheck) hrm__medium_miss(c, nodes, R->wk, N, hl, tea, teb, off_a, off_b, io->M);
        else hrm__emission_miss(c, nodes, R->wk, N, hl, tea, teb, io->M);
    }
    if (chk) {
        /* the Lagrange weights of the nodes at the check sample */
        hrm_real xi = (io->xc - mid) / hl;
        for (j = 0; j < N; ++j) {
            lw[j] = 1;
            for (l = 0; l < N; ++l)
                if (l != j) lw[j] *= (xi - R->x[l]) / (R->x[j] - R->x[l]);
        }
    }
    io->unexplained = 0;
    for (j = 0; j < N; ++j) {
        /* the node where the source is largest: the check of the halves */
        hrm_real s = 0;
        for (n = 0; n < HRM__CH; ++n) s += HRM_FABS(pt[j].gq[n]);
        if (s > big) {
            big = s;
            io->xm = pt[j].p;
            memcpy(io->gqm, pt[j].gq, sizeof io->gqm);
        }
    }
    if (c->coupled) {
        memcpy(ta_at, tau_a, sizeof ta_at);
        ta_known = 1;
    } else if (!c->expo || c->warp != HRM_WARP_NONE) {
        /* tau at a, where the first node is optically deep (below; a fit
           is exact there only without a warp) */
        for (n = 0; n < HRM__CH; ++n) ta_known |= pt[0].tau[n] > 1;
        if (ta_known) hrm__tau_of(c, off_a, ta_at);
    }
    if (c->expo) {
        /* K and G against the exact local exponential */
        hrm__pt pg[HRM__EFIT_MAX];
        for (j = 0, l = 0; j < N; ++j)
            if (R->wg[j] != 0) pg[l++] = pt[j];
        hrm__efit_panel(c, &c->ef[1], pg, hl, eG, mass, gfit, uG);
        hrm__efit_panel(c, &c->ef[0], pt, hl, eK, mass, gfit, uK);
    }
    for (n = 0; n < HRM__NY; ++n) {
        int ch = n % HRM__CH, is_tau = n < HRM__CH;
        hrm_real f[15], rk = 0, rg = 0, rabs = 0, eend;
        if (is_tau && !c->coupled) {
            K[n] = ek[n] = 0;
            continue;
        }
        for (j = 0; j < N; ++j) {
            if (is_tau) {
                f[j] = pt[j].gs[ch];
            } else if (c->coupled) {
                /* tau at the node: the interpolant of sigma_t - sbar at all nodes
                   integrated from a, and sbar over the distance */
                hrm_real t = 0;
                for (l = 0; l < N; ++l) t += R->tau[j * N + l] * pt[l].gs[ch];
                t = tau_a[ch] + c->sbar[ch] * (pt[j].off - off_a) + t * hl;
                f[j] = HRM_EXP(-(t > tau_a[ch] ? t : tau_a[ch])) * pt[j].gq[ch];
            } else {
                f[j] = pt[j].tr[ch] * pt[j].gq[ch];
            }
            rk += R->wk[j] * f[j];
            rg += R->wg[j] * f[j];
            rabs += R->wk[j] * HRM_FABS(f[j]);
        }
        K[n] = rk * hl;
        if (is_tau) K[n] += c->sbar[ch] * (off_b - off_a);
        ek[n] = HRM_FABS((rk - rg) * hl);
        if (!is_tau) {
            /* a kink between the nodes (hrm__gk_tail; with a fit, in its
               fitted values, over the exponential's mass): half the
               coefficients that did not fall, or the rule's estimate
               where larger, as a miss, which no trust in the halves
               scales down */
            hrm_real gc[15], tl;
            if (c->expo) {
                for (j = 0; j < N; ++j) gc[j] = gfit[j][ch];
                hrm__gap_miss(R->x, gc, f, NULL, N, hl, 8, 0, &io->M[ch]);
                K[n] = eK[ch];
                ek[n] = HRM_FABS(eK[ch] - eG[ch]) + (uK[ch] > uG[ch] ? uK[ch] : uG[ch]);
                tl = hrm__gk_tail(R, gc, 1) * mass[ch] / 2;
            } else {
                hrm__gap_miss(R->x, f, f, NULL, N, hl, 8, 0, &io->M[ch]);
                tl = hrm__gk_tail(R, f, hl) / 2;
            }
            if (tl > 0 && ek[n] > tl) tl = ek[n];
            if (tl > io->M[ch]) io->M[ch] = tl;
        }
        eend = 0;
        if (!is_tau) eend = hrm__gk_ends_miss(c, R, pt, f, hl, io, ch);
        if (!is_tau && ta_known && (!c->expo || c->warp != HRM_WARP_NONE))
            eend += hrm__gk_deep_start(c, R, pt, f, hl, Sa, ta_at[ch], ch);
        rabs *= HRM_FABS(hl);
        if (ek[n] < 50 * HRM__EPS * rabs) ek[n] = 50 * HRM__EPS * rabs;
        ek[n] += eend;
        /* the warp's miss at the nodes' S Tr there, where it is larger */
        if (!is_tau && wmiss > 0 && pt[je].J > 0 && HRM_FABS(f[je]) / pt[je].J * wmiss > ek[n])
            ek[n] = HRM_FABS(f[je]) / pt[je].J * wmiss;
        /* the round-off of the nodes' abscissae, eps |p| each, which moves
           tau by its slope in p times that: where a warp packs many optical
           depths into a stretch of p far from 0 (the equiangular warp near
           -pi/2, a light 1e-4 T off, sigma_t T 1e6: 10 optical depths in
           6e-9 of p), L's round-off, which no estimate of the rule sees (K7
           at rtol 1e-8: 7.5e-8 off, its estimates 5e-9, HRM_OK); kept
           apart from |K - G|, which the callers scale by the rate splits
           show, as the medium's miss is */
        if (!is_tau && !c->coupled && pt[N - 1].p > pt[0].p) {
            hrm_real r = rabs * HRM__EPS * (HRM_FABS(a) > HRM_FABS(b) ? HRM_FABS(a) : HRM_FABS(b)) *
                         (pt[N - 1].tau[ch] - pt[0].tau[ch]) / (pt[N - 1].p - pt[0].p);
            if (r > io->M[ch]) io->M[ch] = r;
        }
        if (chk && !is_tau) {
            hrm_real mis = hrm__gk_check_miss(c, R, pt, f, hl, lw, io, ch);
            if (mis > ek[n]) {
                /* Missed by more than a thousandth of K, the nodes do not
                   resolve the integrand there: the whole of K is in doubt
                   (the miss over a node's share alone let a peak 1e-2
                   wide near the ray's end pass 20% low). A smaller miss
                   is the error itself (smooth, at tight rtol). */
                ek[n] = mis > HRM__R(1e-3) * HRM_FABS(K[n]) ? mis + HRM_FABS(K[n]) : mis;
                io->unexplained = 1;
            }
        }
        if (!is_tau) hrm__source_of(&pt[N / 2], ch, &io->Sm[ch]);
    }
}

/* The ray's two ends, sampled once: Gauss-Kronrod's nodes never reach an
   interval's ends, so without them a thin layer at the camera or at the
   surface could pass unseen (hrm__gk). Two evaluations. S receives the
   source there; has[1] is 0 on an infinite ray (its far end is where the
   warp stops: no surface, no layer there). */
static HRM_DEVICE void hrm__gk_ends(hrm__ctx *c, hrm_real S[2][HRM__CH], int has[2])
{
    hrm__pt e;
    int i, k;
    for (k = 0; k < 2; ++k) {
        hrm__eval(c, k ? c->pb : c->pa, &e);
        for (i = 0; i < HRM__CH; ++i) hrm__source_of(&e, i, &S[k][i]);
        has[k] = k == 0 || HRM__FINITE(c->T);
    }
}

/* One interval [a0, b0] finished left to right from tau at its left end
   (acc), its own increments and estimates relative to that end given (K0,
   E0); a refused interval is split in two and its samples discarded but
   its centre node's source, which is where its halves meet: that end of
   each half is known, as in the worst-first driver (an emission that
   ends just past the centre, before the right half's first node, 0.0043
   of its width in, is otherwise in no node at any depth: a bump's Le
   ending 1e-4 of the ray past a dyadic point, every half accepted, L 7
   rtol off with HRM_OK at rtol 1e-4). The source at a0 and b0 where
   sampled (Sa, Sb, or 0), and at its centre, which the caller's rule
   sampled (Sm). */
static HRM_DEVICE HRM__CALL void hrm__gk_local_one(hrm__ctx *c, hrm_real a0, hrm_real b0, const hrm_real *K0,
                              const hrm_real *E0, const hrm_real *Sa, const hrm_real *Sb,
                              const hrm_real *Sm, hrm_real acc[HRM__NY])
{
    hrm_real stack_a[HRM_MAX_DEPTH + 2], stack_b[HRM_MAX_DEPTH + 2], stack_r[HRM_MAX_DEPTH + 2];
    hrm_real stack_s[HRM_MAX_DEPTH + 2][HRM__CH]; /* the source at b, */
    char stack_h[HRM_MAX_DEPTH + 2];              /* where known (1: the
                                                     caller's, 2: a centre
                                                     node's; hrm__gk_io) */
    hrm_real s_a[HRM__CH]; /* at the next interval's start (the last */
    int have_a = Sa != 0;  /* accepted one's end), where known */
    int stack_d[HRM_MAX_DEPTH + 2], top = 1, i;

    hrm__fill(s_a, HRM__CH, 0);
    hrm__fill(stack_s[0], HRM__CH, 0);
    stack_a[0] = a0;
    stack_b[0] = b0;
    stack_d[0] = 0;
    stack_r[0] = 0;
    stack_h[0] = Sb != 0;
    if (Sa) memcpy(s_a, Sa, sizeof s_a);
    if (Sb) memcpy(stack_s[0], Sb, sizeof stack_s[0]);
    while (top > 0) {
        hrm_real a = stack_a[top - 1], b = stack_b[top - 1], parent = stack_r[top - 1];
        hrm_real K[HRM__NY], ek[HRM__NY], y1[HRM__NY], ratio, s_b[HRM__CH], s_m[HRM__CH];
        int d = stack_d[--top], split, have_b = stack_h[top];
        long reserve = c->gk->n * ((long)top + 2);
        memcpy(s_b, stack_s[top], sizeof s_b);
        if (d == 0) { /* integrated already, relative to its left end */
            for (i = 0; i < HRM__NY; ++i) {
                hrm_real f = i < HRM__CH || c->closed ? 1 : HRM_EXP(-acc[i % HRM__CH]);
                K[i] = f * K0[i];
                ek[i] = f * E0[i];
            }
            memcpy(s_m, Sm, sizeof s_m);
        } else {
            hrm__gk_io io;
            io.ha = have_a;
            io.hb = have_b;
            io.hc = 0;
            memcpy(io.Sa, s_a, sizeof io.Sa);
            memcpy(io.Sb, s_b, sizeof io.Sb);
            hrm__gk(c, a, b, acc, K, ek, &io);
            hrm__with_miss(ek, io.M);
            memcpy(s_m, io.Sm, sizeof s_m);
        }
        if (c->status != HRM_OK) return;
        for (i = 0; i < HRM__NY; ++i) y1[i] = acc[i] + K[i];
        ratio = hrm__ratio(c, HRM_CONTROL_PI, a, b, acc, y1, ek);
        split = ratio > 1 && !hrm__rough_ok(c, ratio, parent, a, b, acc, y1, ek);
        if (split && (d >= HRM_MAX_DEPTH || HRM_FABS(b - a) / 2 < c->h_min || !hrm__gk_resolved(c, a, b))) {
            if (hrm__ratio(c, HRM__JUMP, a, b, acc, y1, ek) > 1)
                hrm__warn(c, d >= HRM_MAX_DEPTH ? HRM_WARN_STORAGE : hrm__h_min_status(c));
            split = 0;
        }
        if (split && hrm__spent(c) + reserve > c->max_evals) {
            hrm__warn(c, HRM_WARN_MAX_EVALS);
            split = 0;
        }
        if (split) {
            stack_a[top] = (a + b) / 2;
            stack_b[top] = b;
            stack_r[top] = ratio;
            stack_h[top] = (char)have_b;
            memcpy(stack_s[top], s_b, sizeof s_b);
            stack_d[top++] = d + 1;
            stack_a[top] = a;
            stack_b[top] = (a + b) / 2;
            stack_r[top] = ratio;
            stack_h[top] = 2;
            memcpy(stack_s[top], s_m, sizeof s_m);
            stack_d[top++] = d + 1;
            c->stats.rejected++;
        } else {
            memcpy(acc, y1, sizeof y1);
            hrm__accepted(c, ek);
            c->stats.steps++;
            have_a = have_b;
            memcpy(s_a, s_b, sizeof s_a);
        }
    }
}

/* Gauss-Kronrod, Munoz's local mode: the initial intervals are integrated
   first, relative to tau at their own left ends (their sum is the scale);
   then each is finished left to right (hrm__gk_local_one), so tau at each
   left end is final. */
static HRM_DEVICE HRM__CALL HRM__NOINLINE void hrm__gk_local(hrm__ctx *c, int n0, hrm_real acc[HRM__NY])
{
    hrm_real K0[HRM_GK_INITIAL][HRM__NY], E0[HRM_GK_INITIAL][HRM__NY], Sm0[HRM_GK_INITIAL][HRM__CH];
    hrm_real span = c->pb - c->pa, zero[HRM__NY], tot[HRM__NY], S[2][HRM__CH];
    int k, ch, has[2];

    if (n0 > HRM_GK_INITIAL) n0 = HRM_GK_INITIAL;
    hrm__gk_ends(c, S, has);
    hrm__fill(zero, HRM__NY, 0);
    hrm__fill(tot, HRM__NY, 0);
    for (k = 0; k < n0; ++k) {
        hrm_real a = c->pa + span * ((hrm_real)k / (hrm_real)n0);
        hrm_real b = k + 1 == n0 ? c->pb : c->pa + span * ((hrm_real)(k + 1) / (hrm_real)n0);
        hrm__gk_io io;
        io.ha = k == 0;
        io.hb = k + 1 == n0 && has[1];
        io.hc = 0;
        memcpy(io.Sa, S[0], sizeof io.Sa);
        memcpy(io.Sb, S[1], sizeof io.Sb);
        hrm__gk(c, a, b, zero, K0[k], E0[k], &io);
        hrm__with_miss(E0[k], io.M);
        memcpy(Sm0[k], io.Sm, sizeof Sm0[k]);
        for (ch = 0; ch < HRM__CH; ++ch) {
            hrm_real f = c->closed ? 1 : HRM_EXP(-tot[ch]);
            tot[ch] += K0[k][ch];
            tot[HRM__CH + ch] += f * K0[k][HRM__CH + ch];
        }
    }
    hrm__set_scale(c, tot);

    hrm__fill(acc, HRM__NY, 0);
    for (k = 0; k < n0 && c->status == HRM_OK; ++k)
        hrm__gk_local_one(c, c->pa + span * ((hrm_real)k / (hrm_real)n0),
                          k + 1 == n0 ? c->pb : c->pa + span * ((hrm_real)(k + 1) / (hrm_real)n0),
                          K0[k], E0[k], k == 0 ? S[0] : 0, k + 1 == n0 && has[1] ? S[1] : 0, Sm0[k], acc);
}

/* Worst-first refinement (QUADPACK QAG's strategy), shared by nested
   Simpson and global Gauss-Kronrod: the interval with the largest error
   estimate is split until the summed estimate meets the tolerance of the
   current total, so the tolerance follows the best estimate of |L| and an
   interval accepted early is refined again if the total proves smaller.
   A budget that runs out leaves the best estimate its samples give, the
   error spread where it was largest. Each interval stores its increments
   relative to tau at its own left end (tau_a = 0), and the intervals are
   kept in order so that exp(-tau(a)) follows every refinement to their
   left; with Tr known at the nodes that factor is 1. */
typedef struct hrm__iv {
    hrm_real a, b, V[HRM__NY], E[HRM__NY];
    hrm_real D[HRM__NY]; /* |S2 - S1| or |K - G| */
    hrm_real M[HRM__CH]; /* the medium check's miss (hrm__medium_miss) */
    char fell[HRM__NY]; /* its raw estimate D fell (hrm__wf_trust) at its split */
    int rough; /* splits in a row at which it kept 30% of its parent's estimate */
    hrm_real score; /* its estimates over their shares (hrm__wf_sum) */
} hrm__iv;

/* Each driver's interval: the shared part first, then its own. */
typedef struct hrm__nsi {
    hrm__iv h;
    int s[4]; /* its samples at a, a + h/4, a + h/2, a + 3h/4 */
    char resolved[HRM__CH]; /* its samples of L' look resolved (hrm__resolved5) */
} hrm__nsi;

typedef struct hrm__gki {
    hrm__iv h;
    hrm__gk_io io; /* ends, check sample, centre */
} hrm__gki;

/* The worst-first drivers' storage: nested Simpson's intervals and their
   samples; global Gauss-Kronrod's intervals. Held (hrm__stage) only by
   the solves that run them. */
typedef struct hrm__ns_store {
    hrm__nsi iv[HRM_NS_INTERVALS];
    hrm__pt pool[4 * HRM_NS_INTERVALS + 1];
} hrm__ns_store;

typedef struct hrm__gk_store {
    hrm__gki iv[HRM_GK_INTERVALS];
} hrm__gk_store;

/* The driver's own part of interval v. */
#define HRM__NSI(v) ((hrm__nsi *)(void *)(v))
#define HRM__GKI(v) ((hrm__gki *)(void *)(v))

typedef struct hrm__wf {
    unsigned char *iv; /* the driver's intervals (hrm__nsi or hrm__gki) */
    size_t stride;     /* their size */
    int n, cap;   /* intervals held, storage */
    hrm__pt *pool; /* nested Simpson's samples (0: Gauss-Kronrod) */
    int np, end;  /* samples held; the index of the ray's end sample */
} hrm__wf;

/* Interval i's shared part. */
static HRM_DEVICE hrm__iv *hrm__wf_at(const hrm__wf *w, int i)
{
    return (hrm__iv *)(void *)(w->iv + (size_t)i * w->stride);
}

/* The interval's increments and estimates by its rule. */
static HRM_DEVICE HRM__CALL void hrm__wf_rule(hrm__ctx *c, hrm__wf *w, hrm__iv *v, int b_sample)
{
    hrm_real zero[HRM__NY];
    int i;
    hrm__fill(zero, HRM__NY, 0);
    if (w->pool) {
        hrm__pt *P = w->pool;
        const int *s = HRM__NSI(v)->s;
        hrm__ns_five(c, &P[s[0]], &P[s[1]], &P[s[2]], &P[s[3]], &P[b_sample], zero, v->V, v->E, v->M,
                     HRM__NSI(v)->resolved);
    } else {
        hrm__gk_io *io = &HRM__GKI(v)->io;
        hrm__gk(c, v->a, v->b, zero, v->V, v->E, io);
        memcpy(v->M, io->M, sizeof v->M);
    }
    for (i = 0; i < HRM__NY; ++i) {
        v->D[i] = v->E[i] = HRM_FABS(v->E[i]);
        v->fell[i] = 0;
    }
    /* (D, from which the trust in the halves is judged, is the rule's
       alone: the medium's miss is an error of V itself, never scaled) */
    hrm__with_miss(v->E, v->M);
    v->rough = 0;
}

/* How far a split lets the halves l, r of par trust their estimates:
   fall is the fall of the raw estimate D that shows the asymptotic regime,
   cap the factor applied there, square the nested Simpson variant. For
   nested Simpson, E = |S2 - S1| / 5 estimates S2's error with a factor 3
   of margin once the halves are in the asymptotic regime, where S2 - S1
   falls like h^5 (16 times in the two halves together). There the
   parent's miss of the halves' sum, |V - (V_l + V_r)|, measures the error
   of its Richardson-corrected value, which falls faster still: its ratio
   to the parent's |S2 - S1| (at least the square of the fall: a miss that
   cancels by chance is no evidence), where smaller than 1/5, is the
   halves' factor instead. The regime counts as reached when D fell (8
   times) at this split and at the parent's own (a fall short of 16 that
   one half holds alone does not count: a kink's second-order fall, a mild
   one 0.0003 before a sample 19 rtol off with HRM_OK at rtol 1e-5), and
   only for a half whose samples look resolved (hrm__resolved5): until
   then S2 - S1 itself is the estimate, since a boundary layer that a few
   samples cannot resolve (a thick medium), an oscillation they alias or
   a kink between them (falls of 8 by chance: make render's cloud, a pixel
   5.5 rtol off with HRM_OK at rtol 1e-3) leaves the corrected sum as far
   off as S2 and S1 are apart. (Measured on the bench's smooth scenes,
   rtol 1e-2..1e-10: worst HRM_OK run 0.64 rtol,
   median 0.009-0.022 (0.006 with the fall itself as the floor); one fall
   of 8 let smoke through at 5.7 rtol, a fall of 16 once made a budget of
   65 samples 100 times worse than a uniform Simpson rule on a smooth
   light.) Gauss-Kronrod: hrm__wf_split; where the parent's miss is more
   than 1/64 of its |K - G| (K not yet far better than G7: no asymptotic
   regime, where K15's error falls like h^23 and |K - G| like h^15), the
   halves together keep at least a quarter of the miss, a second-order
   fall (a kink inside the parent, whose halves' |K - G| fell 4 times
   twice by chance: the right half 2.2e-5 against an error of 4.7e-4, 27
   rtol off with HRM_OK at rtol 1e-4; kinked-Li search, K15 silent at
   1e-4 259 -> 119 of 3000, K7 98 -> 43, for +0.1% of the bench's
   evaluations). Never below 16 epsilons of V. */
static HRM_DEVICE HRM__CALL void hrm__wf_trust(const hrm__ctx *c, const hrm__iv *par, hrm__iv *l, hrm__iv *r,
                          hrm_real fall, hrm_real cap, int square)
{
    int j;
    for (j = 0; j < HRM__NY; ++j) {
        hrm_real q = cap, f = 1, rho = par->D[j] > 0 ? (l->D[j] + r->D[j]) / par->D[j] : 1, lo, fl;
        int fell = rho <= fall;
        /* nested Simpson: a fall no better than 1/16 that one half holds
           alone (90%) is a kink's second-order fall, not the asymptotic one */
        if (square && fell && rho > fall / 2 &&
            (l->D[j] > HRM__R(0.9) * (l->D[j] + r->D[j]) || r->D[j] > HRM__R(0.9) * (l->D[j] + r->D[j])))
            fell = 0;
        l->fell[j] = r->fell[j] = (char)fell;
        if (!fell || !par->fell[j]) continue;
        if (j >= HRM__CH || !square) {
            if (j >= HRM__CH && !c->closed) f = HRM_EXP(-l->V[j - HRM__CH]);
            q = HRM_FABS(par->V[j] - l->V[j] - f * r->V[j]) / par->D[j];
            /* (nested Simpson: a miss that cancels by chance is no evidence) */
            lo = square ? rho * rho : 0;
            q = q > lo ? q : lo;
            q = q < cap ? q : cap;
        }
        fl = 16 * HRM__EPS * HRM_FABS(l->V[j]);
        if (!square || j < HRM__CH || HRM__NSI(l)->resolved[j - HRM__CH]) l->E[j] = l->D[j] * q > fl ? l->D[j] * q : fl;
        fl = 16 * HRM__EPS * HRM_FABS(r->V[j]);
        if (!square || j < HRM__CH || HRM__NSI(r)->resolved[j - HRM__CH]) r->E[j] = r->D[j] * q > fl ? r->D[j] * q : fl;
        if (!square && j >= HRM__CH && q > HRM__R(1.0) / 64 && l->D[j] + r->D[j] > 0) {
            /* Gauss-Kronrod whose K missed by more than 1/64 of |K - G|:
               the halves hold at least a quarter of that miss, shared as
               their |K - G| */
            hrm_real share = q * par->D[j] / 4 / (l->D[j] + r->D[j]);
            if (l->D[j] * share > l->E[j]) l->E[j] = l->D[j] * share;
            if (r->D[j] * share > r->E[j]) r->E[j] = r->D[j] * share;
        }
    }
    hrm__with_miss(l->E, l->M);
    hrm__with_miss(r->E, r->M);
}

static HRM_DEVICE int hrm__locate_jump(hrm__ctx *c, hrm_real pl, hrm_real pr, hrm_real *tj);

/* A half that keeps 30% of its parent's raw estimate, three splits in a
   row, does not shrink like a smooth integrand's (1/32 for nested
   Simpson, far less for Gauss-Kronrod): a jump, most likely. It is
   located there and then; a jump found ends the pass (c->jump_found) and
   hrm__dispatch solves again with it as a breakpoint. Where the bisection
   finds none (a steep but smooth integrand: a dense front seen through
   the equiangular warp) the solve goes on without looking again, instead
   of being repeated. */
static HRM_DEVICE HRM__CALL void hrm__wf_rough(hrm__ctx *c, const hrm__iv *par, hrm__iv *l, hrm__iv *r)
{
    hrm_real dl = 0, dr = 0, dp = 0;
    int j;
    for (j = HRM__CH; j < HRM__NY; ++j) {
        dl += l->D[j];
        dr += r->D[j];
        dp += par->D[j];
    }
    l->rough = dp > 0 && dl > HRM__R(0.3) * dp ? par->rough + 1 : 0;
    r->rough = dp > 0 && dr > HRM__R(0.3) * dp ? par->rough + 1 : 0;
    /* (locating the jump, at most 64 evaluations, and the first samples of
       every piece of the solve with it must fit in the budget's rest, with
       as much again to refine) */
    if (!c->find_jumps || c->jump_found ||
        c->max_evals - c->stats.evals < 64 + 2 * c->piece_cost * ((long)c->nbrk + 2))
        return;
    if (l->rough >= 3 || r->rough >= 3) {
        const hrm__iv *v = l->rough >= 3 ? l : r;
        hrm_real e = 0, splits;
        for (j = HRM__CH; j < HRM__NY; ++j) e += v->E[j];
        /* only where refining on (halving its estimate at each split)
           would cost more than locating it (at a loose rtol a few splits
           finish the job: nested Simpson on the occluder at rtol 1e-2, 73
           samples, 197 with the search) */
        splits = c->wf_tol > 0 && e > c->wf_tol ? HRM_LOG(e / c->wf_tol) / HRM_LOG(2) : 0;
        if (splits * (hrm_real)c->split_cost < 64) return;
        if (c->njumps < HRM_MAX_JUMPS && c->nbrk < HRM_MAX_BREAKS && hrm__locate_jump(c, v->a, v->b, &c->cand_t))
            c->jump_found = 1;
        else
            c->find_jumps = 0;
    }
}

/* Split interval k in place into its halves. Nested Simpson: the halves
   keep the five samples and add their quarter points (4 evaluations). */
static HRM_DEVICE HRM__CALL void hrm__wf_split(hrm__ctx *c, hrm__wf *w, int k)
{
    union {
        hrm__nsi ns;
        hrm__gki gk;
    } pu; /* the parent, whole */
    hrm__iv *l = hrm__wf_at(w, k), *r = hrm__wf_at(w, k + 1), par;
    int j, b_sample = w->pool && k + 1 < w->n ? HRM__NSI(r)->s[0] : w->end;
    memcpy(&pu, l, w->stride);
    par = pu.ns.h;
    for (j = w->n; j > k + 1; --j) /* memmove is host-only in CUDA */
        memcpy(hrm__wf_at(w, j), hrm__wf_at(w, j - 1), w->stride);
    w->n++;
    l->a = par.a;
    l->b = r->a = (par.a + par.b) / 2;
    r->b = par.b;
    if (w->pool) {
        hrm__pt *P = w->pool;
        const int *ps = pu.ns.s;
        int *ls = HRM__NSI(l)->s, *rs = HRM__NSI(r)->s, q = w->np;
        w->np += 4;
        hrm__eval(c, (P[ps[0]].p + P[ps[1]].p) / 2, &P[q]);
        hrm__eval(c, (P[ps[1]].p + P[ps[2]].p) / 2, &P[q + 1]);
        hrm__eval(c, (P[ps[2]].p + P[ps[3]].p) / 2, &P[q + 2]);
        hrm__eval(c, (P[ps[3]].p + P[b_sample].p) / 2, &P[q + 3]);
        ls[0] = ps[0];
        ls[1] = q;
        ls[2] = ps[1];
        ls[3] = q + 1;
        rs[0] = ps[2];
        rs[1] = q + 2;
        rs[2] = ps[3];
        rs[3] = q + 3;
        hrm__wf_rule(c, w, l, ps[2]);
        hrm__wf_rule(c, w, r, b_sample);
        hrm__wf_trust(c, &par, l, r, HRM__R(1.0) / 8, HRM__R(0.2), 1);
    } else {
        /* the parent's centre node is the halves' common end; a check
           sample the parent left unexplained, else its node of the
           largest source, checks the half it falls in */
        const hrm__gk_io *pio = &pu.gk.io;
        hrm__gk_io *lio = &HRM__GKI(l)->io, *rio = &HRM__GKI(r)->io;
        hrm__iv *h[2];
        int e;
        h[0] = l;
        h[1] = r;
        memcpy(lio->Sb, pio->Sm, sizeof pio->Sm);
        memcpy(rio->Sa, pio->Sm, sizeof pio->Sm);
        memcpy(rio->Sb, pio->Sb, sizeof pio->Sb);
        lio->hb = rio->ha = 1;
        rio->hb = pio->hb;
        for (e = 0; e < 2; ++e) {
            hrm__gk_io *o = &HRM__GKI(h[e])->io;
            o->hc = 0;
            if (pio->hc && pio->unexplained &&
                (pio->xc - h[e]->a) * (pio->xc - h[e]->b) < 0) {
                o->hc = 1;
                o->xc = pio->xc;
                memcpy(o->gqc, pio->gqc, sizeof o->gqc);
            } else if ((pio->xm - h[e]->a) * (pio->xm - h[e]->b) < 0) {
                o->hc = 1;
                o->xc = pio->xm;
                memcpy(o->gqc, pio->gqm, sizeof o->gqc);
            }
        }
        hrm__wf_rule(c, w, l, 0);
        hrm__wf_rule(c, w, r, 0);
        /* |K - G| bounds G's error, not K's: K15 is exact to degree 22 and
           G7 to 13 (K7 to 11, G3 to 5), so K's error falls like h^23
           (h^13) where |K - G| falls like h^15 (h^7). Once splits show
           |K - G| falling (4 times at least, twice in a row), the parent's
           own miss |K - (K_l + K_r)| measures K's error on it, and its
           ratio to the parent's |K - G|, applied to the halves, overstates
           theirs by 2^8 (2^6) in the asymptotic regime. (A sixteenth of it
           let the worst HRM_OK run on the bench's smooth scenes reach 13
           rtol with K15; one fall alone let a light's peak 1e-2 wide pass
           at 75 rtol; the fall as a floor under the ratio cost 4-17 times
           the samples at rtol 1e-8..1e-10.) */
        hrm__wf_trust(c, &par, l, r, HRM__R(0.25), 1, 0);
    }
    hrm__wf_rough(c, &par, l, r);
}

/* Sum the intervals: acc = (tau, L), err_acc = L's estimate; the score of
   each interval (its weighted estimate over the tolerance) goes to *pick
   for the largest, the leftmost of those within 1e-6 of it (a medium
   given as callbacks or as constants then refines the same intervals:
   round-off does not decide). Returns 1 when the tolerance is met. The weighted
   tau estimates add up to at most rtol min(tau, 1): L's relative error
   from tau is at most their sum where its light comes from. */
static HRM_DEVICE HRM__CALL int hrm__wf_sum(hrm__ctx *c, hrm__wf *w, hrm_real acc[HRM__NY], int *pick)
{
    hrm_real tau[HRM__CH], L[HRM__CH], EL[HRM__CH], Et[HRM__CH], tolL[HRM__CH], tolt[HRM__CH];
    hrm_real worst = -1;
    int i, ch, done = 1;
    *pick = -1;
    hrm__fill(tau, HRM__CH, 0);
    hrm__fill(L, HRM__CH, 0);
    hrm__fill(EL, HRM__CH, 0);
    hrm__fill(Et, HRM__CH, 0);
    /* the sums (with Tr known at the nodes each interval's factor is 1) */
    for (i = 0; i < w->n; ++i) {
        const hrm__iv *v = hrm__wf_at(w, i);
        for (ch = 0; ch < HRM__CH; ++ch) {
            hrm_real f = c->closed ? 1 : HRM_EXP(-tau[ch]);
            tau[ch] += v->V[ch];
            L[ch] += f * v->V[HRM__CH + ch];
            EL[ch] += f * v->E[HRM__CH + ch];
            Et[ch] += f * v->E[ch];
        }
    }
    c->wf_tol = 0;
    for (ch = 0; ch < HRM__CH; ++ch) {
        hrm_real t = HRM_FABS(tau[ch]) < 1 ? HRM_FABS(tau[ch]) : 1;
        tolL[ch] = c->rtol * HRM_FABS(L[ch]);
        tolL[ch] = tolL[ch] > c->atol ? tolL[ch] : c->atol;
        tolt[ch] = c->rtol * t;
        done &= EL[ch] <= tolL[ch] && Et[ch] <= tolt[ch];
        c->wf_tol += tolL[ch];
        acc[ch] = tau[ch];
        acc[HRM__CH + ch] = L[ch];
        c->err_acc[ch] = EL[ch]; /* the estimate of what it returns */
    }
    if (done) return 1;
    /* the scores */
    hrm__fill(tau, HRM__CH, 0);
    for (i = 0; i < w->n; ++i) {
        hrm__iv *v = hrm__wf_at(w, i);
        hrm_real score = 0;
        for (ch = 0; ch < HRM__CH; ++ch) {
            hrm_real eL = v->E[HRM__CH + ch], et = v->E[ch];
            if (!c->closed) {
                hrm_real f = HRM_EXP(-tau[ch]);
                tau[ch] += v->V[ch];
                eL *= f;
                et *= f;
            }
            eL = tolL[ch] > 0 ? eL / tolL[ch] : eL * HRM__R(1e30);
            et = tolt[ch] > 0 ? et / tolt[ch] : et * HRM__R(1e30);
            score = score > eL ? score : eL;
            score = score > et ? score : et;
        }
        v->score = score;
        if (score > worst) worst = score;
    }
    /* the first interval within a millionth of the worst score */
    for (i = 0; i < w->n; ++i)
        if (hrm__wf_at(w, i)->score >= worst * (1 - HRM__R(1e-6))) {
            *pick = i;
            break;
        }
    return 0;
}

/* Returns 1 if the intervals filled their storage before the tolerance
   was met (the caller finishes or warns), else 0. */
static HRM_DEVICE HRM__CALL int hrm__worst_first(hrm__ctx *c, hrm__wf *w, hrm_real acc[HRM__NY])
{
    int cost = w->pool ? 4 : 2 * c->gk->n, roundoff = 0, k, ch;
    for (;;) {
        hrm__iv par;
        if (c->status != HRM_OK) return 0;
        if (hrm__wf_sum(c, w, acc, &k)) return 0;
        if (HRM_FABS(hrm__wf_at(w, k)->b - hrm__wf_at(w, k)->a) / (w->pool ? 8 : 2) < c->h_min ||
            (!w->pool && !hrm__gk_resolved(c, hrm__wf_at(w, k)->a, hrm__wf_at(w, k)->b))) {
            hrm__warn(c, hrm__h_min_status(c)); /* the worst interval is at h_min */
            return 0;
        }
        if (w->n == w->cap) return 1;
        if (hrm__spent(c) + cost > c->max_evals) {
            hrm__warn(c, HRM_WARN_MAX_EVALS);
            return 0;
        }
        par = *hrm__wf_at(w, k);
        hrm__wf_split(c, w, k);
        c->stats.steps++;
        c->stats.rejected++;
        if (c->jump_found) return 0; /* solved again with it as a breakpoint */
        /* Round-off (QUADPACK qag): the halves reproduce the parent's value
           while their error does not drop. */
        for (ch = 0; ch < HRM__CH; ++ch) {
            const hrm__iv *l = hrm__wf_at(w, k), *r = hrm__wf_at(w, k + 1);
            hrm_real f = c->closed ? 1 : HRM_EXP(-l->V[ch]); /* r is relative to its left end */
            hrm_real sum = l->V[HRM__CH + ch] + f * r->V[HRM__CH + ch];
            hrm_real esum = l->D[HRM__CH + ch] + f * r->D[HRM__CH + ch];
            /* (not where nothing is seen yet: sum 0, the estimate what
               lies before the first node, which halving reaches in
               time: sigma_t T = 1e10 took 25 halvings, stopped at 10
               with L = 0) */
            if (HRM_FABS(par.V[HRM__CH + ch] - sum) <= HRM__R(1e-5) * HRM_FABS(sum) &&
                esum >= HRM__R(0.99) * par.D[HRM__CH + ch] && esum > 0 && sum != 0) {
                roundoff++;
                break;
            }
        }
        if (roundoff >= 10) {
            hrm_real dummy[HRM__NY];
            hrm__wf_sum(c, w, dummy, &k);
            hrm__warn(c, HRM_WARN_ROUNDOFF);
            return 0;
        }
    }
}

/* After a worst-first phase that filled its storage: the scale of the
   total found, and the sums restarted for a left-to-right finish. */
static HRM_DEVICE void hrm__finish_scale(hrm__ctx *c, const hrm_real *tot, hrm_real acc[HRM__NY])
{
    int i;
    if (!c->scale_fixed)
        for (i = 0; i < HRM__NY; ++i) c->scale[i] = HRM_FABS(tot[i]) / 2;
    hrm__fill(acc, HRM__NY, 0);
    hrm__fill(c->err_acc, HRM__CH, 0);
}

/* Gauss-Kronrod, global mode: worst first from n0 intervals while they fit
   in HRM_GK_INTERVALS, then each is finished left to right. */
static HRM_DEVICE HRM__CALL void hrm__gk_global(hrm__ctx *c, int n0, hrm_real acc[HRM__NY])
{
    hrm__gki *iv = c->gks->iv;
    hrm__wf w;
    hrm_real span = c->pb - c->pa, S[2][HRM__CH], tot[HRM__NY];
    int i, has[2];

    w.iv = (unsigned char *)(void *)iv;
    w.stride = sizeof *iv;
    w.cap = HRM_GK_INTERVALS;
    w.n = n0 < HRM_GK_INTERVALS ? n0 : HRM_GK_INTERVALS;
    w.pool = 0;
    w.np = w.end = 0;
    hrm__gk_ends(c, S, has);
    for (i = 0; i < w.n; ++i) {
        iv[i].h.a = c->pa + span * ((hrm_real)i / (hrm_real)w.n);
        iv[i].h.b = i + 1 == w.n ? c->pb : c->pa + span * ((hrm_real)(i + 1) / (hrm_real)w.n);
        iv[i].io.ha = i == 0;
        iv[i].io.hb = i + 1 == w.n && has[1];
        iv[i].io.hc = 0;
        memcpy(iv[i].io.Sa, S[0], sizeof S[0]);
        memcpy(iv[i].io.Sb, S[1], sizeof S[1]);
        hrm__wf_rule(c, &w, &iv[i].h, 0);
        c->stats.steps++;
    }
    if (!hrm__worst_first(c, &w, tot)) {
        memcpy(acc, tot, sizeof tot);
        return;
    }
    /* storage full: each interval is finished left to right, at the
       scale of the total found */
    hrm__finish_scale(c, tot, acc);
    for (i = 0; i < w.n && c->status == HRM_OK; ++i)
        hrm__gk_local_one(c, iv[i].h.a, iv[i].h.b, iv[i].h.V, iv[i].h.E, iv[i].io.ha ? iv[i].io.Sa : 0,
                          iv[i].io.hb ? iv[i].io.Sb : 0, iv[i].io.Sm, acc);
}


/* Nested Simpson: worst first from the initial panels while the intervals
   fit in HRM_NS_INTERVALS, then each interval whose estimate exceeds its
   share of the tolerance (hrm__ratio, at the scale of the total found) is
   finished left to right from its two halves. */
static HRM_DEVICE HRM__CALL void hrm__nested_simpson(hrm__ctx *c, int panels, hrm_real acc[HRM__NY])
{
    hrm__nsi *iv = c->ns->iv;
    hrm__pt *pool = c->ns->pool;
    hrm__wf w;
    hrm_real span = c->pb - c->pa, tot[HRM__NY];
    int k, i;

    if (panels > HRM_NS_PANELS) panels = HRM_NS_PANELS;
    w.iv = (unsigned char *)(void *)iv;
    w.stride = sizeof *iv;
    w.cap = HRM_NS_INTERVALS;
    w.n = panels;
    w.pool = pool;
    w.np = 4 * panels + 1;
    w.end = 4 * panels;
    for (k = 0; k <= 4 * panels; ++k)
        hrm__eval(c, k == 4 * panels ? c->pb
                     : c->pa + span * ((hrm_real)k / (hrm_real)(4 * panels)), &pool[k]);
    for (k = 0; k < panels; ++k) {
        iv[k].h.a = pool[4 * k].p;
        iv[k].h.b = pool[4 * k + 4].p;
        for (i = 0; i < 4; ++i) iv[k].s[i] = 4 * k + i;
        hrm__wf_rule(c, &w, &iv[k].h, 4 * k + 4);
        c->stats.steps++;
    }
    if (!hrm__worst_first(c, &w, tot)) {
        memcpy(acc, tot, sizeof tot);
        return;
    }
    /* storage full: each interval whose estimate exceeds its share is
       finished left to right from its halves */
    hrm__finish_scale(c, tot, acc);
    for (k = 0; k < w.n && c->status == HRM_OK; ++k) {
        const hrm__nsi *v = &iv[k];
        const hrm__pt *P = pool;
        int b = k + 1 < w.n ? iv[k + 1].s[0] : w.end;
        hrm_real V[HRM__NY], E[HRM__NY], y1[HRM__NY], M[HRM__CH];
        hrm__ns_five(c, &P[v->s[0]], &P[v->s[1]], &P[v->s[2]], &P[v->s[3]], &P[b], acc, V, E, M, NULL);
        for (i = 0; i < HRM__NY; ++i) {
            y1[i] = acc[i] + V[i];
            E[i] /= 5;
        }
        hrm__with_miss(E, M);
        if (hrm__ratio(c, HRM_CONTROL_PI, v->h.a, v->h.b, acc, y1, E) <= 1) {
            memcpy(acc, y1, sizeof y1);
            hrm__accepted(c, E);
        } else {
            c->stats.rejected++;
            hrm__ns_local(c, &P[v->s[0]], &P[v->s[1]], &P[v->s[2]], acc);
            hrm__ns_local(c, &P[v->s[2]], &P[v->s[3]], &P[b], acc);
        }
    }
}


/* ---------------------------------------------------------------------- */
/* Dispatcher and public functions                                         */
/* ---------------------------------------------------------------------- */

HRM__DEF HRM_DEVICE const char *hrm_status_string(hrm_status status)
{
    switch (status) {
#define HRM__STATUS_CASE(name, value, text) case name: return text;
        HRM__STATUS_LIST(HRM__STATUS_CASE)
#undef HRM__STATUS_CASE
    default: return "unknown status";
    }
}

HRM__DEF HRM_DEVICE const char *hrm_method_name(hrm_method method)
{
    if ((int)method < 0 || (int)method >= (int)HRM_METHOD_COUNT) return "?";
    return hrm__methods[method].name;
}

HRM__DEF HRM_DEVICE int hrm_version(void)
{
    return HRM_VERSION_MAJOR * 10000 + HRM_VERSION_MINOR * 100 + HRM_VERSION_PATCH;
}

HRM__DEF HRM_DEVICE hrm_options hrm_default_options(hrm_method method)
{
    hrm_options o;
    /* method 0 stays 0 (hrm_solve: nested Simpson, whose defaults these
       are; hrm_transmittance: the shadow-ray estimator) */
    hrm_method m = method == HRM_METHOD_DEFAULT ? HRM_NESTED_SIMPSON : method;
    memset(&o, 0, sizeof o);
    o.method = method;
    if ((int)m > 0 && (int)m < (int)HRM_METHOD_COUNT)
        o.steps = hrm__methods[m].steps;
    o.form = HRM_FORM_OPTICAL_DEPTH;
    o.rtol = HRM__R(1e-3);
    o.max_evals = 100000;
    o.control = HRM_CONTROL_PI;
    o.gk_mode = HRM_GK_GLOBAL;
    /* the analytic march takes sigma_t at its samples, as renderers do;
       the other fixed-step methods are resolved with the warp (coupled
       without one: hrm__resolve), the adaptive ones decoupled */
    if ((int)m > 0 && (int)m < (int)HRM_METHOD_COUNT) /* (an unknown one: hrm__resolve) */
        o.tau_mode = hrm__methods[m].driver == HRM__DRV_MARCH ? HRM_TAU_COUPLED
                   : hrm__methods[m].family <= HRM__FIXED_IVP ? HRM_TAU_DEFAULT
                   : HRM_TAU_DECOUPLED;
    else
        o.tau_mode = HRM_TAU_DECOUPLED;
    return o;
}

/* A panel of the shadow-ray estimator (hrm__shadow_run). */
typedef struct hrm__panel {
    hrm_real a, h;
    hrm_real f[5][HRM__CH]; /* sigma_t at a + h (0, 1/4, 1/2, 3/4, 1) */
    hrm_real e[HRM__CH];    /* S2 - S1, at least the fourth difference
                               its samples predict (hrm__fourth_pred) */
    hrm_real worst;         /* the largest |e| (NaN: infinite) */
} hrm__panel;

/* The storage a solve may need, one bit each (hrm__needs, hrm__stage). */
#define HRM__NEED_LAYER 1u /* the transmittance layer (20 KiB at 3 channels) */
#define HRM__NEED_MEMO 2u  /* the adaptive methods' remembered abscissae */
#define HRM__NEED_EFIT 4u  /* the exponential fits' tables */
#define HRM__NEED_NS 8u    /* nested Simpson's storage */
#define HRM__NEED_GK 16u   /* global Gauss-Kronrod's intervals */
#define HRM__NEED_FINISH 32u /* nested Simpson's finish stack: a workspace's
                              only (without one, the finish's own frame) */
#define HRM__NEED_CTX 64u  /* the solve's context: a workspace's only (without
                              one, or in a GPU kernel, where memory no two
                              threads share is slower than their stacks,
                              the solve's own frame) */
#define HRM__NEED_PIECES 128u /* the tables of the pieces between
                                breakpoints: a workspace's only (without
                                one, hrm__solve_broken's own frame) */
#define HRM__NEED_SHADOW 256u /* the shadow-ray estimator's panels: a
                                workspace's only (without one, or in a GPU
                                kernel, its own frame, hrm__shadow_march) */
#define HRM__NEEDS 9
/* (in a GPU kernel the context and the estimator's panels stay on the
   thread's stack, for the reason above) */
#ifdef __CUDA_ARCH__
#define HRM__CTX_NEED 0u
#define HRM__SHADOW_NEED 0u
#else
#define HRM__CTX_NEED HRM__NEED_CTX
#define HRM__SHADOW_NEED HRM__NEED_SHADOW
#endif
/* what the shadow-ray estimator holds (hrm__needs) */
#define HRM__ESTIMATOR_NEED (HRM__CTX_NEED | HRM__NEED_PIECES | HRM__SHADOW_NEED)

/* The bytes of need bit k (1u << k), rounded up to 16 (the alignment of
   the caller's workspace, which holds them in this order). */
static HRM_DEVICE size_t hrm__need_bytes(int k)
{
    static const size_t bytes[HRM__NEEDS] = {HRM__TAU_HEAD + HRM__TAU_CACHE_BYTES +
                                                 sizeof(hrm__tpanel) * HRM_TAU_PANELS,
                                             sizeof(hrm__memo_tab),
                                             HRM__EFIT_BYTES, sizeof(hrm__ns_store),
                                             sizeof(hrm__gk_store), sizeof(hrm__ns_half) * (HRM_MAX_DEPTH + 1),
                                             sizeof(hrm__ctx), sizeof(hrm__piece_tab),
                                             sizeof(hrm__panel) * HRM_SHADOW_PANELS};
    return (bytes[k] + 15) / 16 * 16;
}

/* What a solve with resolved options o may need, whatever its medium
   (the layer: sigma callbacks may need it with any method); the storage
   hrm__needs asks for at the solve is a part of it. */
static HRM_DEVICE unsigned hrm__may_need(const hrm_options *o)
{
    int d = hrm__driver(o);
    return HRM__NEED_LAYER | HRM__CTX_NEED | HRM__NEED_PIECES | (hrm__is_adaptive(o->method) ? HRM__NEED_MEMO : 0u) |
           (o->exponential ? HRM__NEED_EFIT : 0u) | (d == HRM__DRV_NS ? HRM__NEED_NS | HRM__NEED_FINISH : 0u) |
           (d == HRM__DRV_GK ? HRM__NEED_GK : 0u);
}

/* The bytes of the needs in mask, in a workspace. */
static HRM_DEVICE size_t hrm__mask_bytes(unsigned mask)
{
    size_t n = 0;
    int k;
    for (k = 0; k < HRM__NEEDS; ++k)
        if (mask & (1u << k)) n += hrm__need_bytes(k);
    return n;
}

/* What hrm_workspace_size says for resolved options o: with nested
   Simpson (what HRM_METHOD_DEFAULT resolves to), the larger of that and
   what hrm_transmittance's estimator takes (HRM__ESTIMATOR_NEED). */
static HRM_DEVICE size_t hrm__ws_bytes(const hrm_options *o)
{
    size_t n = hrm__mask_bytes(hrm__may_need(o));
    size_t est = hrm__mask_bytes(HRM__ESTIMATOR_NEED);
    return o->method == HRM_NESTED_SIMPSON && est > n ? est : n;
}

/* Nested Simpson's and Gauss-Kronrod's first panels or intervals on a
   piece of the ray: options.steps shared by length in the integration
   variable (share, of [pa, pb]), at least 2 panels or 1 interval (or
   steps, where fewer): a ray cut by breakpoints starts no finer than
   its pieces ask for. */
static HRM_DEVICE int hrm__panels_least(const hrm_options *o)
{
    int lo = hrm__methods[o->method].driver == HRM__DRV_NS ? 2 : 1;
    return o->steps < lo ? o->steps : lo;
}

/* What a piece of the ray costs the method at least: its first step, or
   its first n panels or intervals. */
static HRM_DEVICE long hrm__piece_cost(const hrm_options *o, long n)
{
    const hrm__method_info *mi = &hrm__methods[o->method];
    return mi->family == HRM__PAIR ? hrm__stage_cost(mi->tb) + 1L
         : mi->driver == HRM__DRV_NS ? 4L * n + 1
         : mi->driver == HRM__DRV_GK ? (o->gk_rule == HRM_GK_K7 ? 7L : 15L) * n + 2
         : 0L;
}

/* Resolve zeros to defaults; validate. */
static HRM_DEVICE HRM__CALL hrm_status hrm__resolve(const hrm_options *in, hrm_options *o, int tau_in_t)
{
    hrm_options d = hrm_default_options(in && in->method != HRM_METHOD_DEFAULT ? in->method : HRM_NESTED_SIMPSON);
    const hrm__method_info *mi;
    int estimator = tau_in_t && !(in && in->method != HRM_METHOD_DEFAULT); /* (its budget: its own) */
    if (!in) {
        *o = d;
        in = &d;
    }
    *o = *in;
    if ((int)o->method < 0 || (int)o->method >= (int)HRM_METHOD_COUNT) return HRM_ERR_BAD_METHOD;
    if (o->method == HRM_METHOD_DEFAULT) o->method = d.method;
    mi = &hrm__methods[o->method];
    if (o->steps < 0) return HRM_ERR_BAD_STEPS;
    if (o->steps == 0) o->steps = d.steps;
    /* initial panels and intervals of the adaptive quadratures */
    if (mi->driver == HRM__DRV_NS && o->steps > HRM_NS_PANELS) o->steps = HRM_NS_PANELS;
    if (mi->driver == HRM__DRV_GK && o->steps > HRM_GK_INITIAL) o->steps = HRM_GK_INITIAL;
    if ((int)o->form < 0 || (int)o->form > (int)HRM_FORM_RTE) return HRM_ERR_BAD_OPTION;
    if (o->form == HRM_FORM_DEFAULT) o->form = HRM_FORM_OPTICAL_DEPTH;
    if ((int)o->control < 0 || (int)o->control > (int)HRM_CONTROL_GONTERMAN) return HRM_ERR_BAD_OPTION;
    if (o->control == HRM_CONTROL_DEFAULT) o->control = d.control;
    if ((int)o->gk_mode < 0 || (int)o->gk_mode > (int)HRM_GK_LOCAL) return HRM_ERR_BAD_OPTION;
    if (o->gk_mode == HRM_GK_DEFAULT) o->gk_mode = d.gk_mode;
    if ((int)o->gk_rule < 0 || (int)o->gk_rule > (int)HRM_GK_K7) return HRM_ERR_BAD_OPTION;
    if (o->find_jumps < -1 || o->find_jumps > 1) return HRM_ERR_BAD_OPTION;
    /* the fits need tau at every node (a closed form or the layer) and a
       rule that is a quadrature: not the RTE form, not coupled tau */
    if (o->exponential < 0 || o->exponential > 2) return HRM_ERR_BAD_OPTION;
    if (o->exponential &&
        (!hrm__methods[o->method].fit || o->form == HRM_FORM_RTE || o->tau_mode == HRM_TAU_COUPLED))
        return HRM_ERR_BAD_OPTION;
    if (o->gk_rule == HRM_GK_RULE_DEFAULT) o->gk_rule = HRM_GK_K15;
    if ((int)o->tau_mode < 0 || (int)o->tau_mode > (int)HRM_TAU_STREAM) return HRM_ERR_BAD_OPTION;
    /* the stream needs nodes in increasing t, with tau at each: a
       fixed-step rule's (the analytic march takes its own), no fit */
    if (o->tau_mode == HRM_TAU_STREAM && (!hrm__methods[o->method].stream || o->exponential))
        return HRM_ERR_BAD_OPTION;
    if (o->tau_mode == HRM_TAU_DEFAULT) o->tau_mode = d.tau_mode;
    /* fixed-step methods: tau from their own nodes (what N says, in sigma
       too) without a warp or a fit, and where tau alone is integrated in
       t (tau_in_t: hrm_transmittance on a finite ray, which ignores the
       warp). Under a warp, which spaces the nodes for a light, not for the
       medium: the stream for the rules of order 2 at most, whose own error
       its 16 extra samples stay below; the layer for the others (make
       render's smoke, Simpson N = 32: RMSE 9e-3 with the stream, 1e-3
       with the layer, for 103 and 478 lookups a pixel) and with a fit */
    if (o->tau_mode == HRM_TAU_DEFAULT)
        o->tau_mode = (o->warp.kind == HRM_WARP_NONE || tau_in_t) && !o->exponential ? HRM_TAU_COUPLED
                    : !o->exponential && hrm__methods[o->method].stream == 2
                        ? HRM_TAU_STREAM
                        : HRM_TAU_DECOUPLED;
    if (!(HRM__FINITE(o->rtol) && o->rtol >= 0 && HRM__FINITE(o->atol) && o->atol >= 0 &&
          HRM__FINITE(o->h_min) && o->h_min >= 0 && HRM__FINITE(o->h_max) && o->h_max >= 0 &&
          HRM__FINITE(o->h0) && o->h0 >= 0 && o->max_evals >= 0 &&
          HRM__FINITE(o->tau_tol) && o->tau_tol >= 0 && HRM__FINITE(o->tr_tol) && o->tr_tol >= 0 &&
          o->cutoff >= 0 && o->cutoff <= 1))
        return HRM_ERR_BAD_OPTION;
    if (o->tr_tol == 0) o->tr_tol = HRM__R(1e-3);
    if (o->tr_tol < 64 * HRM__EPS) o->tr_tol = 64 * HRM__EPS;
    if (o->h_max > 0 && o->h_min > o->h_max) return HRM_ERR_BAD_OPTION;
    if (o->rtol == 0) o->rtol = d.rtol;
    if (o->max_evals == 0) o->max_evals = d.max_evals;
    /* tau's share of the error: an eighth of rtol (what the source's
       estimate does not see stays below it: L off by at most rtol/8
       (1 + K/64) from tau, TRANSMITTANCE), or for a fixed
       step count 1/100 of N^-order, below the rule's own error at every N
       on a unit-scale problem (its cost grows only like log(1/tau_tol)) */
    if (o->tau_tol == 0)
        o->tau_tol = hrm__is_adaptive(o->method)
                         ? o->rtol / 8
                         : HRM__R(0.01 * pow((double)o->steps, -(mi->driver == HRM__DRV_RECT && o->jitter
                                                                  ? 1 : mi->order)));
    /* below a few dozen epsilons round-off in tau dominates any estimate */
    if (o->tau_tol < 64 * HRM__EPS) o->tau_tol = 64 * HRM__EPS;
    /* A budget below one step of the method on every piece could not be
       honoured (a breakpoint count out of range is the breakpoints' error). */
    if (o->nbreaks < 0 || o->nbreaks > HRM_MAX_BREAKS) return HRM_ERR_BAD_BREAKS;
    if (!estimator && o->max_evals < (o->nbreaks > 0 ? hrm__piece_cost(o, hrm__panels_least(o)) * ((long)o->nbreaks + 1)
                                                     : hrm__piece_cost(o, o->steps)))
        return HRM_ERR_BAD_OPTION;
    /* the workspace: with its size, at least what the solve takes, on 16 */
    if (o->workspace ? o->workspace_size < hrm__ws_bytes(o) || (uintptr_t)o->workspace % 16 != 0
                     : o->workspace_size != 0)
        return HRM_ERR_BAD_OPTION;
    return HRM_OK;
}

/* Every check of the manual's BAD INPUT table that needs no callback, in
   its order: the interval, the options (resolved into o), the
   breakpoints, the warp's parameters, the medium (flags, sigma given with
   the other coefficients, feature; the constants, then their range). */
static HRM_DEVICE HRM__CALL hrm_status hrm__validate(const hrm_medium *m, hrm_real t0, hrm_real t1, const hrm_options *in,
                                int tr_only, hrm_options *o)
{
    hrm_real range = hrm__range(t1 - t0);
    hrm_status st;
    int i;
    /* t1 = +inf is valid under a warp that maps it to a finite end. */
    if (!HRM__FINITE(t0) || !(t1 >= t0) || (!HRM__FINITE(t1) && t0 == t1)) return HRM_ERR_BAD_INTERVAL;
    if (HRM__FINITE(t1) && !HRM__FINITE(t1 - t0)) return HRM_ERR_RANGE;
    st = hrm__resolve(in, o, tr_only && HRM__FINITE(t1));
    if (st != HRM_OK) return st;
    if (o->nbreaks > 0 && !o->breaks) return HRM_ERR_BAD_BREAKS;
    for (i = 0; i < o->nbreaks; ++i) {
        hrm_real b = o->breaks[i];
        if (!HRM__FINITE(b) || b < t0 || b > t1 || (i > 0 && !(b > o->breaks[i - 1])))
            return HRM_ERR_BAD_BREAKS;
    }
    /* the warp's parameters, even where an empty ray or a transmittance
       alone will not use them */
    if (hrm__warp_valid(&o->warp) != HRM_OK) return HRM_ERR_BAD_WARP;
    if (m->flags & ~(HRM_MEDIUM_HOMOGENEOUS | HRM_EMISSION_PER_LENGTH)) return HRM_ERR_BAD_MEDIUM;
    if (m->sigma && (m->sigma_a || m->sigma_s || m->sigma_t)) return HRM_ERR_BAD_MEDIUM;
    if (!(HRM__FINITE(m->feature) && m->feature >= 0)) return HRM_ERR_BAD_MEDIUM;
    if (!(m->flags & HRM_MEDIUM_HOMOGENEOUS)) return HRM_OK;
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real a = m->const_sigma_a[i], b = m->const_sigma_s[i];
        if (!(HRM__FINITE(a) && HRM__FINITE(b) && a >= 0 && b >= 0 && HRM__FINITE(a + b)))
            return HRM_ERR_BAD_MEDIUM;
    }
    for (i = 0; i < HRM__CH; ++i)
        if (m->const_sigma_a[i] + m->const_sigma_s[i] > range) return HRM_ERR_RANGE;
    return HRM_OK;
}

/* The source terms a solve integrates: Le where sigma_a (or emission per
   length) can weigh it, Li where sigma_s can; neither for Tr alone. */
static HRM_DEVICE void hrm__sources(const hrm_medium *m, int tr_only, int *use_le, int *use_li)
{
    int homog = (m->flags & HRM_MEDIUM_HOMOGENEOUS) != 0;
    *use_le = !tr_only && m->Le && ((m->flags & HRM_EMISSION_PER_LENGTH) || homog || m->sigma_a || m->sigma);
    *use_li = !tr_only && m->Li && (homog || m->sigma_s || m->sigma);
}

/* Where tau comes from: a closed form where there is one (the RTE form
   integrates Tr itself, so it takes sigma_t samples even then), else the
   transmittance layer, the stream or the rules' own tau, as
   options.tau_mode (resolved) says; tau alone (no source) from the layer,
   which needs no nodes. */
static HRM_DEVICE hrm__tau_src hrm__tau_source(const hrm_medium *m, const hrm_options *o, int sources)
{
    return (m->flags & HRM_MEDIUM_HOMOGENEOUS) ? HRM__TAU_HOMOG
         : o->form == HRM_FORM_RTE && hrm__methods[o->method].rte ? HRM__TAU_STATE
         : m->transmittance ? HRM__TAU_TRCB
         : o->tau_mode == HRM_TAU_DECOUPLED ? HRM__TAU_LAYER
         : o->tau_mode == HRM_TAU_STREAM ? (sources ? HRM__TAU_STREAM : HRM__TAU_LAYER)
         : HRM__TAU_RULES;
}

/* Whether Tr is known at every node before the rule runs. */
static HRM_DEVICE int hrm__tau_closed(hrm__tau_src src)
{
    return src == HRM__TAU_HOMOG || src == HRM__TAU_TRCB || src == HRM__TAU_LAYER || src == HRM__TAU_STREAM;
}

/* The context of one solve: medium, flags, tolerances, the warp and the
   step bounds; layer, memo, ef: the storage hrm__needs asked for (else
   NULL). Returns an error, or HRM_OK with c ready to dispatch. */
static HRM_DEVICE HRM__CALL hrm_status hrm__setup(hrm__ctx *c, hrm__tau *layer, hrm__memo_tab *memo, hrm__efit *ef,
                             const hrm_medium *m, hrm_real t0, hrm_real t1, const hrm_options *o,
                             int tr_only)
{
    const hrm__method_info *mi = &hrm__methods[o->method];
    hrm_status st;
    hrm_real P, big;
    int i, t_fine;

    c->m = m;
    c->t0 = t0;
    c->t1 = t1;
    c->T = t1 - t0;
    c->range = hrm__range(c->T);
    c->rng = o->seed;
    c->o_lo = -HRM__R(HUGE_VAL);
    c->o_hi = HRM__R(HUGE_VAL);
    c->homog = (m->flags & HRM_MEDIUM_HOMOGENEOUS) != 0;
    c->per_length = (m->flags & HRM_EMISSION_PER_LENGTH) != 0;
    c->rte = o->form == HRM_FORM_RTE && mi->rte;
    c->use_memo = hrm__is_adaptive(o->method) && memo;
    c->tr_at_nodes = mi->driver != HRM__DRV_MARCH;
    c->memo = memo ? memo->e : NULL;
    c->memo_s = memo ? memo->s : NULL;
    c->memo_bin = memo ? memo->bin : NULL;
    c->memo_sbin = memo ? memo->sbin : NULL;
    if (memo) memset(memo->bin, 0, sizeof memo->bin);
    /* Tolerances: below 100 epsilons round-off dominates any estimate. */
    c->rtol = o->rtol;
    if (c->rtol < 100 * HRM__EPS && hrm__is_adaptive(o->method)) {
        c->rtol = 100 * HRM__EPS;
        c->warning = HRM_WARN_RTOL_CLIPPED;
    }
    c->atol = o->atol;
    c->max_evals = o->max_evals;
    /* The medium scan needs t to resolve the ray to 4096 ulps at least
       (far from the origin, t is too coarse to locate anything within
       it); the source's jump search, to 2^30 or a ray longer than its
       distance from the origin: there a source sampled at rounded t is
       rough at a point light's peak (t0 = 1e8, a light 1e-3 from the ray:
       1e-5 of itself), which the search would take for jumps and solve
       again for nothing. */
    t_fine = HRM_FABS(t0) * HRM__EPS <= c->T / 4096;
    c->piece_cost = hrm__piece_cost(o, hrm__panels_least(o));
    c->split_cost = mi->driver == HRM__DRV_NS ? 4 : o->gk_rule == HRM_GK_K7 ? 14 : 30;
    c->find_jumps = o->find_jumps >= 0 && !c->rte &&
                    (HRM_FABS(t0) <= c->T || HRM_FABS(t0) * HRM__EPS <= c->T / HRM__R(1073741824.0)) &&
                    (hrm__driver(o) == HRM__DRV_NS || hrm__driver(o) == HRM__DRV_GK);
    /* the medium scan: adaptive methods by default, fixed-step ones when
       asked (find_jumps = 1; their cost is otherwise N's alone) */
    c->scan = (o->find_jumps == 1 || (o->find_jumps == 0 && hrm__is_adaptive(o->method))) && !c->homog && !m->transmittance &&
              (m->sigma_a || m->sigma_s || m->sigma_t || m->sigma) && t_fine;
    c->gk = o->gk_rule == HRM_GK_K7 ? &hrm__k7 : &hrm__k15;
    c->rough_left = HRM__JUMP;
    if (c->homog) {
        for (i = 0; i < HRM__CH; ++i) {
            c->sa[i] = m->const_sigma_a[i];
            c->ss[i] = m->const_sigma_s[i];
            c->st[i] = c->sa[i] + c->ss[i]; /* (checked: hrm__validate) */
        }
    }
    hrm__sources(m, tr_only, &c->use_le, &c->use_li);
    c->src = hrm__tau_source(m, o, c->use_le || c->use_li);
    c->decoupled = c->src == HRM__TAU_LAYER;
    c->closed = hrm__tau_closed(c->src);
    /* (against a Tr callback only where sigma_t at a node costs no call
       more than the source's: sigma as one call, or sigma_a and sigma_s
       both wanted) */
    c->mcheck = (c->decoupled || (c->src == HRM__TAU_TRCB &&
                                  (m->sigma || (!m->sigma_t && m->sigma_a && m->sigma_s && c->use_le &&
                                                !c->per_length && c->use_li)))) &&
                hrm__is_adaptive(o->method);
    c->coupled = c->src == HRM__TAU_RULES;
    c->need_st = c->coupled || c->rte || c->src == HRM__TAU_STREAM;
    c->expo = c->closed ? o->exponential : 0;
    c->tau_from_tr = c->src == HRM__TAU_TRCB;
    c->ef = ef;
    if (c->expo) hrm__efit_setup(c, o);
    c->tau = layer;
    if (layer && !c->keep_layer) hrm__tau_init(layer, HRM__FINITE(c->T) ? c->T : HRM__R(1e30), o->tau_tol);
    if (t0 == t1) return HRM_OK;

    if (tr_only && HRM__FINITE(c->T)) {
        /* tau alone is integrated in t: a warp only says where an
           infinite ray ends (its parameters checked all the same) */
        hrm_warp none;
        memset(&none, 0, sizeof none);
        st = hrm__setup_warp(c, &none);
    } else {
        st = hrm__setup_warp(c, &o->warp);
        if (st == HRM_ERR_BAD_INTERVAL && o->warp.kind == HRM_WARP_EQUIANGULAR && o->warp.D > 0) {
            hrm_warp dw; /* the equiangular range unresolved (above) */
            memset(&dw, 0, sizeof dw);
            dw.kind = HRM_WARP_DISTANCE;
            st = hrm__setup_warp(c, &dw);
            hrm__warn(c, HRM_WARN_ROUNDOFF);
        }
    }
    if (st == HRM_OK) st = c->status;
    if (st != HRM_OK) return st;
    c->off_end = c->s_end - c->t0;
    if (!(c->off_end > 0) && !HRM__FINITE(c->T)) {
        /* a warp's whole reach below one ulp of t0 (sigma 1e5 at t0 1e13):
           the offsets still resolve it where t does not; the callbacks
           see t0 alone (an empty layer had made L NaN with HRM_OK) */
        hrm_real J;
        hrm__map(c, c->pb, &c->off_end, &J);
        hrm__warn(c, HRM_WARN_ROUNDOFF);
    }
    if (layer && c->keep_layer) hrm__tau_cut(layer, c->off_end);
    else if (layer) hrm__tau_init(layer, c->off_end, o->tau_tol);
    if (layer && c->warp == HRM_WARP_EQUIANGULAR && c->w_delta - c->t0 > 0 && c->w_delta - c->t0 < c->off_end)
        layer->foot = c->w_delta - c->t0;
    /* the breakpoints strictly inside what is integrated, as offsets */
    for (i = 0; i < o->nbreaks; ++i) {
        hrm_real off = o->breaks[i] - t0;
        if (off > 0 && off < c->off_end && (c->nbrk == 0 || off > c->brk_off[c->nbrk - 1]))
            c->brk_off[c->nbrk++] = off;
    }
    if (c->src == HRM__TAU_STREAM) {
        /* extra points: HRM__STREAM_EXTRA, or what 2N + 8 leaves after
           a method's distinct abscissae and the ray's ends where that is
           fewer (N + 2 for the rectangle rule, Monte Carlo and Euler,
           N + 4 for Adams-Bashforth); 16 for Simpson and RK4 (2N + 1
           nodes, ends included: 2N + 17 in all). Where a warp leaves the
           nodes sparse (the ray's ends, far from the light) 16 bring tau
           level with the rule's own error; 7 did not for the
           fourth-order rules (bench/results/summary.md's smoke, Simpson
           at N = 128: L off by 2.7e-4 with 7, 3.3e-6 with 16, 1.3e-5
           with the exact Tr; the rectangle rule at N = 128 on the test
           file's smoke: 4.6e-5 with 16, 2.2e-4 with 7, 8.5e-5 with Tr
           exact) */
        long N = o->steps, d = o->method == HRM_RECTANGLE || o->method == HRM_MONTE_CARLO ? N + 2
                             : o->method == HRM_EULER ? N + 2
                             : o->method == HRM_ADAMS_BASHFORTH && N >= 4 && !c->nbrk ? N + 4
                             : 2 * N + 1;
        int fourth = o->method == HRM_SIMPSON || o->method == HRM_RK4;
        long room = 2 * N + 8 - d;
        c->sm.extra = fourth || room > HRM__STREAM_EXTRA ? HRM__STREAM_EXTRA : room > 0 ? room : 0;
        hrm__stream_level(c, fourth ? 2 * N : N);
    }

    /* step bounds, in the parameter */
    P = c->pb - c->pa;
    c->h_max = o->h_max > 0 && o->h_max < P ? o->h_max : P;
    big = HRM_FABS(c->pa) > HRM_FABS(c->pb) ? HRM_FABS(c->pa) : HRM_FABS(c->pb);
    big = big > P ? big : P;
    c->h_min = o->h_min > 0 ? o->h_min
             : o->control == HRM_CONTROL_MUNOZ ? P / 1024 : 64 * HRM__EPS * big;
    /* Without a warp an abscissa is t0 + p, resolved to eps |t0|: a step
       below twice that could not place a node apart from its neighbours
       (its evaluations would repeat earlier ones), so none is taken; one
       refused there is taken with HRM_WARN_ROUNDOFF. */
    c->h_res = c->warp == HRM_WARP_NONE ? 2 * HRM__EPS * HRM_FABS(c->t0) : 0;
    if (c->h_min < c->h_res) c->h_min = c->h_res;
    if (c->h_min > c->h_max) c->h_min = c->h_max;
    return HRM_OK;
}

static HRM_DEVICE void hrm__adaptive_once(hrm__ctx *c, const hrm_options *o, hrm_real y[HRM__NY])
{
    const hrm__method_info *mi = &hrm__methods[o->method];
    hrm__fill(c->err_acc, HRM__CH, 0);
    c->rough_left = HRM__JUMP;
    switch (hrm__driver(o)) {
    case HRM__DRV_NS: hrm__nested_simpson(c, c->panels0, y); break;
    case HRM__DRV_GK_LOCAL: hrm__gk_local(c, c->panels0, y); break;
    case HRM__DRV_GK: hrm__gk_global(c, c->panels0, y); break;
    default: hrm__ivp_adaptive(c, mi->tb, o->control, o->h0, y);
    }
}

/* The adaptive methods, verified: the shares of the tolerance their steps
   accepted add up to at most atol + 2 rtol |L|, and rtol |L| more for
   the rough steps (TOLERANCES), if the scale they judged by was |L| / 2.
   A first estimate of the total that proved too large (a pilot sample on
   a light's peak) makes the accepted estimates add up to more: the
   method is run once more at the scale found, and if that still does not
   hold, HRM_WARN_TOLERANCE says so with the estimate in result.error.
   (Munoz's and Gonterman's controllers keep their own definitions.) */
static HRM_DEVICE HRM__CALL void hrm__adaptive(hrm__ctx *c, const hrm_options *o, hrm_real y[HRM__NY])
{
    const hrm__method_info *mi = &hrm__methods[o->method];
    int pass, n;
    if ((mi->family == HRM__PAIR && o->control != HRM_CONTROL_PI) || c->rte) {
        /* the RTE form amplifies local errors: no sum of them bounds L's */
        hrm__adaptive_once(c, o, y);
        return;
    }
    for (pass = 0; pass < 2; ++pass) {
        int held = 1, loose = 0;
        hrm__adaptive_once(c, o, y);
        if (c->status != HRM_OK || c->jump_found ||
            (c->warning != HRM_OK && c->warning != HRM_WARN_RTOL_CLIPPED))
            return; /* a warning already says the tolerance was missed */
        for (n = 0; n < HRM__CH; ++n) {
            int ok = c->err_acc[n] <= c->atol + 3 * c->rtol * HRM_FABS(y[HRM__CH + n]) +
                                          16 * HRM__EPS * HRM_FABS(y[HRM__CH + n]);
            held &= ok;
            loose |= !ok && c->scale[HRM__CH + n] > HRM_FABS(y[HRM__CH + n]);
        }
        if (held) return;
        /* a scale above |L| let more through: solved again at the scale
           found; otherwise steps accepted without meeting their share
           (at t's resolution on a ray far from the origin, rough steps
           past their share) missed it, and no second pass would do
           better (HRM_OK with an estimate 600 times the tolerance) */
        if (pass == 1 || !loose || c->stats.evals >= c->max_evals / 2) {
            hrm__warn(c, HRM_WARN_TOLERANCE);
            return;
        }
        for (n = 0; n < HRM__NY; ++n) c->scale[n] = HRM_FABS(y[n]) / 2;
        c->scale_fixed = 1;
    }
}

/* Run the method: y receives (tau, L), or (Tr, L) in the RTE form. */
static HRM_DEVICE void hrm__dispatch_one(hrm__ctx *c, const hrm_options *o, int N, hrm_real y[HRM__NY])
{
    const hrm__method_info *mi = &hrm__methods[o->method];
    hrm__fill(y, HRM__NY, 0);
    switch (mi->driver) {
    case HRM__DRV_SIMPSON: hrm__simpson(c, N, y + HRM__CH, y); break;
    case HRM__DRV_RECT:
        hrm__nodes(c, N, 0, o->jitter ? hrm__uniform(&c->rng) : HRM__R(0.5), y + HRM__CH, y);
        break;
    case HRM__DRV_MARCH:
        hrm__march(c, N, o->jitter ? hrm__uniform(&c->rng) : HRM__R(0.5), y + HRM__CH, y);
        break;
    case HRM__DRV_MC: hrm__nodes(c, N, o->stratified ? 1 : 2, 0, y + HRM__CH, y); break;
    case HRM__DRV_IVP:
    case HRM__DRV_AB4: hrm__ivp_fixed(c, mi->tb, mi->driver == HRM__DRV_AB4, N, y); break;
    default:
        /* fewer first panels where the budget's rest holds no more */
        while (N > hrm__panels_least(o) && hrm__piece_cost(o, N) > c->max_evals - c->stats.evals) --N;
        c->panels0 = N;
        hrm__adaptive(c, o, y);
    }
}

/* The parameter of an offset from t0: the warp's inverse. */
static HRM_DEVICE HRM__CALL hrm_real hrm__unmap(hrm__ctx *c, hrm_real off)
{
    hrm_real p;
    switch (c->warp) {
    case HRM_WARP_DISTANCE:
        p = -HRM_EXPM1(-c->w_sigma * off);
        break;
    case HRM_WARP_EQUIANGULAR:
        p = HRM_ATAN2(c->t0 + off - c->w_delta, c->w_D);
        break;
    case HRM_WARP_USER:
        p = c->status == HRM_OK ? c->uw->u_of_t(c->uw->user, c->t0 + off) : c->pa;
        break;
    default:
        p = off;
    }
    if (!HRM__FINITE(p)) {
        if (c->status == HRM_OK) c->status = HRM_ERR_CALLBACK_VALUE;
        p = c->pa;
    }
    return p < c->pa ? c->pa : p > c->pb ? c->pb : p;
}

/* Run the method: y receives (tau, L), or (Tr, L) in the RTE form. With
   breakpoints the ray is cut into pieces, each solved on its own (a
   fixed-step method's N shared among them in proportion to their length
   in the integration variable, at least one step each, by largest
   remainders; an adaptive method at rtol on each piece, which bounds the
   sum; Adams-Bashforth restarts with RK4 on each), and composed: L =
   sum of the pieces' L, each attenuated by Tr up to its start where its
   rule integrated tau from its own start (coupled tau, the RTE form). */
static HRM_DEVICE void hrm__solve_broken(hrm__ctx *c, const hrm_options *o, hrm_real y[HRM__NY]);

static HRM_DEVICE void hrm__solve_pieces(hrm__ctx *c, const hrm_options *o, hrm_real y[HRM__NY])
{
    if (c->src == HRM__TAU_STREAM) {
        c->sm.n = 0;
        c->sm.start = 0;
        c->sm.left = c->sm.extra;
        hrm__fill(c->sm.tau, HRM__CH, 0);
    }
    if (c->nbrk == 0) {
        c->scale_fixed = 0;
        hrm__fill(c->scale, HRM__NY, 0);
        hrm__dispatch_one(c, o, o->steps, y);
        return;
    }
    hrm__solve_broken(c, o, y);
}

/* A piece [a, b]'s share of N steps by its length in [pa, pb], in [0, N]
   (halves: no overflow on a ray across the whole range). */
static HRM_DEVICE hrm_real hrm__share(int steps, hrm_real a, hrm_real b, hrm_real pa, hrm_real pb)
{
    hrm_real r = (hrm_real)steps * (b / 2 - a / 2) / (pb / 2 - pa / 2);
    return !(r >= 0) ? 0 : r > (hrm_real)steps ? (hrm_real)steps : r;
}

/* The pieces between breakpoints, each solved on its own, with their
   tables in t (the caller's workspace, or hrm__solve_broken's frame). */
static HRM_DEVICE HRM__CALL HRM__NOINLINE void hrm__solve_broken_in(hrm__ctx *c, const hrm_options *o,
                                                                    hrm_real y[HRM__NY], hrm_real *P, int *N)
{
    const hrm__method_info *mi = &hrm__methods[o->method];
    hrm_real pa = c->pa, pb = c->pb;
    hrm_real yk[HRM__NY], err[HRM__CH], acc[HRM__CH];
    int n = c->nbrk + 1, k, i, fixed;
    long max_evals = c->max_evals;
    /* a piece's tolerance is of its own L: a piece that missed it (a step
       at h_min, or its estimates' sum) warns only where the pieces'
       estimates together miss the ray's (the PI control's sum; the RTE
       form's local errors bound nothing) */
    int judge = !c->rte && (mi->family != HRM__PAIR || o->control == HRM_CONTROL_PI);
    hrm_status missed = HRM_OK;

    P[0] = pa;
    P[n] = pb;
    for (k = 1; k < n; ++k) {
        /* within [the last end, pb], whatever the map gave */
        P[k] = hrm__unmap(c, c->brk_off[k - 1]);
        if (!(P[k] >= P[k - 1])) P[k] = P[k - 1];
        if (P[k] > pb) P[k] = pb;
    }
    fixed = mi->family == HRM__FIXED_QUAD || mi->family == HRM__FIXED_IVP;
    if (fixed) {
        /* N shared by length, at least 1 each, then one more to the
           largest remainders (recomputed: no table on the stack) */
        int left = o->steps;
        for (k = 0; k < n; ++k) {
            N[k] = (int)hrm__share(o->steps, P[k], P[k + 1], pa, pb);
            if (N[k] < 1) N[k] = 1;
            left -= N[k];
        }
        while (left > 0) {
            int best = 0;
            hrm_real most = 0;
            for (k = 0; k < n; ++k) {
                hrm_real r = hrm__share(o->steps, P[k], P[k + 1], pa, pb) - (hrm_real)N[k];
                if (k == 0 || r > most) {
                    best = k;
                    most = r;
                }
            }
            N[best]++;
            left--;
        }
    }
    hrm__fill(y, HRM__NY, 0);
    hrm__fill(err, HRM__CH, 0);
    hrm__fill(acc, HRM__CH, c->rte ? 1 : 0);
    for (k = 0; k < n && c->status == HRM_OK && !c->jump_found; ++k) {
        if (!(P[k + 1] > P[k])) continue;
        c->pa = P[k];
        c->pb = P[k + 1];
        c->o_lo = k == 0 ? -HRM__R(HUGE_VAL) : c->brk_off[k - 1];
        c->o_hi = k + 1 == n ? HRM__R(HUGE_VAL) : c->brk_off[k];
        if (c->src == HRM__TAU_STREAM && k > 0) hrm__stream_piece(c, c->brk_off[k - 1]);
        c->scale_fixed = 0;
        hrm__fill(c->scale, HRM__NY, 0);
        /* the budget keeps what the pieces after this one need to start */
        c->max_evals = max_evals - c->piece_cost * (long)(n - 1 - k);
        if (!fixed) {
            N[k] = (int)(hrm__share(o->steps, P[k], P[k + 1], pa, pb) + HRM__R(0.5));
            if (N[k] < hrm__panels_least(o)) N[k] = hrm__panels_least(o);
        }
        {
            hrm_status before = c->warning;
            hrm__dispatch_one(c, o, N[k], yk);
            if (judge && n > 1 && c->warning != before &&
                (c->warning == HRM_WARN_H_MIN || c->warning == HRM_WARN_TOLERANCE)) {
                if (missed == HRM_OK) missed = c->warning;
                c->warning = before;
            }
        }
        c->max_evals = max_evals;
        for (i = 0; i < HRM__CH; ++i) {
            /* Tr up to the piece's start, where the piece's L is relative */
            hrm_real f = c->rte ? acc[i] : c->coupled ? HRM_EXP(-acc[i]) : 1;
            y[HRM__CH + i] += f * yk[HRM__CH + i];
            err[i] += HRM_FABS(f) * c->err_acc[i]; /* (the RTE form's Tr can be < 0) */
            if (c->rte) acc[i] *= yk[i];
            else acc[i] += yk[i];
        }
        /* each piece within the range, their sum too (the RTE form's
           pieces multiply) */
        hrm__state_check(c, y, HRM__NY);
        hrm__state_check(c, acc, HRM__CH);
    }
    if (missed != HRM_OK) {
        int held = 1;
        for (i = 0; i < HRM__CH; ++i)
            held &= err[i] <= c->atol + c->rtol * HRM_FABS(y[HRM__CH + i]) + 16 * HRM__EPS * HRM_FABS(y[HRM__CH + i]);
        if (!held) hrm__warn(c, missed);
    }
    memcpy(y, acc, sizeof acc);
    memcpy(c->err_acc, err, sizeof err);
    c->pa = pa;
    c->pb = pb;
    c->o_lo = -HRM__R(HUGE_VAL);
    c->o_hi = HRM__R(HUGE_VAL);
}

/* The tables in a frame of their own without a workspace, which a ray
   without breakpoints never holds: for at most HRM__PIECES_FEW pieces
   a frame of that size (104 bytes instead of 792), else for every
   breakpoint the options may give. */
#define HRM__PIECES_FEW 8
static HRM_DEVICE HRM__NOINLINE void hrm__solve_broken_few(hrm__ctx *c, const hrm_options *o, hrm_real y[HRM__NY])
{
    hrm_real P[HRM__PIECES_FEW + 1];
    int N[HRM__PIECES_FEW];
    hrm__solve_broken_in(c, o, y, P, N);
}

static HRM_DEVICE HRM__NOINLINE void hrm__solve_broken_on_stack(hrm__ctx *c, const hrm_options *o,
                                                               hrm_real y[HRM__NY])
{
    hrm__piece_tab t;
    hrm__solve_broken_in(c, o, y, t.P, t.N);
}

static HRM_DEVICE void hrm__solve_broken(hrm__ctx *c, const hrm_options *o, hrm_real y[HRM__NY])
{
    if (c->pieces) hrm__solve_broken_in(c, o, y, c->pieces->P, c->pieces->N);
    else if (c->nbrk + 1 <= HRM__PIECES_FEW) hrm__solve_broken_few(c, o, y);
    else hrm__solve_broken_on_stack(c, o, y);
}

/* The source S (per unit length) in every channel at parameter p, the
   offset there and Tr(t0, there) (1 where Tr is not known at a node). */
static HRM_DEVICE void hrm__source_at(hrm__ctx *c, hrm_real p, hrm_real S[HRM__CH], hrm_real *off,
                                      hrm_real tr[HRM__CH])
{
    hrm__pt pt;
    int i;
    hrm__eval(c, p, &pt);
    for (i = 0; i < HRM__CH; ++i) {
        hrm__source_of(&pt, i, &S[i]);
        tr[i] = c->closed ? pt.tr[i] : 1;
    }
    *off = pt.off;
}

/* Whether a bisection of [a, b] (offsets) has reached t's resolution:
   its middle m at the abscissa of an end (the ends then adjacent
   abscissae, or one), where a jump between them is placed at the second
   (hrm__locate_jump, hrm__locate_sigma_jump). */
static HRM_DEVICE int hrm__adjacent(const hrm__ctx *c, hrm_real a, hrm_real m, hrm_real b)
{
    hrm_real tm = hrm__abscissa(c, m);
    return tm == hrm__abscissa(c, a) || tm == hrm__abscissa(c, b);
}

/* Locate the jump inside [pl, pr] (in p) by bisection on the source:
   the half whose ends differ more keeps it, until its ends are adjacent
   abscissae (about 50 evaluations in double on a unit interval). A smooth
   integrand splits its change between the halves, a jump keeps all of
   it in one: three halvings in a row that keep less than 3/4 of the
   change end the search, as for the medium (hrm__locate_sigma_jump). A
   jump of at least 1% of the larger side is kept, as t, in *tj; returns
   0 where there is none (a smooth integrand that merely refines
   slowly). */
static HRM_DEVICE HRM__CALL int hrm__locate_jump(hrm__ctx *c, hrm_real pl, hrm_real pr, hrm_real *tj)
{
    hrm_real Sl[HRM__CH], Sr[HRM__CH], Sm[HRM__CH], trl[HRM__CH], trm[HRM__CH]; /* Tr at pl, pm */
    hrm_real ol, or_, om, d = 0, big = 0, gap;
    int it, i, smooth = 0, fine = 0;
    hrm__source_at(c, pl, Sl, &ol, trl);
    hrm__source_at(c, pr, Sr, &or_, trm);
    for (it = 0; it < 64 && c->status == HRM_OK; ++it) {
        hrm_real pm = pl / 2 + pr / 2, dl = 0, dr = 0, J;
        if (!(pm > pl && pm < pr)) break;
        hrm__map(c, pm, &om, &J);
        if (hrm__adjacent(c, ol, om, or_)) {
            fine = 1;
            break;
        }
        hrm__source_at(c, pm, Sm, &om, trm);
        for (i = 0, big = 0; i < HRM__CH; ++i) {
            dl += HRM_FABS(Sm[i] - Sl[i]);
            dr += HRM_FABS(Sr[i] - Sm[i]);
            big += HRM_FABS(Sl[i]) > HRM_FABS(Sr[i]) ? HRM_FABS(Sl[i]) : HRM_FABS(Sr[i]);
        }
        /* no change left to follow (the source constant across: a thick
           homogeneous ray's interval that refines slowly for Tr's sake,
           50 evaluations of bisection for nothing) */
        if (!(dl + dr > HRM__R(0.01) * big)) return 0;
        smooth = (dl > dr ? dl : dr) < HRM__R(0.75) * (dl + dr) ? smooth + 1 : 0;
        if (smooth >= 3) return 0;
        if (dl > dr) {
            pr = pm;
            or_ = om;
            memcpy(Sr, Sm, sizeof Sm);
        } else {
            pl = pm;
            ol = om;
            memcpy(Sl, Sm, sizeof Sm);
            memcpy(trl, trm, sizeof trm);
        }
    }
    for (i = 0, big = 0; i < HRM__CH; ++i) {
        d += HRM_FABS(Sr[i] - Sl[i]);
        big += HRM_FABS(Sl[i]) > HRM_FABS(Sr[i]) ? HRM_FABS(Sl[i]) : HRM_FABS(Sr[i]);
    }
    if (!(d > HRM__R(0.01) * big)) return 0;
    /* the jump lies anywhere in the bracket: the pieces on either side of
       *tj extend their sides over up to half of it, the jump times that
       at Tr there (the bracket's start's); between adjacent abscissae, *tj
       the second (exact where the jump is at an abscissa, as the callbacks
       see it), up to the whole gap */
    *tj = c->t0 + (ol / 2 + or_ / 2);
    gap = (or_ - ol) / 2;
    if (fine && hrm__abscissa(c, or_) > hrm__abscissa(c, ol)) {
        *tj = hrm__abscissa(c, or_);
        gap = *tj - hrm__abscissa(c, ol);
    }
    for (i = 0; i < HRM__CH; ++i) c->cand_miss[i] = HRM_FABS(Sr[i] - Sl[i]) * gap * trl[i];
    return 1;
}

/* Make offset off (strictly inside, not yet one) a breakpoint, reported
   as a located jump; 0 where there is no room or it is not inside. */
static HRM_DEVICE int hrm__add_jump(hrm__ctx *c, hrm_real off)
{
    int k;
    if (c->njumps >= HRM_MAX_JUMPS || c->nbrk >= HRM_MAX_BREAKS) return 0;
    if (!(off > 0 && off < c->off_end) || hrm__is_break(c, off)) return 0;
    for (k = c->nbrk; k > 0 && c->brk_off[k - 1] > off; --k) c->brk_off[k] = c->brk_off[k - 1];
    c->brk_off[k] = off;
    c->nbrk++;
    for (k = c->njumps; k > 0 && c->jumps[k - 1] > c->t0 + off; --k) c->jumps[k] = c->jumps[k - 1];
    c->jumps[k] = c->t0 + off;
    c->njumps++;
    return 1;
}

/* sigma_t summed over channels at offset off (side: which side of a
   breakpoint there). */
static HRM_DEVICE hrm_real hrm__sigma_sum(hrm__ctx *c, hrm_real off, int side, hrm_real st[HRM__CH])
{
    hrm_real sum = 0;
    int i;
    hrm__sigma_t_at(c, off, side, st);
    for (i = 0; i < HRM__CH; ++i) sum += st[i];
    return sum;
}

/* Whether sigma_t changes by a factor 2 or more between two samples. */
static HRM_DEVICE int hrm__sigma_differs(hrm_real fa, hrm_real fb)
{
    hrm_real big = fa > fb ? fa : fb;
    return HRM_FABS(fb - fa) >= big / 2 && big > 0;
}

/* Bisect [a, b] (offsets, sigma_t sums fa, fb) for a jump of the medium:
   the half whose ends differ more keeps it. A smooth ramp splits its
   change between the halves, a jump keeps all of it in one: three halvings
   in a row that keep less than 3/4 of the change end the search (a steep
   but smooth edge, cheaply). Down to adjacent abscissae, a change of 1% of
   the larger side is a jump; its offset goes to *off. The medium's edge
   (sigma_t 0 on one side) still bracketed against the ray's end or a
   breakpoint is no breakpoint once what the bracket can hold, its width
   times the larger sigma_t, is below 1/64 of tau's tolerance (a panel of
   the layer is never asked for less, and a kink that close to a piece's
   end moves no rule's estimate): a medium that fades out at the ray's
   ends (a sphere of smoke entered and left) costs a few lookups at each,
   not fifty. */
static HRM_DEVICE HRM__CALL int hrm__locate_sigma_jump(hrm__ctx *c, hrm_real a, hrm_real b, hrm_real fa, hrm_real fb,
                                  hrm_real *off)
{
    hrm_real st[HRM__CH], a0 = a, b0 = b;
    hrm_real etol = (c->decoupled ? c->tau->tol : c->rtol) / 64;
    int it, smooth = 0, edge = (fa == 0) != (fb == 0), fine = 0;
    int at_a = a == 0 || hrm__is_break(c, a), at_b = b == c->off_end || hrm__is_break(c, b);
    for (it = 0; it < 80 && c->status == HRM_OK && smooth < 3; ++it) {
        hrm_real m = a / 2 + b / 2, fm, dl, dr;
        if (!(m > a && m < b)) break;
        if (hrm__adjacent(c, a, m, b)) {
            fine = 1;
            break;
        }
        if (edge && ((at_a && a == a0) || (at_b && b == b0)) && (b - a) * (fa > fb ? fa : fb) <= etol)
            return 0;
        fm = hrm__sigma_sum(c, m, 0, st);
        if (edge) {
            /* the medium's edge (sigma_t 0 on one side): a kink at least,
               where it rises from 0 (a cloud's iso-surface), located as a
               jump is, the half where 0 meets sigma_t > 0 kept */
            if ((fm == 0) == (fa == 0)) {
                a = m;
                fa = fm;
            } else {
                b = m;
                fb = fm;
            }
            continue;
        }
        dl = HRM_FABS(fm - fa);
        dr = HRM_FABS(fb - fm);
        smooth = (dl > dr ? dl : dr) < HRM__R(0.75) * (dl + dr) ? smooth + 1 : 0;
        if (dl > dr) {
            b = m;
            fb = fm;
        } else {
            a = m;
            fa = fm;
        }
    }
    if (smooth >= 3 || c->status != HRM_OK) return 0;
    if (!(HRM_FABS(fb - fa) > HRM__R(0.01) * (fa > fb ? fa : fb))) return 0;
    /* (not down to adjacent abscissae: a jump at the bracket's middle, an
       edge at its end inside the medium, the piece beyond smooth from its
       start: at the middle, a float ray had the kink on either side by an
       ulp, and a pair descended to t's resolution at it) */
    *off = edge ? (fa == 0 ? b : a) : a / 2 + b / 2;
    if (fine) {
        /* sigma_t changes between two adjacent abscissae: the breakpoint
           at the second, exact where the face is at an abscissa (at the
           bracket's middle or end, a slab at t = 15 in float, sigma_t 700
           over 0.002, was up to 8 ulps thick or thin: L 8 rtol off with
           HRM_OK at rtol 1e-4; in a vacuum, 57% of such solves) */
        hrm_real tb = hrm__abscissa(c, b) - c->t0;
        if (tb > a && hrm__abscissa(c, tb) == hrm__abscissa(c, b)) *off = tb;
    }
    return 1;
}

/* The medium scan (options.find_jumps, sigma from callbacks): sigma_t at
   nscan + 1 offsets (hrm__scan_at: by default the degree-8 Lobatto points
   of panels laid over the pieces between the breakpoints, 4 at least and
   one a piece (hrm__scan_layout: 33 points without breakpoints); with the
   medium's feature, as many panels as keep its points that close, one a
   piece at least (a constant medium as callbacks: 9 samples a ray); kept
   for the transmittance layer, whose march tries those panels first on
   them; where they would be more than HRM__SCAN_Q, evenly spaced, at
   most HRM__SCAN_MAX (the feature's spacing, or 33 points); and both
   sides of each breakpoint);
   where neighbours differ by a factor 2 or more the jump between them is
   located and made a breakpoint before the method runs, so that a slab or
   a bounding box is integrated at each piece's order by every method and
   every form; so is a medium's edge (sigma_t 0 on one side), kink or
   jump. Where no jump is found between them (a steep but smooth change),
   the transmittance layer learns the larger of the two samples, which its
   panels must then reproduce: a feature a few scan points wide is not
   lost between the samples of its first panel (9 over the whole ray where
   sigma_t is 0 at t0). What lies between two neighbours unseen stays
   unseen. A sample that stands above or below both neighbours by an
   eighth of the three's largest is taught too (while half the layer's
   memory is free): a bump or a hole a few scan points wide that changes
   by less than a factor 2 a spacing, which the layer's first panels step
   over (a Gaussian hole to 0.41 of the medium, 0.04 wide at half depth,
   on a unit ray of tau 3.4: Tr 9% low, L 8.6 rtol off with HRM_OK at
   rtol 1e-2; in a random search of holes and bumps under a Gaussian Li,
   nested Simpson at rtol 1e-1..1e-3, 126 and 55 of 10 000 solves silent
   without, 18 and 16 with it, those left the source's own miss of a
   narrow Li, as silent with the exact Tr given). Not where a
   transmittance callback gives Tr: no layer to teach (33 sigma calls a
   solve saved); the medium check's gross misses find most of what lies
   between the nodes, the scan with it little more (bench/README.md, "A
   transmittance callback ..."). The scan ends where the trapezoid rule on its
   own samples puts tau (the thinnest channel's) past twice ln(64 / rtol):
   behind that no jump moves L by a share of rtol, and the layer and the
   rules, which still cover the rest, spend little there (a cloud's core:
   a quarter of a camera ray's lookups saved). */

/* The scan's panels over the pieces between the breakpoints: one a piece
   at least, 4 in all at least, the rest to the pieces whose panels are
   longest; their ends into b. Returns their count, 0 where the pieces are
   more than HRM__SCAN_Q (the scan then evenly spaced). */
static HRM_DEVICE int hrm__scan_layout(const hrm__ctx *c, hrm_real b[HRM__SCAN_Q + 1])
{
    int np = c->nbrk + 1, nq = np > 4 ? np : 4, q[HRM__SCAN_Q], i, j, k = 0, e;
    hrm_real lo[HRM__SCAN_Q], len[HRM__SCAN_Q], wide = c->m->feature / HRM__SCAN_GAP;
    if (np > HRM__SCAN_Q) return 0;
    for (i = 0; i < np; ++i) {
        lo[i] = i ? c->brk_off[i - 1] : 0;
        len[i] = (i < c->nbrk ? c->brk_off[i] : c->off_end) - lo[i];
        q[i] = 1;
    }
    if (wide > 0) {
        /* with a feature: each piece's panels no wider than its spacing
           asks for, the layout only where they are HRM__SCAN_Q at most */
        for (i = 0, nq = 0; i < np; ++i) {
            hrm_real n = len[i] / wide;
            if (!(n <= HRM__SCAN_Q)) return 0;
            q[i] = n > 1 ? (int)n : 1;
            q[i] += (hrm_real)q[i] < n;
            nq += q[i];
        }
        if (nq > HRM__SCAN_Q) return 0;
    }
    for (e = wide > 0 ? nq : np; e < nq; ++e) {
        int best = 0;
        for (i = 1; i < np; ++i)
            if (len[i] * (hrm_real)q[best] > len[best] * (hrm_real)q[i]) best = i;
        q[best]++;
    }
    for (i = 0; i < np; ++i)
        for (j = 0; j < q[i]; ++j) b[k++] = j ? lo[i] + len[i] * ((hrm_real)j / (hrm_real)q[i]) : lo[i];
    b[nq] = c->off_end;
    return nq;
}

static HRM_DEVICE HRM__CALL HRM__NOINLINE void hrm__scan_medium(hrm__ctx *c)
{
    hrm_real sa[HRM__CH], sx[HRM__CH], pb[HRM__SCAN_Q + 1];
    hrm_real a = 0, fa = hrm__sigma_sum(c, 0, 0, sa), tau[HRM__CH], least;
    hrm_real deep = 2 * HRM_LOG(64 / c->rtol);
    int k = 1, b = 0, i, nscan = HRM__SCAN, prev = 0, keep, nq = 0;
    hrm_real fp = 0;
    hrm__fill(tau, HRM__CH, 0);
    nq = hrm__scan_layout(c, pb);
    if (nq) {
        nscan = 8 * nq;
    } else if (c->m->feature > 0) {
        /* evenly at the spacing of the medium's thinnest feature */
        hrm_real n = c->off_end / c->m->feature;
        nscan = n >= HRM__SCAN_MAX ? HRM__SCAN_MAX : (int)n + 1;
    }
    /* the samples kept for the layer's first panels */
    keep = c->decoupled && nq && c->tau->end == c->off_end && c->tau->scan;
    if (keep) {
        hrm__tau *L = c->tau;
        L->scan_q = nq;
        memcpy(L->scan->b, pb, sizeof pb);
        memset(L->scan->have, 0, sizeof L->scan->have);
        memset(L->scan->ha, 0, sizeof L->scan->ha);
        memcpy(L->scan->s[0], sa, sizeof sa);
        L->scan->have[0] = 1;
    }
    while (a < c->off_end && c->status == HRM_OK) {
        hrm_real grid = hrm__scan_at(pb, nq, c->off_end, k, nscan), x, fx, at;
        int is_brk, gk = k;
        /* the next point: a grid point or a breakpoint, whichever is first */
        while (b < c->nbrk && c->brk_off[b] <= a) ++b;
        is_brk = b < c->nbrk && c->brk_off[b] <= grid;
        x = is_brk ? c->brk_off[b] : grid;
        if (!is_brk) ++k;
        if (!(x > a)) continue;
        fx = hrm__sigma_sum(c, x, -1, sx);
        if (keep && x == grid) {
            memcpy(c->tau->scan->s[gk], sx, sizeof sx);
            c->tau->scan->have[gk] = 1;
        }
        for (i = 0, least = HRM__R(HUGE_VAL); i < HRM__CH; ++i) {
            tau[i] += (x - a) * (sa[i] / 2 + sx[i] / 2);
            least = tau[i] < least ? tau[i] : least;
        }
        if (hrm__sigma_differs(fa, fx)) {
            if (hrm__locate_sigma_jump(c, a, x, fa, fx, &at)) {
                if (!hrm__add_jump(c, at)) return; /* no room for more */
            } else if (c->decoupled) {
                if (fx > fa) hrm__tau_learn(c->tau, x, sx);
                else if (a > 0) hrm__tau_learn(c->tau, a, sa);
            }
        }
        if (c->decoupled && prev && c->tau->nmem < HRM__TMEM / 2) {
            /* a is a peak or a trough of the scan's samples, off the line
               through its neighbours by an eighth of the largest: taught
               (while half the layer's memory is left for its own); by a
               64th where the scan lies evenly at medium.feature, whose
               points the layer's panels, 32 a ray at most, need not
               reach (a 5% notch as wide as the feature, 1/280 of the
               ray, under a light's warp: every method 14 rtol off with
               HRM_OK at rtol 1e-4, tau without it) */
            hrm_real big = fp > fx ? fp : fx;
            big = fa > big ? fa : big;
            if (((fa < fp && fa < fx) || (fa > fp && fa > fx)) &&
                HRM_FABS(fa - (fp / 2 + fx / 2)) > big / (!nq && c->m->feature > 0 ? 64 : 8))
                hrm__tau_learn(c->tau, a, sa);
        }
        a = x;
        if (c->cut_tau > 0 && least > c->cut_tau && x < c->off_end) {
            /* options.cutoff passed: the ray ends here */
            c->cut_at = x;
            return;
        }
        if (least > deep) return;
        fp = fa;
        prev = !is_brk;
        if (is_brk) {
            fa = hrm__sigma_sum(c, x, 1, sa);
            if (keep && x == grid && gk % 8 == 0) { /* a panel's start: its side */
                memcpy(c->tau->scan->a[gk / 8], sa, sizeof sa);
                c->tau->scan->ha[gk / 8] = 1;
            }
        } else {
            fa = fx;
            memcpy(sa, sx, sizeof sa);
        }
    }
}

/* Run the method over the pieces; where a split found a jump, locate it,
   make it a breakpoint (reported in hrm_result.jumps) and solve again.
   The evaluations of every pass count. */
static HRM_DEVICE HRM__CALL void hrm__dispatch(hrm__ctx *c, const hrm_options *o, hrm_real y[HRM__NY])
{
    hrm_status w0 = c->warning;
    int i;
    for (;;) {
        c->jump_found = 0;
        c->layer_miss = 0;
        hrm__solve_pieces(c, o, y);
        if (c->status != HRM_OK) return;
        if (c->layer_miss && c->restarts < 8 && c->max_evals - c->stats.evals >= c->stats.evals) {
            /* the layer learns sigma_t there and is built again; the solve
               is repeated with it (once per miss, 8 at most) */
            hrm_real st[HRM__CH];
            c->restarts++;
            c->warning = w0;
            hrm__sigma_t_at(c, c->miss_off, 0, st);
            hrm__tau_rebuild(c->tau);
            hrm__tau_learn(c->tau, c->miss_off, st);
            continue;
        }
        if (!c->jump_found) {
            /* no budget or no tries left to repair a miss: the answer's
               tau is known to miss something, which HRM_OK must not hide */
            if (c->layer_miss) hrm__warn(c, HRM_WARN_TOLERANCE);
            return;
        }
        c->warning = w0;
        if (!hrm__add_jump(c, c->cand_t - c->t0)) {
            c->find_jumps = 0; /* solve once more without looking */
            continue;
        }
        for (i = 0; i < HRM__CH; ++i) c->jump_miss[i] += c->cand_miss[i];
        /* the layer's panels end at breakpoints: built again */
        if (c->decoupled) hrm__tau_rebuild(c->tau);
    }
}

/* Tr(t0, t1) and the status: a closed form is exact in every method and
   form, the layer's tau is the one the nodes saw. */
static HRM_DEVICE HRM__CALL hrm_status hrm__finish(hrm__ctx *c, const hrm_options *o, const hrm_real y[HRM__NY],
                              hrm_real L[HRM__CH], hrm_real Tr[HRM__CH], hrm_real err[HRM__CH])
{
    int adaptive = hrm__is_adaptive(o->method);
    int i;
    hrm_real absorbed[HRM__CH]; /* 1 - Tr, without cancellation where tau is known */
    memcpy(L, y + HRM__CH, sizeof(hrm_real) * HRM__CH);
    if (c->decoupled || c->src == HRM__TAU_STREAM) {
        if (c->decoupled) {
            hrm__tau_at(c, c->tau, c->off_end, Tr, 0);
        } else {
            hrm__stream_to(c, c->off_end, 0, NULL);
            memcpy(Tr, c->sm.tau, sizeof(hrm_real) * HRM__CH);
        }
        for (i = 0; i < HRM__CH; ++i) {
            absorbed[i] = -HRM_EXPM1(-Tr[i]);
            Tr[i] = HRM_EXP(-Tr[i]);
        }
    } else if (c->homog || c->m->transmittance) {
        hrm__closed_tr(c, Tr);
        for (i = 0; i < HRM__CH; ++i)
            absorbed[i] = c->homog ? -HRM_EXPM1(-c->st[i] * c->off_end) : 1 - Tr[i];
    } else if (c->rte) {
        memcpy(Tr, y, sizeof(hrm_real) * HRM__CH); /* y holds (Tr, L) */
        for (i = 0; i < HRM__CH; ++i) absorbed[i] = 1 - Tr[i];
    } else {
        for (i = 0; i < HRM__CH; ++i) {
            absorbed[i] = -HRM_EXPM1(-y[i]);
            Tr[i] = HRM_EXP(-y[i]);
        }
    }
    for (i = 0; i < HRM__CH; ++i) {
        err[i] = adaptive ? c->err_acc[i] + c->jump_miss[i] : -1;
        /* a located jump that t places no better than its bracket, which
           holds more than twice the tolerance (float, a layer 0.005 thick
           at t = 10: its edge to 2 ulps, L 7 rtol off at rtol 1e-4 with
           HRM_OK; past rtol, an independent check's float media with
           slabs and emission warned on 48 answers within rtol, none
           beyond) */
        if (adaptive && c->jump_miss[i] > c->atol + 2 * c->rtol * HRM_FABS(y[HRM__CH + i]))
            hrm__warn(c, HRM_WARN_ROUNDOFF);
        /* an estimate past the range (a forced step in the RTE form far
           past its stability limit: NaN): none, the range instead */
        if (adaptive && !(err[i] <= c->range)) {
            err[i] = c->range;
            hrm__warn(c, HRM_WARN_TOLERANCE);
        }
    }
    for (i = 0; i < HRM__CH; ++i)
        /* fixed steps across the transmittance callback's underflow that
           count beyond round-off: upper bounds, not estimates */
        if (c->unsure[i] > 16 * HRM__EPS * HRM_FABS(L[i])) hrm__warn(c, HRM_WARN_ROUNDOFF);
    if (!c->per_length) {
        /* physically bounded whatever a budget cut short, a fixed step
           overshot or an explicit step past its stability limit gave
           (Simpson N = 32 on a ray 1e30 long: L = 1.4e27; Fehlberg in the
           RTE form: Tr 1506): 0 <= Tr <= 1 and 0 <= L <= the largest S /
           sigma_t sampled (the larger of Le and Li where sigma_t is not
           known at a sample, S / sigma_t being their weighted mean) times
           1 - Tr; what is cut off counts in the estimate. Fixed steps in
           the RTE form keep the papers' blow-up (a warning only); fixed
           steps without a fit keep up to twice the bound (a rule's error
           where the sampled S / sigma_t and its own Tr are coarse: Euler
           in a slab, clamped to the bound, reached 1e-2 at no N). */
        for (i = 0; i < HRM__CH; ++i) {
            hrm_real top, cut = 0, l = L[i], tr = Tr[i], slack;
            int bad = 0;
            if (c->rte && !(tr >= 0 && tr <= 1)) {
                bad = !(tr >= -16 * HRM__EPS && tr <= 1 + 16 * HRM__EPS);
                tr = tr > 1 ? 1 : 0;
                absorbed[i] = 1 - tr;
            }
            top = c->src_max[i] * absorbed[i] * (1 + 16 * HRM__EPS);
            slack = 16 * HRM__EPS * top;
            /* (Monte Carlo: any; a sample's value past it is no miss,
               and cutting it would bias the mean over pixels) */
            if (!adaptive && !c->expo && l > top && (l <= 2 * top || o->method == HRM_MONTE_CARLO)) {
                top = l;
            }
            if (l > top) {
                cut = l - top;
                l = top;
            }
            if (l < 0) {
                cut = -l;
                l = 0;
            }
            if (adaptive || !c->rte) {
                L[i] = l;
                Tr[i] = tr;
            }
            if (adaptive) err[i] += cut;
            /* a cut beyond the tolerance: the rule missed, and HRM_OK
               must not hide it (t's resolution on a ray far from the
               origin under a user warp gave L 625 times too large, the
               cut its only trace); fixed steps: beyond round-off */
            if (bad || (adaptive ? err[i] > c->atol + 3 * c->rtol * HRM_FABS(l) + 16 * HRM__EPS * HRM_FABS(l)
                                 : cut > slack))
                /* round-off where the ray spans fewer than 2^20 ulps of t */
                hrm__warn(c, HRM_FABS(c->t0) * HRM__EPS * HRM__R(1048576.0) > c->T ? HRM_WARN_ROUNDOFF
                                                                                  : HRM_WARN_TOLERANCE);
        }
    }
    /* t cannot place the nodes near a light to better than w_res of its
       distance, nor sample the light's profile there to better than w_res:
       an error of 1 to 6 times it (float, a light 2.3e-3 from the ray at t
       = 17 or 1.7e-3 at 82: every method 9 and 36 rtol off with HRM_OK).
       Past 2 rtol (an independent check's hard float scenes, lights 1e-4
       to 3e-2 of the ray from it, 29 250 solves through
       hrm_light_options: beyond 3 rtol with HRM_OK 57 -> 0, beyond rtol
       102 -> 34, warnings on answers within rtol 1 552 -> 2 863; past rtol
       0, 30 and 3 870; past 4 rtol 27, 62, 2 145; at rtol / 8 the tests'
       accurate answers warned as well) */
    if (adaptive && (c->unresolved || c->w_res > 2 * c->rtol)) hrm__warn(c, HRM_WARN_ROUNDOFF);
    if (c->status != HRM_OK) {
        hrm__fill(L, HRM__CH, 0);
        hrm__fill(Tr, HRM__CH, 1);
        hrm__fill(err, HRM__CH, -1);
        return c->status;
    }
    return c->warning;
}

/* The shadow-ray estimator (hrm_transmittance without a method): tau by
   Simpson panels in t, refined worst-first against one error estimate for
   each segment of the ray. A panel has 5 samples of sigma_t; e = S2 - S1
   (Simpson on its halves minus Simpson on it) is the size of S1's error,
   or where the two agreed by chance, what its samples' differences
   predict (hrm__fourth_pred, where their third differences agree: a C1
   fade at a medium's edge that the samples saw as a cubic, 24 times the
   tolerance off at 1e-5; 22 of bench_shadow's 30 000 answers beyond 3
   tolerances, 3 with it), the panel contributes S2 + (S2 - S1) / 15, and
   a segment's estimate is the larger
   of |sum e| and 2 sqrt(sum e^2): in noise (fBm smoke) the panels' errors
   have random signs and add like a random walk, which the second term
   bounds however the signs fall (twice the root: with the root alone,
   3.1% of smoke rays missed a 1e-4 tolerance, with twice it 0.8%);
   where they do not (a smooth medium) the first is the larger. Accepting
   each panel's |e| at its share of the tolerance instead made 8 to 60
   times the error asked for in the smoke, and twice the lookups; Lyness's
   |e| / 15 left 41% of those rays beyond 1e-3. The worst panel (largest
   |e|) is split until the estimate is within tr_tol max(1, cutoff / Tr)
   times the segment's share of the ray (Tr the thinnest channel's at the
   segment's start), so that |Tr - exact| <= tr_tol max(Tr, cutoff) to
   first order. A segment starts as 4 panels, or with medium.feature,
   panels no wider than it (a slab between the first samples is not seen);
   the first is the ray (with a cut-off, a quarter of it), each next sized
   to start as a quarter of the storage's worth of panels (8 at least) at
   the density the last one needed (with a cut-off, to end at most a
   quarter past where the last one's rate of tau reaches it), and none
   past a breakpoint (options.breaks: a slab given only by its edges,
   between the first samples, had left Tr near 1 with HRM_OK), sigma_t
   sampled on each side of it; where
   HRM_SHADOW_PANELS fill, the segment ends at its middle panel (the
   right half's samples given up). The march stops after
   the segment where every channel's Tr falls below the cut-off or
   underflows. Panels narrower than twice h_min (64 eps of the ray's reach)
   are not split; where none can be, or past max_evals medium evaluations,
   the segment is taken as it is, with HRM_WARN_H_MIN or
   HRM_WARN_MAX_EVALS. */

/* A panel's S2 (Simpson on its halves), channel ch. */
static HRM_DEVICE hrm_real hrm__panel_s2(const hrm__panel *p, int ch)
{
    return p->h / 12 * (p->f[0][ch] + 4 * p->f[1][ch] + 2 * p->f[2][ch] + 4 * p->f[3][ch] + p->f[4][ch]);
}

/* A panel's S1 (Simpson on it), channel ch. */
static HRM_DEVICE hrm_real hrm__panel_s1(const hrm__panel *p, int ch)
{
    return p->h / 6 * (p->f[0][ch] + 4 * p->f[2][ch] + p->f[4][ch]);
}

/* e and worst from a panel's samples, once they are all taken. */
static HRM_DEVICE void hrm__panel_set(hrm__panel *p)
{
    int i;
    p->worst = 0;
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real d, pred = hrm__fourth_pred((const hrm_real(*)[HRM__CH])p->f, i, p->h, 1);
        p->e[i] = hrm__panel_s2(p, i) - hrm__panel_s1(p, i);
        if (pred > HRM_FABS(p->e[i])) p->e[i] = p->e[i] < 0 ? -pred : pred;
        d = HRM_FABS(p->e[i]);
        if (!(d <= p->worst)) p->worst = d == d ? d : HRM__R(HUGE_VAL);
    }
}

/* The estimate of panels p[0..np), the largest channel's max(|sum e|,
   2 sqrt(sum e^2)); with tau, their S2 + e / 15 added to it. */
static HRM_DEVICE hrm_real hrm__shadow_take(const hrm__panel *p, int np, hrm_real *tau)
{
    hrm_real est = 0;
    int i, k;
    for (i = 0; i < HRM__CH; ++i) {
        hrm_real sum = 0, sq = 0, e;
        for (k = 0; k < np; ++k) {
            e = p[k].e[i];
            sum += e;
            sq += e * e;
            if (tau) {
                hrm_real s2 = hrm__panel_s2(&p[k], i), d = s2 + (s2 - hrm__panel_s1(&p[k], i)) / 15;
                tau[i] += d > 0 ? d : 0;
            }
        }
        e = HRM_FABS(sum) > 2 * HRM_SQRT(sq) ? HRM_FABS(sum) : 2 * HRM_SQRT(sq);
        if (!(e <= est)) est = e; /* NaN or inf: the largest */
    }
    return est;
}

static HRM_DEVICE HRM__CALL void hrm__shadow_run(hrm__ctx *c, const hrm_options *o, hrm_real tau[HRM__CH], hrm__panel *p)
{
    hrm_real T = c->T, hmin, cap = -HRM_LOG(HRM__TINY), feature = c->m->feature;
    hrm_real taumin = 0, rise, loose = 1, tau_cut = o->cutoff > 0 ? -HRM_LOG(o->cutoff) : HRM__R(HUGE_VAL);
    hrm_real a = 0, len = o->cutoff > 0 ? T / 4 : T;
    int i;
    hmin = 64 * HRM__EPS * (HRM_FABS(c->t0) > T ? HRM_FABS(c->t0) : T);
    hrm__fill(tau, HRM__CH, 0);
    c->stats.t_cut = c->t1;
    hrm__sigma_t_at(c, 0, 0, p[0].f[0]);
    while (a < T && c->status == HRM_OK) {
        hrm_real b, allow;
        int np = 4, k, j;
        hrm_status short_of = HRM_OK;
        /* with feature: panels no wider than it, at most half the
           storage to start with */
        if (feature > 0 && len > HRM_SHADOW_PANELS / 2 * feature) len = HRM_SHADOW_PANELS / 2 * feature;
        b = a + len;
        if (!(b < T) || T - b < hmin) b = T;
        /* a segment ends at a breakpoint (sigma_t may jump there: its
           samples on each side); the next starts from it */
        for (k = 0; k < c->nbrk; ++k)
            if (c->brk_off[k] > a && c->brk_off[k] < b) {
                b = c->brk_off[k];
                break;
            }
        if (a > 0 && hrm__is_break(c, a)) hrm__sigma_t_at(c, a, 1, p[0].f[0]);
        if (feature > 0 && (b - a) / feature > (hrm_real)np) {
            np = (int)((b - a) / feature);
            if ((hrm_real)np * feature < b - a && np < HRM_SHADOW_PANELS / 2) ++np;
        }
        /* the segment's first panels, their samples shared at the ends */
        for (k = 0; k < np; ++k) {
            p[k].a = a + (b - a) * (hrm_real)k / (hrm_real)np;
            p[k].h = (k + 1 == np ? b : a + (b - a) * (hrm_real)(k + 1) / (hrm_real)np) - p[k].a;
            if (k > 0) memcpy(p[k].f[0], p[k - 1].f[4], sizeof p[0].f[0]);
            for (j = 1; j <= 4; ++j) {
                int left = j == 4 && k + 1 == np && hrm__is_break(c, b); /* sigma_t before it */
                hrm__sigma_t_at(c, left ? b : p[k].a + p[k].h * (hrm_real)j / 4, -left, p[k].f[j]);
            }
            hrm__panel_set(&p[k]);
        }
        c->stats.steps += np;
        allow = o->tr_tol * loose * (b - a) / T;
        while (c->status == HRM_OK && !(hrm__shadow_take(p, np, NULL) <= allow)) {
            hrm_real worst = -1;
            int w = -1;
            for (k = 0; k < np; ++k)
                if (p[k].h / 2 > hmin && p[k].worst > worst) {
                    worst = p[k].worst;
                    w = k;
                }
            if (w < 0 || c->stats.medium_evals >= o->max_evals) {
                short_of = w < 0 ? HRM_WARN_H_MIN : HRM_WARN_MAX_EVALS;
                break;
            }
            if (np == HRM_SHADOW_PANELS) {
                /* storage full: the segment ends at its middle panel, the
                   right half's samples given up */
                np /= 2;
                b = p[np].a;
                allow = o->tr_tol * loose * (b - a) / T;
                continue;
            }
            /* panel w into halves, 4 samples more */
            for (i = np; i > w; --i) p[i] = p[i - 1];
            ++np;
            p[w].h /= 2;
            p[w + 1].a = p[w].a + p[w].h;
            p[w + 1].h -= p[w].h;
            memcpy(p[w + 1].f[0], p[w].f[2], sizeof p[0].f[0]);
            memcpy(p[w + 1].f[2], p[w].f[3], sizeof p[0].f[0]);
            memcpy(p[w].f[4], p[w].f[2], sizeof p[0].f[0]);
            memcpy(p[w].f[2], p[w].f[1], sizeof p[0].f[0]);
            hrm__sigma_t_at(c, p[w].a + p[w].h / 4, 0, p[w].f[1]);
            hrm__sigma_t_at(c, p[w].a + 3 * p[w].h / 4, 0, p[w].f[3]);
            hrm__sigma_t_at(c, p[w + 1].a + p[w + 1].h / 4, 0, p[w + 1].f[1]);
            hrm__sigma_t_at(c, p[w + 1].a + 3 * p[w + 1].h / 4, 0, p[w + 1].f[3]);
            hrm__panel_set(&p[w]);
            hrm__panel_set(&p[w + 1]);
            c->stats.steps++;
            c->stats.rejected++;
        }
        if (c->status != HRM_OK) break;
        if (short_of != HRM_OK) hrm__warn(c, short_of);
        hrm__shadow_take(p, np, tau);
        rise = taumin;
        for (i = 0; i < HRM__CH; ++i)
            if (i == 0 || tau[i] < taumin) taumin = tau[i];
        rise = taumin - rise;
        loose = o->cutoff > 0 && taumin > tau_cut - 1 ? o->cutoff / HRM_EXP(-taumin) : 1;
        if (loose < 1) loose = 1;
        /* the next segment sized to start a quarter of the storage's worth
           of panels (8 at least), as this one's needed: more than the 4 a
           segment starts with, so that segments grow again past a dense
           stretch (aiming at a quarter of 8 or 16 panels, segments never
           grow and at 8 only shrink: a smooth medium on [0, 6] at the
           default tr_tol does not finish in 20 minutes) */
        len = (b - a) * (hrm_real)HRM__SHADOW_AIM / (hrm_real)np;
        if (len > 4 * (b - a)) len = 4 * (b - a);
        /* with a cut-off, no longer than to a quarter past where the
           thinnest channel's tau reaches it at this segment's rate (never
           shorter than this segment): the march stops soon after the
           cut-off, whatever the storage (sized by the storage alone, with
           4 096 panels a segment the second runs to t1) */
        if (rise > 0 && taumin < tau_cut) {
            hrm_real reach = (tau_cut - taumin) / rise * (b - a) * HRM__R(1.25);
            if (reach < b - a) reach = b - a;
            if (len > reach) len = reach;
        }
        memcpy(p[0].f[0], p[np - 1].f[4], sizeof p[0].f[0]);
        a = b;
        /* every channel below the cut-off, or underflowed: stop */
        if ((taumin >= cap || taumin > tau_cut) && a < T) {
            c->stats.t_cut = hrm__abscissa(c, a);
            break;
        }
    }
}

/* The estimator with its panels in a frame of its own (no workspace). */
static HRM_DEVICE HRM__CALL HRM__NOINLINE void hrm__shadow_march(hrm__ctx *c, const hrm_options *o, hrm_real tau[HRM__CH])
{
    hrm__panel p[HRM_SHADOW_PANELS];
    hrm__shadow_run(c, o, tau, p);
}

/* One call's arguments, carried through the frames that hold the storage
   it needs (hrm__stage). */
typedef struct hrm__job {
    const hrm_medium *m;
    hrm_real t0, t1;
    hrm_options o;         /* resolved */
    int tr_only;
    int estimator;         /* hrm_transmittance's shadow-ray estimator */
    hrm_real *L, *Tr, *err;
    hrm_stats *stats;
    int *njumps;
    hrm_real *jumps;
    unsigned need;         /* HRM__NEED_*: storage still to provide */
    void *at[HRM__NEEDS];  /* where each need is held (need bit k: at[k]) */
    unsigned char *ws;     /* the caller's workspace, what is left of it */
    const hrm_real *tr_end; /* a ray cut where Tr has a closed form
                              (hrm__solve_cut): Tr(t0, t_end), else NULL */
    hrm_real t_end;        /* and the ray's end past the cut */
} hrm__job;

/* The storage a solve needs: the layer where tau comes from it (not for
   the shadow-ray estimator, which keeps its own panels; the distance
   warp's reach marched without it elsewhere, hrm__reach_march); the memo for the
   adaptive methods (not for the estimator, whose samples never repeat and
   never go through hrm__eval); the fits' tables where a fit runs; the worst-first
   drivers' storage where they run. Each is held only then, in the
   caller's workspace or in a frame of its own, so that a fixed-step solve
   on constants reserves none of it. */
static HRM_DEVICE unsigned hrm__needs(const hrm_medium *m, const hrm_options *o, int tr_only, int estimator)
{
    int le, li;
    hrm__tau_src src;
    unsigned need = 0;
    hrm__sources(m, tr_only, &le, &li);
    src = hrm__tau_source(m, o, le || li);
    if (!estimator && src == HRM__TAU_LAYER) need |= HRM__NEED_LAYER;
    if (hrm__is_adaptive(o->method) && !estimator) need |= HRM__NEED_MEMO;
    if (o->exponential && hrm__tau_closed(src)) need |= HRM__NEED_EFIT;
    need |= estimator ? HRM__ESTIMATOR_NEED : HRM__CTX_NEED | HRM__NEED_PIECES;
    /* the drivers run where there is a source or tau comes from their
       nodes (not for Tr alone from the layer or a closed form) */
    if (!estimator && (le || li || !hrm__tau_closed(src)))
        need |= hrm__may_need(o) & (HRM__NEED_NS | HRM__NEED_GK | HRM__NEED_FINISH);
    return need;
}

static HRM_DEVICE hrm_status hrm__stage(hrm__job *j);

/* Without a workspace, each need in a frame of its own. */
/* The layer with npanel panels, ncoef panels' coefficients, ncheck
   checkpoints and, where scanned, the medium scan's storage (scan_decl
   declares it, scan_at points to it; empty and NULL without): a worst-
   first method's, a pair's, a fixed-step rule's (with options.find_jumps
   1, the only one to scan, and without). A fixed-step rule asks for tau at
   nodes in increasing t: it never marches a forgotten panel again from a
   checkpoint (were it to, fewer checkpoints would cost lookups, never
   change a value). */
#define HRM__LAYER_FRAME(name, npanel, ncoef, ncheck, scan_decl, scan_at) \
    static HRM_DEVICE HRM__NOINLINE hrm_status name(hrm__job *j)              \
    {                                                                         \
        hrm__tau layer;                                                       \
        hrm__tpanel tab[npanel];                                              \
        hrm__tcoef cache[ncoef];                                              \
        hrm__tcheck cp[ncheck];                                               \
        scan_decl                                                             \
        layer.tab = tab;                                                      \
        layer.ntab = npanel;                                                  \
        layer.cache = cache;                                                  \
        layer.ncache = ncoef;                                                 \
        layer.cp = cp;                                                        \
        layer.cpcap = ncheck;                                                 \
        layer.scan = scan_at;                                                 \
        j->at[0] = &layer;                                                    \
        j->need &= ~HRM__NEED_LAYER;                                          \
        return hrm__stage(j);                                                 \
    }
HRM__LAYER_FRAME(hrm__with_layer, HRM__TAU_STACK, HRM__TCACHE, HRM__TCHECK, hrm__tscan scan;, &scan)
HRM__LAYER_FRAME(hrm__with_layer_pair, HRM__TAU_STACK_FIXED, HRM__TCACHE, HRM__TCHECK, hrm__tscan scan;, &scan)
HRM__LAYER_FRAME(hrm__with_layer_fixed_scan, HRM__TAU_STACK_RULE, HRM__TCACHE_FIXED, HRM__TCHECK_FIXED,
                 hrm__tscan scan;, &scan)
HRM__LAYER_FRAME(hrm__with_layer_fixed, HRM__TAU_STACK_RULE, HRM__TCACHE_FIXED, HRM__TCHECK_FIXED, , NULL)

static HRM_DEVICE HRM__NOINLINE hrm_status hrm__with_memo(hrm__job *j)
{
    hrm__memo_tab memo;
    j->at[1] = &memo;
    j->need &= ~HRM__NEED_MEMO;
    return hrm__stage(j);
}

/* The fits on n0 and n1 nodes at most (hrm__efit_setup): Simpson's on 3;
   a pair's on its distinct nodes; Gauss-Kronrod's on its Kronrod nodes
   and its Gauss nodes (at most 8). */
#define HRM__EFIT_FRAME(name, n0, n1)                                         \
    static HRM_DEVICE HRM__NOINLINE hrm_status name(hrm__job *j)              \
    {                                                                         \
        hrm__efit ef[2];                                                      \
        hrm_real A0[(n0) * (n0)], A1[(n1) * (n1)];                            \
        ef[0].A = A0;                                                         \
        ef[0].cap = (n0) * (n0);                                              \
        ef[1].A = A1;                                                         \
        ef[1].cap = (n1) * (n1);                                              \
        j->at[2] = ef;                                                        \
        j->need &= ~HRM__NEED_EFIT;                                           \
        return hrm__stage(j);                                                 \
    }
HRM__EFIT_FRAME(hrm__with_efit3, 3, 1)
HRM__EFIT_FRAME(hrm__with_efit_pair, HRM__MAX_STAGES, 1)
HRM__EFIT_FRAME(hrm__with_efit_gk, HRM__EFIT_MAX, 8)

static HRM_DEVICE HRM__NOINLINE hrm_status hrm__with_ns(hrm__job *j)
{
    hrm__ns_store ns;
    j->at[3] = &ns;
    j->need &= ~HRM__NEED_NS;
    return hrm__stage(j);
}

static HRM_DEVICE HRM__NOINLINE hrm_status hrm__with_gk(hrm__job *j)
{
    hrm__gk_store gks;
    j->at[4] = &gks;
    j->need &= ~HRM__NEED_GK;
    return hrm__stage(j);
}

/* c set up for job j on [j->t0, t1] in the storage j holds (keep_layer:
   a ray cut by the scan, hrm__cut_ray). */
static HRM_DEVICE HRM__CALL hrm_status hrm__job_setup(hrm__job *j, hrm__ctx *c, hrm_real t1, int keep_layer)
{
    memset(c, 0, sizeof *c);
    c->ns = (hrm__ns_store *)j->at[3];
    c->gks = (hrm__gk_store *)j->at[4];
    c->finish = (hrm__ns_half *)j->at[5];
    c->pieces = (hrm__piece_tab *)j->at[7];
    c->keep_layer = keep_layer;
    return hrm__setup(c, (hrm__tau *)j->at[0], (hrm__memo_tab *)j->at[1], (hrm__efit *)j->at[2], j->m, j->t0, t1,
                      &j->o, j->tr_only);
}

/* The ray cut where the medium scan's tau passed options.cutoff's: c set
   up again on [t0, t0 + c->cut_at], with what the scan found (its jumps,
   the layer's first panels and samples, its lookups) kept. A frame of its
   own, left before the solve runs. */
static HRM_DEVICE HRM__NOINLINE hrm_status hrm__cut_ray(hrm__job *j, hrm__ctx *c)
{
    hrm_real brk[HRM_MAX_BREAKS], jumps[HRM_MAX_JUMPS], t1 = c->t0 + c->cut_at;
    hrm_stats stats = c->stats;
    hrm_status warning = c->warning, st;
    int nbrk = c->nbrk, njumps = c->njumps, k;
    memcpy(brk, c->brk_off, sizeof brk);
    memcpy(jumps, c->jumps, sizeof jumps);
    /* the distance warp keeps its sigma_ref (its reach, marched again,
       would cost its lookups again, and clear what the scan taught the
       layer) */
    if (c->warp == HRM_WARP_DISTANCE) j->o.warp.sigma_ref = c->w_sigma;
    st = hrm__job_setup(j, c, t1, 1);
    if (st != HRM_OK) return st;
    /* the scan's breakpoints (the options' among them) inside the cut ray */
    for (k = 0, c->nbrk = 0; k < nbrk; ++k)
        if (brk[k] < c->off_end) c->brk_off[c->nbrk++] = brk[k];
    for (k = 0; k < njumps; ++k)
        if (jumps[k] < t1) c->jumps[c->njumps++] = jumps[k];
    c->stats = stats;
    c->stats.t_cut = t1;
    if (warning != HRM_OK) c->warning = warning;
    return HRM_OK;
}

/* A ray cut by options.cutoff before the equiangular warp's light foot: the
   source there, sampled once (one evaluation, one lookup), so that the
   remainder's estimate holds the light's peak, which the solve never came
   near (a light 1 from the ray 7 past t_cut: the estimate 2.1 times short of
   the remainder without it, 1.0e-5 against 2.1e-5; where Tr has a closed
   form the estimate took the mean S / sigma_t of the part solved alone: a
   light 0.0015 from the ray 1.2 past t_cut, 1.5e5 times short). A
   callback's bad value there leaves the solve's answer as it was. */
static HRM_DEVICE void hrm__cut_foot(hrm__ctx *c, hrm_real s)
{
    hrm_real sa[HRM__CH], ss[HRM__CH], st[HRM__CH], q[HRM__CH], keep[HRM__CH];
    memcpy(keep, c->src_max, sizeof keep);
    c->stats.medium_evals += hrm__coeffs_all(c, s, sa, ss, st);
    hrm__source(c, s, sa, ss, st, q);
    if (c->status != HRM_OK) {
        c->status = HRM_OK;
        memcpy(c->src_max, keep, sizeof keep);
    }
}

/* The solve itself, once its storage is held (c: its context, in the
   caller's workspace or the frame of hrm__solve_local). */
static HRM_DEVICE HRM__CALL HRM__NOINLINE hrm_status hrm__solve_job(hrm__job *j, hrm__ctx *c)
{
    const hrm_options *o = &j->o;
    hrm_real y[HRM__NY], t1 = j->t1;
    hrm_status st;
    int k, cut;

    st = hrm__job_setup(j, c, t1, 0);
    *j->stats = c->stats;
    if (st != HRM_OK) return st;
    if (j->t0 == t1) {
        if (hrm__is_adaptive(o->method)) hrm__fill(j->err, HRM__CH, 0);
        return st;
    }
    c->stats.t_cut = t1;
    if (j->estimator) {
        /* the shadow-ray estimator */
        if (j->at[8]) hrm__shadow_run(c, o, y, (hrm__panel *)j->at[8]);
        else hrm__shadow_march(c, o, y);
        *j->stats = c->stats;
        if (c->status != HRM_OK) return c->status;
        for (k = 0; k < HRM__CH; ++k) j->Tr[k] = HRM_EXP(-y[k]);
        return c->warning;
    }
    /* options.cutoff on sigma callbacks: the scan's trapezoid tau says
       where (a solve on the layer; the warp the one asked for, not a
       fallback) */
    if (o->cutoff > 0 && c->decoupled && !j->tr_only && c->warp == o->warp.kind && HRM__FINITE(t1))
        c->cut_tau = -HRM_LOG(o->cutoff);
    if (c->scan && !(c->closed && !c->decoupled && !c->use_le && !c->use_li)) hrm__scan_medium(c);
    if (c->status == HRM_OK && c->cut_at > 0) {
        st = hrm__cut_ray(j, c);
        if (st != HRM_OK) return st;
    }
    if (c->status != HRM_OK) {
        hrm__fill(y, HRM__NY, 0); /* a callback's bad output: the status says it */
    } else if (!c->use_le && !c->use_li && c->closed) {
        /* Nothing to integrate: Tr alone, from the layer or a closed form. */
        hrm__fill(y, HRM__NY, 0);
    } else {
        hrm__dispatch(c, o, y);
    }
    st = hrm__finish(c, o, y, j->L, j->Tr, j->err);
    cut = c->keep_layer || j->tr_end;
    if (cut && st >= 0 && o->warp.kind == HRM_WARP_EQUIANGULAR && o->warp.delta > c->t1 &&
        o->warp.delta < (j->tr_end ? j->t_end : j->t1) && c->status == HRM_OK)
        hrm__cut_foot(c, o->warp.delta);
    for (k = 0; k < HRM__CH && cut && st >= 0; ++k) {
        /* cut by options.cutoff: what lies past t_cut, estimated with the
           largest S / sigma_t the solve sampled (at least its mean, L /
           (1 - Tr)), over Tr(t0, t_cut) less the whole ray's (on sigma
           callbacks unknown: Tr at the cut, which bounds it) */
        hrm_real a = j->Tr[k], rem = 1 - a > 0 ? j->L[k] / (1 - a) : 0;
        rem = (c->src_max[k] > rem ? c->src_max[k] : rem) * (j->tr_end ? a - j->tr_end[k] : a);
        if (j->err[k] >= 0 && rem > 0) j->err[k] += rem;
    }
    *j->stats = c->stats;
    if (j->njumps && st >= 0) {
        *j->njumps = c->njumps;
        memcpy(j->jumps, c->jumps, sizeof c->jumps);
    }
    return st;
}

static HRM_DEVICE HRM__NOINLINE hrm_status hrm__solve_local(hrm__job *j)
{
    hrm__ctx c;
    return hrm__solve_job(j, &c);
}

/* The storage j needs, then the solve: all of it from the caller's
   workspace (in hrm__need_bytes' order, within what hrm__ws_bytes
   asked for: the needs are a part of hrm__may_need), else each in a
   frame of its own. */
static HRM_DEVICE hrm_status hrm__stage(hrm__job *j)
{
    int k;
    if (j->ws && j->need) {
        for (k = 0; k < HRM__NEEDS; ++k)
            if (j->need & (1u << k)) {
                j->at[k] = j->ws;
                if (k == 0) {
                    /* the layer's cache and table after it, whole */
                    hrm__tau *L = (hrm__tau *)j->ws;
                    L->cache = (hrm__tcoef *)(j->ws + HRM__TAU_HEAD);
                    L->ncache = HRM__TCACHE;
                    L->tab = (hrm__tpanel *)(j->ws + HRM__TAU_HEAD + HRM__TAU_CACHE_BYTES);
                    L->ntab = HRM_TAU_PANELS;
                    L->scan = (hrm__tscan *)(j->ws + sizeof(hrm__tau));
                    L->cp = (hrm__tcheck *)(j->ws + sizeof(hrm__tau) + sizeof(hrm__tscan));
                    L->cpcap = HRM__TCHECK;
                } else if (k == 2) {
                    /* the fits' matrices after them */
                    hrm__efit *ef = (hrm__efit *)j->ws;
                    ef[0].A = (hrm_real *)(j->ws + HRM__EFIT_HEAD);
                    ef[1].A = ef[0].A + HRM__EFIT_MAX * HRM__EFIT_MAX;
                    ef[0].cap = ef[1].cap = HRM__EFIT_MAX * HRM__EFIT_MAX;
                }
                j->ws += hrm__need_bytes(k);
            }
        j->need = 0;
    }
    if (j->need & HRM__NEED_LAYER)
        return hrm__methods[j->o.method].family == HRM__ADAPTIVE_QUAD ? hrm__with_layer(j)
             : hrm__methods[j->o.method].family == HRM__PAIR         ? hrm__with_layer_pair(j)
             : j->o.find_jumps == 1                                  ? hrm__with_layer_fixed_scan(j)
                                                                      : hrm__with_layer_fixed(j);
    if (j->need & HRM__NEED_MEMO) return hrm__with_memo(j);
    if (j->need & HRM__NEED_EFIT)
        return hrm__methods[j->o.method].driver == HRM__DRV_SIMPSON ? hrm__with_efit3(j)
             : hrm__methods[j->o.method].family == HRM__PAIR ? hrm__with_efit_pair(j)
                                                              : hrm__with_efit_gk(j);
    if (j->need & HRM__NEED_NS) return hrm__with_ns(j);
    if (j->need & HRM__NEED_GK) return hrm__with_gk(j);
    /* (HRM__NEED_FINISH and HRM__NEED_PIECES without a workspace:
       hrm__ns_local, hrm__solve_broken) */
    return j->at[6] ? hrm__solve_job(j, (hrm__ctx *)j->at[6]) : hrm__solve_local(j);
}

/* The one solve behind hrm_solve and hrm_transmittance (tr_only: no
   source, so only sigma_t is integrated). */
static HRM_DEVICE HRM__CALL hrm_status hrm__run(const hrm_medium *m, hrm_real t0, hrm_real t1,
                           const hrm_options *in, int tr_only, hrm_real L[HRM__CH],
                           hrm_real Tr[HRM__CH], hrm_real err[HRM__CH], hrm_stats *stats,
                           int *njumps, hrm_real *jumps, hrm_real t_end, const hrm_real *tr_end)
{
    hrm__job j;
    hrm_status st;

    memset(stats, 0, sizeof *stats);
    if (njumps) {
        *njumps = 0;
        hrm__fill(jumps, HRM_MAX_JUMPS, 0);
    }
    hrm__fill(L, HRM__CH, 0);
    hrm__fill(Tr, HRM__CH, 1);
    hrm__fill(err, HRM__CH, -1);
    memset(&j, 0, sizeof j);
    st = hrm__validate(m, t0, t1, in, tr_only, &j.o);
    if (st != HRM_OK) return st;
    j.m = m;
    j.t0 = t0;
    j.t1 = t1;
    j.tr_only = tr_only;
    /* Tr alone without a method named, where sigma_t must be integrated
       over a finite ray: the shadow-ray estimator (its own panels; an
       infinite ray goes the way of a named method, the layer's) */
    j.estimator = tr_only && (!in || in->method == HRM_METHOD_DEFAULT) && !(m->flags & HRM_MEDIUM_HOMOGENEOUS) &&
                  !m->transmittance && HRM__FINITE(t1);
    j.L = L;
    j.Tr = Tr;
    j.err = err;
    j.stats = stats;
    j.njumps = njumps;
    j.jumps = jumps;
    j.t_end = t_end;
    j.tr_end = tr_end;
    j.need = hrm__needs(m, &j.o, tr_only, j.estimator);
    j.ws = (unsigned char *)j.o.workspace;
    if (!j.ws) j.need &= ~(HRM__NEED_FINISH | HRM__NEED_CTX | HRM__NEED_PIECES | HRM__NEED_SHADOW);
    return hrm__stage(&j);
}

/* Early ray termination (options.cutoff, where Tr has a closed form):
   where every channel's Tr(t0, t) falls below the cut-off, into *t_cut
   (t1 where it does not, or without a closed form), and Tr(t0, t1) into
   tr_end. A homogeneous medium in closed form; a transmittance callback
   by bisection (20 calls and one for the whole ray, returned). A value
   that is not a number leaves the ray whole (the solve reports it). */
static HRM_DEVICE HRM__CALL long hrm__cut_point(const hrm_medium *m, hrm_real t0, hrm_real t1, hrm_real cutoff,
                           hrm_real *t_cut, hrm_real tr_end[HRM__CH])
{
    hrm_real tr[HRM__CH], lo = t0, hi = t1, mx, smin = HRM__R(HUGE_VAL);
    long calls = 0;
    int i, k;
    *t_cut = t1;
    if (m->flags & HRM_MEDIUM_HOMOGENEOUS) {
        for (i = 0; i < HRM__CH; ++i) {
            hrm_real st = m->const_sigma_a[i] + m->const_sigma_s[i];
            if (!(HRM__FINITE(st) && st >= 0)) return 0;
            if (st < smin) smin = st;
            tr_end[i] = HRM_EXP(-st * (t1 - t0));
        }
        if (smin > 0 && t0 + -HRM_LOG(cutoff) / smin < t1) *t_cut = t0 + -HRM_LOG(cutoff) / smin;
        return 0;
    }
    if (!m->transmittance || !HRM__FINITE(t1)) return 0;
    m->transmittance(m->user, t0, t1, tr_end);
    calls++;
    for (i = 0, mx = 0; i < HRM__CH; ++i) mx = tr_end[i] > mx || tr_end[i] != tr_end[i] ? tr_end[i] : mx;
    if (!(mx < cutoff)) return calls;
    for (k = 0; k < 20; ++k) {
        hrm_real mid = lo + (hi - lo) / 2;
        m->transmittance(m->user, t0, mid, tr);
        calls++;
        for (i = 0, mx = 0; i < HRM__CH; ++i) mx = tr[i] > mx || tr[i] != tr[i] ? tr[i] : mx;
        if (mx < cutoff) hi = mid;
        else if (mx >= cutoff) lo = mid;
        else return calls;
    }
    *t_cut = hi;
    return calls;
}

HRM__DEF HRM_DEVICE size_t hrm_workspace_size(const hrm_options *options)
{
    hrm_options o;
    hrm_options probe;
    if (options) {
        probe = *options;
        probe.workspace = NULL; /* its own size is what is asked */
        probe.workspace_size = 0;
        options = &probe;
    }
    return hrm__resolve(options, &o, 0) == HRM_OK ? hrm__ws_bytes(&o) : (size_t)0;
}

/* hrm_solve with options.cutoff, on valid input only (bad input is the
   solve's to report, before any callback): where every channel's Tr
   falls below the cut-off before t1, the ray solved up to there into *r
   (a list of breakpoints loses those beyond the cut) and its status into
   *st: 1; else 0, and the caller solves the whole ray. A frame of its own:
   the copies it makes cost a solve without a cut-off nothing. */
static HRM_DEVICE HRM__CALL HRM__NOINLINE int hrm__solve_cut(const hrm_medium *medium, hrm_real t0, hrm_real t1,
                                        const hrm_options *options, hrm_result *r, hrm_status *st)
{
    hrm_options o;
    hrm_real tc = t1, tr_end[HRM__CH], brk[HRM_MAX_BREAKS];
    long calls;
    int i, n = 0;
    if (hrm__validate(medium, t0, t1, options, 0, &o) != HRM_OK) return 0;
    calls = hrm__cut_point(medium, t0, t1, options->cutoff, &tc, tr_end);
    if (!(tc < t1 && tc > t0)) return 0;
    o = *options;
    for (i = 0; i < o.nbreaks; ++i)
        if (o.breaks[i] < tc) brk[n++] = o.breaks[i];
    o.breaks = n ? brk : NULL;
    o.nbreaks = n;
    /* (the remainder's estimate in the error: hrm__solve_job) */
    *st = hrm__run(medium, t0, tc, &o, 0, r->L, r->Tr, r->error, &r->stats, &r->njumps, r->jumps, t1, tr_end);
    r->stats.medium_evals += calls;
    if (*st >= 0) {
        memcpy(r->Tr, tr_end, sizeof r->Tr); /* Tr of the whole ray */
        r->stats.t_cut = tc;
    }
    return 1;
}

HRM__DEF HRM_DEVICE hrm_status hrm_solve(const hrm_medium *medium, hrm_real t0, hrm_real t1,
                              const hrm_options *options, hrm_result *result)
{
    hrm_result r;
    hrm_status st;
    if (!result) return HRM_ERR_NULL_ARGUMENT;
    if (!medium) {
        memset(result, 0, sizeof *result);
        hrm__fill(result->Tr, HRM__CH, 1);
        hrm__fill(result->error, HRM__CH, -1);
        return HRM_ERR_NULL_ARGUMENT;
    }
    /* Work on a local copy: result may alias nothing we read, and a failed
       solve leaves exactly the defined error result. */
    if (!(options && options->cutoff > 0 && options->cutoff <= 1 && HRM__FINITE(t0) && t1 > t0 &&
          hrm__solve_cut(medium, t0, t1, options, &r, &st)))
        st = hrm__run(medium, t0, t1, options, 0, r.L, r.Tr, r.error, &r.stats, &r.njumps, r.jumps, t1, NULL);
    *result = r;
    return st;
}

HRM__DEF HRM_DEVICE hrm_status hrm_transmittance(const hrm_medium *medium, hrm_real t0,
                                      hrm_real t1, const hrm_options *options,
                                      hrm_real Tr[HRM_CHANNELS], hrm_stats *stats)
{
    hrm_real L[HRM__CH], out[HRM__CH], err[HRM__CH];
    hrm_stats s;
    hrm_status st;
    if (!Tr) {
        if (stats) memset(stats, 0, sizeof *stats);
        return HRM_ERR_NULL_ARGUMENT;
    }
    if (!medium) {
        hrm__fill(Tr, HRM__CH, 1);
        if (stats) memset(stats, 0, sizeof *stats);
        return HRM_ERR_NULL_ARGUMENT;
    }
    st = hrm__run(medium, t0, t1, options, 1, L, out, err, &s, NULL, NULL, t1, NULL);
    memcpy(Tr, out, sizeof out);
    if (stats) *stats = s;
    return st;
}

#endif /* HRM__IMPLEMENTATION_DONE */
#endif /* HRM_IMPLEMENTATION */

/*
------------------------------------------------------------------------------
MIT License

Copyright (c) 2026 the hrm.h authors

Permission is hereby granted, free of charge, to any person obtaining a copy
of this software and associated documentation files (the "Software"), to deal
in the Software without restriction, including without limitation the rights
to use, copy, modify, merge, publish, distribute, sublicense, and/or sell
copies of the Software, and to permit persons to whom the Software is
furnished to do so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in
all copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
------------------------------------------------------------------------------
*/
