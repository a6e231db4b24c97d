/* gpu.cu - `make gpu`: hrm.h inside a CUDA kernel, one thread per pixel
   calling hrm_solve, against the same scene on every CPU thread.

   The scene: a camera inside heterogeneous fog (sigma through one
   callback, a smooth analytic density, albedo 0.8, slightly chromatic),
   a point light in it, a wall behind at z = 8 of constant radiance. Each
   camera ray takes the light's equiangular warp (hrm_equiangular_warp);
   Li is the light's intensity over r^2 through the fog's mean extinction,
   times an isotropic phase function (the host's shadow ray, kept cheap).
   The same __host__ __device__ code (HRM_DEVICE) sets up and solves a
   pixel on either side; the callbacks are functions of both sides, so a
   medium built in a kernel points at their device code.

   Methods: Simpson N = 32, nested Simpson, Gauss-Kronrod and
   Dormand-Prince at rtol 1e-3. Each GPU thread owns a slice of one device
   buffer as options.workspace (hrm_workspace_size bytes), so a solve's
   storage stays off the GPU stack; the grid is the device's resident
   threads (the occupancy API), each looping over pixels.

   Checks (exit status 1 if one fails): no solve returns an error; the
   fixed-step image matches the CPU's within 1e-12 relative per channel
   (double; 5e-4 with HRM_REAL=float), the adaptive images within an RMSE
   of 0.1 rtol relative to the CPU's (FMA contraction on the GPU may move
   an adaptive decision: the pixels whose evaluation counts differ are
   counted and printed).

   The stack: for each method the smallest cudaLimitStackSize, in 1 KiB
   steps, at which its image is the one rendered with a 64 KiB stack, bit
   for bit, with no launch error (the driver reserves the stack for every
   thread the device can hold: 64 KiB is 17 GB on an H100). A stack
   overflow is an illegal address that poisons the CUDA context, so each
   size is tried in a child process (this program run again with
   --probe). The timed runs use the largest of those minima (or --stack
   KiB, which skips the search).

   Prints Mray/s per method on the GPU and on all CPU threads
   (std::thread), the stack set and each method's least stack; writes
   OUT/gpu.png (each method's GPU image and the false-colour difference
   to the CPU's). Usage: gpu [--out DIR] [--size W H] [--stack KiB]
   [--no-workspace] (each solve's storage on the GPU stack) [--coupled]
   (options.tau_mode = HRM_TAU_COUPLED: tau from the sigma samples at the
   nodes, no transmittance layer) [--cpu-only] (the CPU's half alone, no
   CUDA call).

   Registers: ptxas gives the kernel about 220 a thread (8 warps an SM).
   Built with -DGPU_MIN_BLOCKS=8 the kernel asks for 8 blocks of 128 an
   SM (__launch_bounds__), which caps it at 64 registers (32 warps): the
   faster build for storage on the stack, which the hardware interleaves
   across a warp's threads; the slower one with a workspace, whose
   per-thread slices do not coalesce (README, "Inside a GPU kernel"). */
#define HRM_IMPLEMENTATION
#include "hrm.h"
#include "png.h"

#include <cuda_runtime.h>

#ifndef GPU_MIN_BLOCKS
#define GPU_MIN_BLOCKS 1 /* blocks of 128 an SM the kernel asks for */
#endif

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

/* the stack of the probes' reference image: with a workspace, and
   without (nested Simpson's and Gauss-Kronrod's storage on the stack) */
#define PROBE_STACK_KIB(s) ((s).workspace ? 64 : 192)

struct scene {
    double light[3], I; /* point light: position, intensity */
    double colour[HRM_CHANNELS]; /* the light's, relative */
    double sigma0;      /* extinction scale (1/length) */
    double albedo;
    double tint[HRM_CHANNELS]; /* extinction per channel relative */
    double wall_z, bg;  /* the wall behind and its radiance */
    double fov_tan;     /* tan of half the vertical field of view */
    int w, h;
    int workspace;      /* 1: each thread a workspace; 0: none (the stack) */
    int coupled;        /* 1: options.tau_mode = HRM_TAU_COUPLED */
};

struct method_cfg {
    hrm_method method;
    int steps;   /* fixed-step: N; 0 for the default */
    double rtol; /* adaptive; 0 for fixed-step */
    const char *label;
};

static const method_cfg methods[] = {
    {HRM_SIMPSON, 32, 0, "simpson N=32"},
    {HRM_NESTED_SIMPSON, 0, 1e-3, "nested simpson 1e-3"},
    {HRM_GAUSS_KRONROD, 0, 1e-3, "gauss-kronrod 1e-3"},
    {HRM_DORMAND_PRINCE, 0, 1e-3, "dormand-prince 1e-3"},
};
#define NMETHODS ((int)(sizeof methods / sizeof methods[0]))

/* The ray of one pixel, the callbacks' user data. */
struct ray_ctx {
    const scene *s;
    double o[3], d[3];
};

/* The fog's density at p: smooth, in [0.2, 1] times sigma0 (as smooth
   along a ray as the issue's probe: about 27 evaluations a ray at rtol
   1e-3). */
static HRM_DEVICE double density(const scene *s, const double p[3])
{
    return s->sigma0 * (0.6 + 0.4 * sin(1.3 * p[0] + 0.5) * sin(1.1 * p[1] + 0.2) * cos(0.9 * p[2]));
}

static HRM_DEVICE void fog_sigma(void *user, hrm_real t, hrm_real sa[HRM_CHANNELS], hrm_real ss[HRM_CHANNELS])
{
    const ray_ctx *r = (const ray_ctx *)user;
    double p[3], rho;
    int i;
    for (i = 0; i < 3; ++i) p[i] = r->o[i] + (double)t * r->d[i];
    rho = density(r->s, p);
    for (i = 0; i < HRM_CHANNELS; ++i) {
        double st = rho * r->s->tint[i];
        sa[i] = (hrm_real)((1 - r->s->albedo) * st);
        ss[i] = (hrm_real)(r->s->albedo * st);
    }
}

/* In-scattered radiance toward the camera: the light through an
   extinction of 0.6 sigma0 a channel, isotropic phase. */
static HRM_DEVICE void fog_li(void *user, hrm_real t, hrm_real out[HRM_CHANNELS])
{
    const ray_ctx *r = (const ray_ctx *)user;
    const scene *s = r->s;
    double r2 = 0;
    int i;
    for (i = 0; i < 3; ++i) {
        double v = s->light[i] - (r->o[i] + (double)t * r->d[i]);
        r2 += v * v;
    }
    for (i = 0; i < HRM_CHANNELS; ++i)
        out[i] = (hrm_real)(s->I * s->colour[i] * exp(-0.6 * s->sigma0 * s->tint[i] * sqrt(r2)) / r2 /
                            (4 * 3.14159265358979));
}

/* One pixel, on either side: the camera at the origin looking along +z,
   the ray to the wall solved with the light's warp; rgb = L + Tr bg. */
static HRM_DEVICE hrm_status solve_pixel(const scene *s, const method_cfg *m, long pix, void *ws,
                                         size_t ws_bytes, hrm_real rgb[HRM_CHANNELS], long *evals)
{
    int x = (int)(pix % s->w), y = (int)(pix / s->w), i;
    double u = (2 * (x + 0.5) / s->w - 1) * s->fov_tan * s->w / s->h;
    double v = (1 - 2 * (y + 0.5) / s->h) * s->fov_tan;
    double len = sqrt(u * u + v * v + 1);
    ray_ctx r;
    hrm_medium fog;
    hrm_options opt;
    hrm_result res;
    hrm_real o[3] = {0, 0, 0}, d[3], light[3];
    hrm_status st;
    r.s = s;
    r.d[0] = u / len;
    r.d[1] = v / len;
    r.d[2] = 1 / len;
    for (i = 0; i < 3; ++i) {
        r.o[i] = 0;
        d[i] = (hrm_real)r.d[i];
        light[i] = (hrm_real)s->light[i];
    }
    memset(&fog, 0, sizeof fog);
    fog.user = &r;
    fog.sigma = fog_sigma;
    fog.Li = fog_li;
    opt = hrm_default_options(m->method);
    if (m->steps > 0) opt.steps = m->steps;
    if (m->rtol > 0) opt.rtol = (hrm_real)m->rtol;
    if (hrm_equiangular_warp(o, d, light, &opt.warp) != HRM_OK) opt.warp.kind = HRM_WARP_NONE;
    if (s->coupled) opt.tau_mode = HRM_TAU_COUPLED;
    opt.workspace = ws_bytes > 0 ? ws : NULL;
    opt.workspace_size = ws_bytes;
    st = hrm_solve(&fog, 0, (hrm_real)(s->wall_z / r.d[2]), &opt, &res);
    for (i = 0; i < HRM_CHANNELS; ++i) rgb[i] = res.L[i] + res.Tr[i] * (hrm_real)s->bg;
    *evals = res.stats.evals;
    return st;
}

/* One thread's pixels: every nthreads-th from its index, its workspace
   the ws_bytes from ws + id ws_bytes. */
__global__ void __launch_bounds__(128, GPU_MIN_BLOCKS) render_kernel(scene s, method_cfg m, unsigned char *ws, size_t ws_bytes, hrm_real *img,
                              long *evals, int *status)
{
    long id = (long)blockIdx.x * blockDim.x + threadIdx.x, n = (long)gridDim.x * blockDim.x;
    long npix = (long)s.w * s.h, p;
    void *mine = ws + (size_t)id * ws_bytes;
    for (p = id; p < npix; p += n) status[p] = (int)solve_pixel(&s, &m, p, mine, ws_bytes, img + p * HRM_CHANNELS, &evals[p]);
}

/* A rendered image and its per-pixel evaluations and statuses. */
struct image {
    std::vector<hrm_real> rgb;
    std::vector<long> evals;
    std::vector<int> status;
    double seconds;
};

static size_t ws_size(const scene &s, const method_cfg *m)
{
    hrm_options opt = hrm_default_options(m->method);
    if (m->steps > 0) opt.steps = m->steps;
    if (m->rtol > 0) opt.rtol = (hrm_real)m->rtol;
    opt.warp.kind = HRM_WARP_EQUIANGULAR;
    opt.warp.D = 1;
    if (s.coupled) opt.tau_mode = HRM_TAU_COUPLED;
    return s.workspace ? hrm_workspace_size(&opt) : 0;
}

static int cuda_ok(cudaError_t e, const char *what)
{
    if (e == cudaSuccess) return 1;
    std::fprintf(stderr, "gpu: %s: %s\n", what, cudaGetErrorString(e));
    return 0;
}

/* Renders on the GPU with a per-thread stack of stack_kib; the second of
   two launches is timed. 0 on a CUDA error. */
static int render_gpu(const scene &s, const method_cfg &m, int stack_kib, image *out, size_t *ws_total)
{
    long npix = (long)s.w * s.h;
    size_t wsb = ws_size(s, &m), total;
    int dev = 0, sms = 0, per_sm = 0, block = 128, grid, k;
    unsigned char *ws = NULL;
    hrm_real *img = NULL;
    long *ev = NULL;
    int *st = NULL, ok = 0;
    cudaEvent_t e0, e1;
    float ms = 0;
    if (!cuda_ok(cudaDeviceSetLimit(cudaLimitStackSize, (size_t)stack_kib * 1024), "cudaLimitStackSize") ||
        !cuda_ok(cudaGetDevice(&dev), "cudaGetDevice") ||
        !cuda_ok(cudaDeviceGetAttribute(&sms, cudaDevAttrMultiProcessorCount, dev), "attribute") ||
        !cuda_ok(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, render_kernel, block, 0), "occupancy"))
        return 0;
    grid = sms * (per_sm > 0 ? per_sm : 1);
    if ((long)grid * block > npix) grid = (int)((npix + block - 1) / block);
    total = (size_t)grid * block * wsb;
    if (ws_total) *ws_total = total;
    if (!cuda_ok(cudaMalloc(&ws, total > 0 ? total : 16), "cudaMalloc workspace") ||
        !cuda_ok(cudaMalloc(&img, sizeof(hrm_real) * HRM_CHANNELS * (size_t)npix), "cudaMalloc image") ||
        !cuda_ok(cudaMalloc(&ev, sizeof(long) * (size_t)npix), "cudaMalloc evals") ||
        !cuda_ok(cudaMalloc(&st, sizeof(int) * (size_t)npix), "cudaMalloc status"))
        goto done;
    cudaEventCreate(&e0);
    cudaEventCreate(&e1);
    for (k = 0; k < 2; ++k) {
        cudaEventRecord(e0);
        render_kernel<<<grid, block>>>(s, m, ws, wsb, img, ev, st);
        cudaEventRecord(e1);
        if (!cuda_ok(cudaGetLastError(), "launch") || !cuda_ok(cudaEventSynchronize(e1), "kernel")) goto done;
    }
    cudaEventElapsedTime(&ms, e0, e1);
    out->seconds = ms * 1e-3;
    out->rgb.resize((size_t)npix * HRM_CHANNELS);
    out->evals.resize((size_t)npix);
    out->status.resize((size_t)npix);
    ok = cuda_ok(cudaMemcpy(out->rgb.data(), img, sizeof(hrm_real) * out->rgb.size(), cudaMemcpyDeviceToHost), "copy") &&
         cuda_ok(cudaMemcpy(out->evals.data(), ev, sizeof(long) * out->evals.size(), cudaMemcpyDeviceToHost), "copy") &&
         cuda_ok(cudaMemcpy(out->status.data(), st, sizeof(int) * out->status.size(), cudaMemcpyDeviceToHost), "copy");
done:
    cudaFree(ws);
    cudaFree(img);
    cudaFree(ev);
    cudaFree(st);
    return ok;
}

/* The same image on every CPU thread, each with its own workspace. */
static void render_cpu(const scene &s, const method_cfg &m, image *out)
{
    long npix = (long)s.w * s.h;
    unsigned nt = std::thread::hardware_concurrency(), t;
    size_t wsb = ws_size(s, &m);
    std::vector<std::thread> pool;
    std::vector<unsigned char> mem((size_t)(nt ? nt : 1) * (wsb + 16) + 16);
    if (nt == 0) nt = 1;
    out->rgb.assign((size_t)npix * HRM_CHANNELS, 0);
    out->evals.assign((size_t)npix, 0);
    out->status.assign((size_t)npix, 0);
    auto t0 = std::chrono::steady_clock::now();
    for (t = 0; t < nt; ++t)
        pool.emplace_back([&, t]() {
            unsigned char *base = mem.data() + (size_t)t * (wsb + 16);
            void *ws = base + (16 - (uintptr_t)base % 16) % 16;
            for (long p = t; p < npix; p += nt)
                out->status[(size_t)p] = (int)solve_pixel(&s, &m, p, ws, wsb, &out->rgb[(size_t)p * HRM_CHANNELS],
                                                          &out->evals[(size_t)p]);
        });
    for (auto &th : pool) th.join();
    out->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/* FNV-1a over the image's bytes, its evaluations and statuses. */
static unsigned long long image_hash(const image &im)
{
    unsigned long long h = 1469598103934665603ULL;
    const unsigned char *b[3] = {(const unsigned char *)im.rgb.data(), (const unsigned char *)im.evals.data(),
                                 (const unsigned char *)im.status.data()};
    size_t n[3] = {im.rgb.size() * sizeof(hrm_real), im.evals.size() * sizeof(long), im.status.size() * sizeof(int)};
    for (int k = 0; k < 3; ++k)
        for (size_t i = 0; i < n[k]; ++i) h = (h ^ b[k][i]) * 1099511628211ULL;
    return h;
}

/* The child of the stack search: renders method m with stack kib and
   writes "ok HASH" or "fail" to path. */
static int probe(const scene &s, int m, int kib, const char *path)
{
    image im;
    FILE *f;
    int ok = render_gpu(s, methods[m], kib, &im, NULL);
    if (!(f = std::fopen(path, "w"))) return 2;
    if (ok) std::fprintf(f, "ok %llu\n", image_hash(im));
    else std::fprintf(f, "fail\n");
    std::fclose(f);
    return ok ? 0 : 1;
}

/* Runs the probe child for method m at kib; its hash, or 0 on failure. */
static unsigned long long run_probe(const char *self, const scene &s, int m, int kib, const char *dir)
{
    char cmd[4096], path[2048], word[16] = "";
    unsigned long long h = 0;
    FILE *f;
    std::snprintf(path, sizeof path, "%s/probe.txt", dir);
    std::remove(path);
    std::snprintf(cmd, sizeof cmd, "\"%s\" --size %d %d%s%s --probe %d %d \"%s\" 2>/dev/null", self, s.w, s.h,
                  s.workspace ? "" : " --no-workspace", s.coupled ? " --coupled" : "", m, kib, path);
    if (std::system(cmd) == -1) return 0;
    if (!(f = std::fopen(path, "r"))) return 0;
    if (std::fscanf(f, "%15s %llu", word, &h) != 2 || std::strcmp(word, "ok") != 0) h = 0;
    std::fclose(f);
    return h;
}

/* The smallest stack (KiB) at which method m renders the image of the
   PROBE_STACK_KIB stack: a bisection, a stack that suffices staying
   sufficient. -1 if even PROBE_STACK_KIB fails. */
static int least_stack(const char *self, const scene &s, int m, const char *dir)
{
    unsigned long long ref = run_probe(self, s, m, PROBE_STACK_KIB(s), dir);
    int lo = 0, hi = PROBE_STACK_KIB(s); /* lo fails (or is 0), hi renders the reference */
    if (ref == 0) return -1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (run_probe(self, s, m, mid, dir) == ref) hi = mid;
        else lo = mid;
    }
    return hi;
}

/* A tone-mapped 8-bit copy of an image. */
static void to_image8(const scene &s, const image &im, image8 *out)
{
    for (long p = 0; p < (long)s.w * s.h; ++p)
        for (int c = 0; c < 3; ++c) {
            double x = (double)im.rgb[(size_t)p * HRM_CHANNELS + (size_t)(c < HRM_CHANNELS ? c : 0)];
            out->px[3 * p + c] = (unsigned char)(255 * std::pow(x / (1 + x), 1 / 2.2) + 0.5);
        }
}

/* --cpu-only: the CPU's half alone (no CUDA call), each method's Mray/s,
   evaluations a ray and statuses; 1 if a solve fails. */
static int cpu_report(const scene &s)
{
    long npix = (long)s.w * s.h;
    int fail = 0;
    std::printf("%d x %d pixels on %u CPU threads\n", s.w, s.h, std::thread::hardware_concurrency());
    for (int m = 0; m < NMETHODS; ++m) {
        image c;
        long ev = 0, warn = 0, err = 0;
        double sum = 0;
        render_cpu(s, methods[m], &c);
        for (long p = 0; p < npix; ++p) {
            ev += c.evals[(size_t)p];
            warn += c.status[(size_t)p] > 0;
            err += c.status[(size_t)p] < 0;
            sum += (double)c.rgb[(size_t)p * HRM_CHANNELS];
        }
        fail |= err > 0;
        std::printf("%-20s %8.3f Mray/s %8.1f evals/ray, workspace %6zu bytes, mean pixel %.6f, %ld warnings, %ld errors\n",
                    methods[m].label, npix / c.seconds * 1e-6, (double)ev / npix, ws_size(s, &methods[m]), sum / npix,
                    warn, err);
    }
    return fail;
}

int main(int argc, char **argv)
{
    scene s = {{0.4, 0.5, 4.0}, 20.0, {0}, 0.35, 0.8, {0}, 8.0, 0.05, 0.6, 1024, 1024, 1, 0};
    const char *outdir = "build/gpu", *self = argv[0];
    int stack = -1, least[NMETHODS], fail = 0, ndev = 0, cpu_only = 0, i, m;
    double fixed_bound = sizeof(hrm_real) == sizeof(float) ? 5e-4 : 1e-12;
    image8 sheet;
    unsigned char white[3] = {255, 255, 255};
    char path[2048];
    cudaDeviceProp prop;
    for (i = 0; i < HRM_CHANNELS; ++i) { /* a warm light; blue scattered the most */
        double x = HRM_CHANNELS > 1 ? (double)i / (HRM_CHANNELS - 1) : 0;
        s.colour[i] = 1 - 0.45 * x;
        s.tint[i] = 0.7 + 0.3 * x;
    }
    for (i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--out") && i + 1 < argc) outdir = argv[++i];
        else if (!std::strcmp(argv[i], "--size") && i + 2 < argc) {
            s.w = std::atoi(argv[++i]);
            s.h = std::atoi(argv[++i]);
        } else if (!std::strcmp(argv[i], "--stack") && i + 1 < argc) stack = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--cpu-only")) cpu_only = 1;
        else if (!std::strcmp(argv[i], "--no-workspace")) s.workspace = 0;
        else if (!std::strcmp(argv[i], "--coupled")) s.coupled = 1;
        else if (!std::strcmp(argv[i], "--probe") && i + 3 < argc)
            return probe(s, std::atoi(argv[i + 1]), std::atoi(argv[i + 2]), argv[i + 3]);
        else {
            std::fprintf(stderr, "usage: %s [--out DIR] [--size W H] [--stack KiB] [--no-workspace] [--coupled] [--cpu-only]\n", argv[0]);
            return 2;
        }
    }
    if (s.w < 1 || s.h < 1) return 2;
    if (cpu_only) return cpu_report(s);
    if (cudaGetDeviceCount(&ndev) != cudaSuccess || ndev == 0) {
        std::printf("gpu: no CUDA device here; nothing run (the build is what make test checks)\n");
        return 0;
    }
    std::snprintf(path, sizeof path, "%s/probe.txt", outdir);
    {
        FILE *f = std::fopen(path, "w");
        if (!f) {
            std::printf("gpu: cannot write in %s (--out DIR: an existing directory)\n", outdir);
            return 1;
        }
        std::fclose(f);
    }
    cudaGetDeviceProperties(&prop, 0);
    std::printf("gpu: %s, %d SMs; CPU: %u threads; %d x %d pixels, hrm_real %s, %d channels\n", prop.name,
                prop.multiProcessorCount, std::thread::hardware_concurrency(), s.w, s.h,
                sizeof(hrm_real) == sizeof(float) ? "float" : "double", HRM_CHANNELS);
    std::printf("gpu: storage %s, tau %s, kernel built for %d blocks of 128 an SM (GPU_MIN_BLOCKS)\n",
                s.workspace ? "in a workspace a thread" : "on the stack", s.coupled ? "coupled" : "by default",
                GPU_MIN_BLOCKS);

    /* the least stack of each method, each size in a child process */
    if (stack < 0) {
        stack = 1;
        for (m = 0; m < NMETHODS; ++m) {
            least[m] = least_stack(self, s, m, outdir);
            if (least[m] < 0) {
                std::printf("stack: %-20s fails even at %d KiB\n", methods[m].label, PROBE_STACK_KIB(s));
                fail = 1;
                continue;
            }
            if (least[m] > stack) stack = least[m];
        }
        for (m = 0; m < NMETHODS; ++m)
            if (least[m] > 0)
                std::printf("stack: %-20s least cudaLimitStackSize %3d KiB (target %d)\n", methods[m].label,
                            least[m], methods[m].rtol > 0 ? 32 : 8);
    }
    std::printf("stack: cudaLimitStackSize set to %d KiB per thread\n\n", stack);

    if (!image8_alloc(&sheet, 2 * s.w + 3 * 8, NMETHODS * (s.h + 24) + 8)) return 1;
    image8_fill(&sheet, 24, 24, 24);
    std::printf("%-20s %9s %9s %7s %8s %10s %10s  %s\n", "method", "GPU Mray/s", "CPU Mray/s", "ratio",
                "evals/ray", "workspace", "GPU vs CPU", "pixels with other evals, warnings");
    for (m = 0; m < NMETHODS; ++m) {
        const method_cfg &mc = methods[m];
        image g, c;
        size_t ws_total = 0;
        long npix = (long)s.w * s.h, differ = 0, warn = 0, err = 0, ev = 0;
        double num = 0, den = 0, worst = 0, diff;
        int pass;
        image8 gi = {0, 0, NULL}, di = {0, 0, NULL};
        if (!render_gpu(s, mc, stack, &g, &ws_total)) {
            std::printf("%-20s GPU render failed\n", mc.label);
            fail = 1;
            continue;
        }
        render_cpu(s, mc, &c);
        for (long p = 0; p < npix; ++p) {
            differ += g.evals[(size_t)p] != c.evals[(size_t)p];
            ev += g.evals[(size_t)p];
            warn += g.status[(size_t)p] > 0;
            err += g.status[(size_t)p] < 0 || c.status[(size_t)p] < 0;
            for (int ch = 0; ch < HRM_CHANNELS; ++ch) {
                double a = (double)g.rgb[(size_t)p * HRM_CHANNELS + ch], b = (double)c.rgb[(size_t)p * HRM_CHANNELS + ch];
                num += (a - b) * (a - b);
                den += b * b;
                if (std::fabs(a - b) > worst * std::fabs(b)) worst = std::fabs(a - b) / std::fabs(b);
            }
        }
        diff = mc.rtol > 0 ? std::sqrt(num / den) : worst;
        pass = err == 0 && (mc.rtol > 0 ? diff <= 0.1 * mc.rtol : diff <= fixed_bound);
        fail |= !pass;
        std::printf("%-20s %9.2f %9.2f %6.1fx %8.1f %7.0f MiB %10.2e  %ld, %ld%s%s\n", mc.label, npix / g.seconds * 1e-6,
                    npix / c.seconds * 1e-6, c.seconds / g.seconds, (double)ev / npix, ws_total / 1048576.0, diff,
                    differ, warn, err ? " ERRORS" : "", pass ? "" : "  FAILED");

        /* the sheet: the GPU's image, then |GPU - CPU| / CPU in false colour */
        if (image8_alloc(&gi, s.w, s.h) && image8_alloc(&di, s.w, s.h)) {
            to_image8(s, g, &gi);
            for (long p = 0; p < npix; ++p) {
                double a = (double)g.rgb[(size_t)p * HRM_CHANNELS], b = (double)c.rgb[(size_t)p * HRM_CHANNELS];
                double e = std::fabs(a - b) / (std::fabs(b) > 0 ? std::fabs(b) : 1);
                /* 1e-16 black .. 1e-2 white, logarithmic */
                false_colour(e > 0 ? (std::log10(e) + 16) / 14 : 0, &di.px[3 * p]);
            }
            image8_blit(&sheet, &gi, 8, m * (s.h + 24) + 24);
            image8_blit(&sheet, &di, s.w + 16, m * (s.h + 24) + 24);
            draw_text(&sheet, 8, m * (s.h + 24) + 8, mc.label, 2, white);
        }
        image8_free(&gi);
        image8_free(&di);
    }
    std::snprintf(path, sizeof path, "%s/probe.txt", outdir);
    std::remove(path);
    std::snprintf(path, sizeof path, "%s/gpu.png", outdir);
    if (!png_write(path, &sheet)) {
        std::printf("gpu: could not write %s\n", path);
        fail = 1;
    } else {
        std::printf("\nwrote %s (GPU image | relative difference to the CPU's, 1e-16 black .. 1e-2 white)\n", path);
    }
    image8_free(&sheet);
    std::printf("%s\n", fail ? "gpu: FAILED" : "gpu: ok");
    return fail;
}
