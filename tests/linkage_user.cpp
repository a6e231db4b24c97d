// C++ user of hrm.h, linked against the implementation compiled as C
// (linkage_impl.c): every call below crosses the extern "C" boundary.
#include "hrm.h"
#define HARNESS_IMPLEMENTATION // a single-file program: the tally lives here
#include "harness.h"

#include <cmath>
#include <cstring>

static void emit(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const double *le = static_cast<const double *>(user);
    (void)t;
    for (int c = 0; c < HRM_CHANNELS; ++c) out[c] = static_cast<hrm_real>(le[c]);
}

static void test_linkage()
{
    double le[HRM_CHANNELS];
    hrm_medium m;
    std::memset(&m, 0, sizeof m);
    m.user = le;
    m.flags = HRM_MEDIUM_HOMOGENEOUS;
    m.Le = emit;
    for (int c = 0; c < HRM_CHANNELS; ++c) {
        le[c] = 1.0 + c;
        m.const_sigma_a[c] = static_cast<hrm_real>(0.2 + 0.1 * c);
        m.const_sigma_s[c] = static_cast<hrm_real>(0.3);
    }
    hrm_options o = hrm_default_options(HRM_SIMPSON);
    o.steps = 64;
    hrm_result r;
    CHECK_INT(hrm_solve(&m, 0, 5, &o, &r), HRM_OK, "hrm_solve status");
    CHECK_INT(r.stats.evals, 129, "Simpson with 64 panels: 2N + 1 evaluations");
    for (int c = 0; c < HRM_CHANNELS; ++c) {
        double sa = 0.2 + 0.1 * c, st = sa + 0.3, T = 5;
        // L = Le sigma_a/sigma_t (1 - e^{-sigma_t T}). Simpson, H = 5/64: the
        // relative error is (H sigma_t)^4/2880 for this exponential integrand
        // (doubled for higher-order terms), plus round-off eps (N + 16)(1 + tau).
        double exact = le[c] * sa / st * -std::expm1(-st * T);
        double eps = sizeof(hrm_real) == sizeof(float) ? 1.2e-7 : 2.3e-16;
        double tol = 2 * std::pow(T / 64 * st, 4) / 2880 + eps * (64 + 16) * (1 + st * T);
        CHECK_REL(r.L[c], exact, tol, "channel %d: L against the closed form", c);
        CHECK_REL(r.Tr[c], std::exp(-st * T), 16 * eps * (1 + st * T),
                  "channel %d: Tr = exp(-sigma_t T)", c);
    }
    CHECK_INT(hrm_solve(nullptr, 0, 1, &o, &r), HRM_ERR_NULL_ARGUMENT, "medium NULL");
    const char *ok = hrm_status_string(HRM_OK);
    CHECK(ok != nullptr && std::strcmp(ok, "ok") == 0, "hrm_status_string(HRM_OK)");
    const char *bad = hrm_status_string(HRM_ERR_BAD_INTERVAL);
    CHECK(bad != nullptr && bad[0] != 0 && std::strcmp(bad, ok) != 0, "hrm_status_string(HRM_ERR_BAD_INTERVAL)");
    const char *name = hrm_method_name(HRM_RK4);
    CHECK(name != nullptr && std::strcmp(name, "rk4") == 0, "hrm_method_name(HRM_RK4)");
    CHECK(std::strcmp(hrm_method_name(static_cast<hrm_method>(999)), "?") == 0, "hrm_method_name(999)");
    CHECK_INT(hrm_version(), HRM_VERSION_MAJOR * 10000 + HRM_VERSION_MINOR * 100 + HRM_VERSION_PATCH,
              "hrm_version()");
}

int main()
{
    RUN_GROUP(test_linkage);
    return harness_summary();
}
