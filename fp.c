#define HRM_IMPLEMENTATION
#include <stdio.h>
#include "hrm.h"
#include <stdio.h>
#include <stdlib.h>
#include <math.h>
static double sigt(double s, int c) { return 0.6 * (1 + 0.3 * sin(0.3 * s + c)); }
static void sa(void *u, hrm_real t, hrm_real o[HRM_CHANNELS]) { int c; (void)u; for (c=0;c<HRM_CHANNELS;++c) o[c]=(hrm_real)(sigt((double)t,c)/6); }
static void ss(void *u, hrm_real t, hrm_real o[HRM_CHANNELS]) { int c; (void)u; for (c=0;c<HRM_CHANNELS;++c) o[c]=(hrm_real)(sigt((double)t,c)*5/6); }
static void li(void *u, hrm_real t, hrm_real o[HRM_CHANNELS]) { int c; if (getenv("TR")) fprintf(stderr,"%.4f ",(double)t); double x=(double)t-5; (void)u; for (c=0;c<HRM_CHANNELS;++c) o[c]=(hrm_real)(1/(0.04+x*x)); }
int main(int argc, char **argv) {
  hrm_real brk[2] = {(hrm_real)2.7, (hrm_real)6.1}; int m = atoi(argv[1]); double rtol = atof(argv[2]); int nb = atoi(argv[3]);
  hrm_medium md; hrm_options o = hrm_default_options((hrm_method)m); hrm_result r; hrm_status st;
  memset(&md,0,sizeof md); md.sigma_a=sa; md.sigma_s=ss; md.Li=li;
  o.rtol=(hrm_real)rtol; o.warp.kind=HRM_WARP_DISTANCE; if (nb) { o.breaks=brk; o.nbreaks=2; }
  st = hrm_solve(&md,0,10,&o,&r);
  printf("st %d L %.6g err %.3g evals %ld steps %ld\n", st, (double)r.L[0], (double)r.error[0], r.stats.evals, r.stats.steps);
}
