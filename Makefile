# hrm.h - build, test and benchmark.
#   make test    the compile matrix (gcc/clang, C99/C++, double/float, 1/3/8 channels,
#                -O0/-O2, ASan+UBSan, HRM_STATIC, C/C++ linkage), each run
#                of the test suite; the fuzz corpus replayed; threads (also
#                under TSan) and heap allocations (tests/threads.c); ending
#                with the line "N passed, N failed"
#   make check   the test suite in one configuration (cc -O2, double, 3
#                channels): the quick tier while working, about 15 s on 2
#                cores; make test (the matrix) is what CI runs
#   make bench   the single-ray convergence benchmark, the shadow-ray
#                benchmark (bench/shadow.c) and the silent-answer sweep
#                (bench/sweep.c): tables on the terminal, files
#                in bench/out/ only (ignored by git)
#   make bench-quick   the same over short ranges (bench/out/quick/)
#   make bench-snapshot   make bench, then refresh the committed snapshot
#                bench/results/ (summary.md, timing.md, shadow.md, sweep.md,
#                the figures but time.svg) from bench/out/; run it on
#                request, and commit
#   make fuzz    the libFuzzer harness tests/fuzz.c (clang, ASan, UBSan), run
#                for FUZZ_TIME seconds (default 60) from the seed corpus
#                tests/corpus/; findings in build/fuzz/crashes/ (needs clang's
#                libFuzzer: Debian package libfuzzer-14-dev where missing)
#   make render  the renderer-level comparison (examples/render.c): four
#                scenes, an independent reference each, the production
#                marches and hrm's configurations over ladders of budgets,
#                costs at equal RMSE; sheets and summary.md in render/out/
#                only (ignored by git)
#   make render-quick   the same at a quarter of the pixels (render/out/quick/)
#   make render-snapshot   make render, then refresh the committed snapshot
#                examples/results/ (the overview sheets and summary.md); on
#                request, then commit
#   make examples
#   make gpu     examples/gpu.cu (nvcc, sm_90 and sm_75): a fog and a point
#                light rendered by hrm_solve in a CUDA kernel, one thread a
#                pixel, against all CPU threads (Mray/s, the images compared,
#                each method's least per-thread stack) where a GPU is; one
#                line and success without nvcc or a GPU. make test compiles
#                it wherever nvcc is found (make gpu-build)
CC      ?= cc
WARN    = -Wall -Wextra -pedantic -Werror -Wshadow -Wdouble-promotion
BUILD   = build

.PHONY: all test check bench bench-quick bench-snapshot render render-quick render-snapshot examples gpu gpu-build fuzz clean

all: test

test:
	@sh tests/run.sh

CHECK_SRC = tests/main.c tests/common.c tests/test_tables.c tests/test_fixed.c \
            tests/test_adaptive.c tests/test_warp.c tests/test_transmittance.c \
            tests/test_breaks.c tests/test_exponential.c tests/test_extremes.c \
            tests/test_bad_input.c

$(BUILD)/check: $(CHECK_SRC) tests/common.h tests/harness.h hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. $(CHECK_SRC) -o $@ -lm

check: $(BUILD)/check
	./$(BUILD)/check

# The benchmark: measurement, reporting, figures and the command line, with
# the scenes, the reference quadrature and the SVG writer (bench/README.md).
BENCH_SRC = bench/main.c bench/measure.c bench/report.c bench/figures.c bench/qag.c \
            bench/scenes.c bench/reference.c bench/svg.c
BENCH_HDR = bench/bench.h bench/scenes.h bench/reference.h bench/svg.h bench/qag.h

$(BUILD)/bench: $(BENCH_SRC) $(BENCH_HDR) hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. $(BENCH_SRC) -o $@ -lm

# bench/out/ is the run's output (ignored by git): make bench writes nothing
# else. bench/results/ is the committed snapshot that the READMEs link to,
# refreshed only by make bench-snapshot: summary.md and the figures are the
# same on every run of the same build; timing.md is one machine's timings.
# time.svg (error vs time) stays out of it.
# shadow rays (bench/shadow.c): hrm_transmittance's lookups for an
# accuracy of Tr against hand marches and ratio tracking, bench/out/shadow.md
$(BUILD)/bench_shadow: bench/shadow.c hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. bench/shadow.c -o $@ -lm

# silent answers and false alarms in random scenes (bench/sweep.c):
# thick fog past a point light, hrm_light_options' lights and spheres, and
# an Li whose slope jumps
$(BUILD)/bench_sweep: bench/sweep.c hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. bench/sweep.c -o $@ -lm

bench: $(BUILD)/bench $(BUILD)/bench_shadow $(BUILD)/bench_sweep
	./$(BUILD)/bench --out bench/out
	./$(BUILD)/bench_shadow bench/out
	./$(BUILD)/bench_sweep bench/out

bench-quick: $(BUILD)/bench
	./$(BUILD)/bench --quick --out bench/out/quick

bench-snapshot: bench
	@mkdir -p bench/results
	rm -f bench/results/*.svg bench/results/*.md
	cp bench/out/summary.md bench/out/timing.md bench/out/shadow.md bench/out/sweep.md bench/results/
	for f in bench/out/*.svg; do \
	    case $$f in */time.svg) ;; *) cp $$f bench/results/ ;; esac; \
	done

FUZZ_TIME ?= 60
$(BUILD)/fuzz/fuzz: tests/fuzz.c hrm.h
	@mkdir -p $(BUILD)/fuzz
	clang -std=c99 -O1 -g $(WARN) -I. -DFUZZ_LIBFUZZER -fsanitize=fuzzer,address,undefined \
	    -fno-sanitize-recover=all tests/fuzz.c -o $@ -lm

# the working corpus (build/fuzz/corpus) starts from the committed seeds;
# a crash found is a file in build/fuzz/crashes/: fix its cause, then commit
# it to tests/corpus/, which make test replays
fuzz: $(BUILD)/fuzz/fuzz
	@mkdir -p $(BUILD)/fuzz/corpus $(BUILD)/fuzz/crashes
	cp tests/corpus/* $(BUILD)/fuzz/corpus/
	cd $(BUILD)/fuzz && ./fuzz -max_total_time=$(FUZZ_TIME) -artifact_prefix=crashes/ corpus

$(BUILD)/example_ray: examples/ray.c hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. examples/ray.c -o $@ -lm

$(BUILD)/example_render: examples/render.c examples/png.h hrm.h
	@mkdir -p $(BUILD)
	$(CC) -std=c99 -O2 $(WARN) -I. examples/render.c -o $@ -lm -pthread

# render/out/ is the run's output (ignored by git); examples/results/ the
# committed snapshot the README shows, refreshed only by make render-snapshot.
render: $(BUILD)/example_render
	@mkdir -p render/out
	./$(BUILD)/example_render render/out

render-quick: $(BUILD)/example_render
	@mkdir -p render/out/quick
	./$(BUILD)/example_render render/out/quick all quick

render-snapshot: render
	@mkdir -p examples/results
	cp render/out/shafts_overview.png render/out/cloud_overview.png \
	    render/out/smoke_overview.png render/out/lamps_overview.png \
	    render/out/summary.md examples/results/

examples: $(BUILD)/example_ray $(BUILD)/example_render

# The CUDA example: nvcc from $CUDA_HOME/bin, else from PATH. Two
# architectures (Hopper, and Turing: the oldest CUDA 13 keeps), both
# compiled at once; warnings as errors, nvcc's and the host compiler's.
NVCC ?= $(or $(if $(CUDA_HOME),$(wildcard $(CUDA_HOME)/bin/nvcc)),$(shell command -v nvcc 2>/dev/null))
GPU_ARCH = -gencode arch=compute_90,code=sm_90 -gencode arch=compute_75,code=sm_75
NVFLAGS = -O2 --threads 2 -Werror all-warnings -Xcompiler -Wall,-Wextra,-Werror

$(BUILD)/example_gpu: examples/gpu.cu examples/png.h hrm.h
	@mkdir -p $(BUILD)
	$(NVCC) $(NVFLAGS) $(GPU_ARCH) -I. examples/gpu.cu -o $@

gpu-build:
	@if [ -z "$(NVCC)" ]; then \
	    echo "gpu: skipped, no nvcc (neither \$$CUDA_HOME/bin/nvcc nor nvcc on PATH)"; \
	else $(MAKE) --no-print-directory $(BUILD)/example_gpu; fi

# build/gpu/ holds its picture (gpu.png) and the stack search's scratch file
gpu: gpu-build
	@if [ -n "$(NVCC)" ]; then mkdir -p $(BUILD)/gpu && ./$(BUILD)/example_gpu --out $(BUILD)/gpu; fi

clean:
	rm -rf $(BUILD)
