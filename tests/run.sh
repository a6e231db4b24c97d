#!/bin/sh
# The compile matrix of `make test`: every configuration builds the test
# suite with warnings as errors and runs it; the last line sums them all.
set -u
cd "$(dirname "$0")/.." || exit 2
B=build/test
mkdir -p "$B"
WARN="-Wall -Wextra -pedantic -Werror -Wshadow -Wdouble-promotion"
pass=0
fail=0
configs=0

# The test program: several translation units, each including hrm.h; only
# test_tables.c compiles the implementation (every file with HRM_STATIC).
SRCS="tests/main.c tests/common.c tests/test_tables.c tests/test_fixed.c tests/test_adaptive.c tests/test_warp.c tests/test_transmittance.c tests/test_breaks.c tests/test_exponential.c tests/test_extremes.c tests/test_bad_input.c"

# build NAME COMPILER FLAGS... : compile each file of the test program to
# an object, all at once (they are independent; the configurations still
# run one after the other), then link them into $B/NAME. Diagnostics go to
# $B/NAME.log. "-x none" ends a "-x c++" among the flags before the objects.
build() {
    name=$1
    shift
    objs=$B/$name.objs
    rm -rf "$objs"
    mkdir -p "$objs"
    pids=
    for src in $SRCS; do
        obj=$objs/$(basename "$src" .c).o
        "$@" -I. -c "$src" -o "$obj" 2> "$obj.log" &
        pids="$pids $!"
    done
    ok=1
    for pid in $pids; do wait "$pid" || ok=0; done
    cat "$objs"/*.log > "$B/$name.log"
    [ $ok -eq 1 ] && "$@" -x none "$objs"/*.o -o "$B/$name" -lm 2>> "$B/$name.log"
}

# run NAME COMPILER FLAGS... : build the test program and start it; it
# runs while the next configuration builds (two cores: one compiles, one
# tests), and finish adds it up before the next one starts
pending_pid=
pending_name=
run() {
    name=$1
    configs=$((configs + 1))
    if ! build "$@"; then
        finish
        echo "$name: build failed"; cat "$B/$name.log"; fail=$((fail + 1)); return
    fi
    finish
    "$B/$name" > "$B/$name.out" 2>&1 &
    pending_pid=$!
    pending_name=$name
}

# finish: wait for the test program run started, and add it up
finish() {
    [ -n "$pending_pid" ] || return 0
    wait "$pending_pid"
    code=$?
    pending_pid=
    tally_out "$pending_name" "$code" "$B/$pending_name.out"
}

# tally NAME BINARY [ARGS...]: run it, add its "N passed, N failed" line to the sums
tally() {
    tname=$1
    shift
    "$@" > "$B/$tname.out" 2>&1
    tally_out "$tname" $? "$B/$tname.out"
}

# tally_out NAME EXIT_CODE OUTPUT_FILE: the sums from a program's output
tally_out() {
    tname=$1
    code=$2
    out=$(cat "$3")
    line=$(printf '%s\n' "$out" | grep -E '^[0-9]+ passed, [0-9]+ failed' | tail -n 1)
    if [ -z "$line" ] || [ $code -ne 0 ]; then
        printf '%s\n' "$out" | grep -E 'FAIL|error|runtime|ThreadSanitizer' | head -n 40
        echo "$tname: exit $code, summary '${line}'"
    fi
    if [ -z "$line" ]; then fail=$((fail + 1)); return; fi
    p=${line%% passed*}
    f=${line#*passed, }; f=${f%% failed*}
    if [ $code -ne 0 ] && [ "$f" -eq 0 ]; then f=1; fi
    pass=$((pass + p)); fail=$((fail + f))
    echo "$tname: $line"
}

run gcc-c99-O0          gcc   -std=c99 -O0 $WARN
run gcc-c99-O2          gcc   -std=c99 -O2 $WARN
run gcc-c99-O2-float    gcc   -std=c99 -O2 $WARN -DHRM_REAL=float
run gcc-c99-O0-float    gcc   -std=c99 -O0 $WARN -DHRM_REAL=float
run clang-c99-O0        clang -std=c99 -O0 $WARN
run clang-c99-O2        clang -std=c99 -O2 $WARN
run clang-c99-O2-float  clang -std=c99 -O2 $WARN -DHRM_REAL=float
run gxx-O2              g++     -x c++ -std=c++11 -O2 $WARN
run clangxx-O0-float    clang++ -x c++ -std=c++11 -O0 $WARN -DHRM_REAL=float
# HRM_STATIC, with the shadow-ray estimator at its least storage (16 panels).
run gcc-static-O2-shadow16 gcc -std=c99 -O2 $WARN -DHRM_STATIC -DHRM_SHADOW_PANELS=16
run clang-asan-ubsan    clang -std=c99 -O1 -g $WARN -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# Channel counts other than the default 3 (the tests loop over HRM_CHANNELS).
run gcc-c99-O2-ch1      gcc   -std=c99 -O2 $WARN -DHRM_CHANNELS=1
run gcc-c99-O2-ch1-float gcc  -std=c99 -O2 $WARN -DHRM_CHANNELS=1 -DHRM_REAL=float
run clang-c99-O2-ch8    clang -std=c99 -O2 $WARN -DHRM_CHANNELS=8
finish

# The CUDA example (examples/gpu.cu) compiled by nvcc where the Makefile
# finds it ($CUDA_HOME/bin, else PATH), for sm_90 and sm_75, warnings as
# errors: every function of hrm.h on the device, its tables on both sides.
# make gpu runs it where a GPU is. It builds in the background while the
# single-threaded checks below run, and is added up at the end.
gstart=$(date +%s)
rm -f build/example_gpu
( make --no-print-directory -s gpu-build > "$B/gpu.log" 2>&1; echo $? > "$B/gpu.rc"; date +%s > "$B/gpu.end" ) &
gpu_pid=$!

# Stack use (tests/stack.c): each method's largest stack over its forms, warps,
# fits, Gauss-Kronrod modes and rules, breakpoints and media, on a painted
# thread stack, within STACK_LIMIT (twice it with a shadow ray solved in Li).
# Built and run one after the other in the background too (they measure
# stack, not time), added up at the end.
# stackprog NAME COMPILER FLAGS...: build tests/stack.c with them and run
# it, its output in $B/NAME.out and its exit status in $B/NAME.rc ("build"
# where it did not build)
stackprog() {
    sname=$1
    shift
    if "$@" -I. tests/stack.c -o "$B/$sname" -lm -pthread 2> "$B/$sname.log"; then
        "$B/$sname" > "$B/$sname.out" 2>&1
        echo $? > "$B/$sname.rc"
    else
        echo build > "$B/$sname.rc"
    fi
}
STACKPROGS="stack-gcc-O2 stack-gcc-O2-float stack-clang-O2-ch8"
(
    stackprog stack-gcc-O2          gcc   -std=c99 -O2 $WARN
    stackprog stack-gcc-O2-float    gcc   -std=c99 -O2 $WARN -DHRM_REAL=float
    stackprog stack-clang-O2-ch8    clang -std=c99 -O2 $WARN -DHRM_CHANNELS=8
) &
stack_pid=$!

# Implementation compiled as C, used from C++: the extern "C" linkage pair.
configs=$((configs + 1))
if gcc -std=c99 -O2 $WARN -I. -c tests/linkage_impl.c -o "$B/linkage_impl.o" 2> "$B/linkage.log" &&
   g++ -std=c++11 -O2 $WARN -I. tests/linkage_user.cpp "$B/linkage_impl.o" -o "$B/linkage" -lm 2>> "$B/linkage.log"; then
    tally linkage-c-impl-cxx-user "$B/linkage"
else
    echo "linkage: build failed"; cat "$B/linkage.log"; fail=$((fail + 1))
fi

# The fuzz harness without libFuzzer: every input of the seed corpus and
# every regression case committed there (make fuzz explains) replayed
# against the manual's promises.
configs=$((configs + 1))
if gcc -std=c99 -O2 $WARN -I. tests/fuzz.c -o "$B/fuzz-replay" -lm 2> "$B/fuzz-replay.log"; then
    tally fuzz-corpus-replay "$B/fuzz-replay" tests/corpus/*
else
    echo "fuzz-replay: build failed"; cat "$B/fuzz-replay.log"; fail=$((fail + 1))
fi

# Threads and memory (tests/threads.c): the same solves on 4 threads and
# serially, bit for bit, also under ThreadSanitizer.
# prog NAME COMPILER FLAGS...: build tests/threads.c with them and run it
prog() {
    pname=$1
    shift
    configs=$((configs + 1))
    if "$@" -I. -Itests tests/threads.c -o "$B/$pname" -lm 2> "$B/$pname.log"; then
        tally "$pname" "$B/$pname"
    else
        echo "$pname: build failed"; cat "$B/$pname.log"; fail=$((fail + 1))
    fi
}
prog threads-gcc-O2       gcc   -std=c99 -O2 $WARN -pthread
prog threads-clang-tsan   clang -std=c99 -O1 -g $WARN -fsanitize=thread -pthread

# No heap use (tests/alloc.c): every method x form x warp x fit x medium,
# the other options, nested shadow rays, every error path and every public
# function, one call at a time, with the four allocator functions wrapped.
configs=$((configs + 1))
if gcc -std=c99 -O2 $WARN -I. -Itests tests/alloc.c -o "$B/alloc" \
       -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free -lm 2> "$B/alloc.log"; then
    tally alloc-gcc-O2 "$B/alloc"
else
    echo "alloc: build failed"; cat "$B/alloc.log"; fail=$((fail + 1))
fi

# The quick start in hrm.h's top comment is the README's, and compiles and
# runs as printed: as C, as C++, in float and with one channel.
configs=$((configs + 1))
sed -n '/---- quick start begin ----/,/---- quick start end ----/p' hrm.h |
    sed '1d;$d' | sed 's/^   //' > "$B/quickstart.c"
sed -n '/^## Quick start/,/^## /p' README.md | sed -n '/^```c$/,/^```$/p' | sed '1d;$d' > "$B/quickstart_readme.c"
if cmp -s "$B/quickstart.c" "$B/quickstart_readme.c"; then
    pass=$((pass + 1))
else
    echo "quickstart: the README's differs from the manual's"; diff "$B/quickstart.c" "$B/quickstart_readme.c" | head -20
    fail=$((fail + 1))
fi
for qs in "gcc -std=c99" "g++ -x c++ -std=c++11" "gcc -std=c99 -DHRM_REAL=float" "gcc -std=c99 -DHRM_CHANNELS=1"; do
    if $qs -O2 $WARN -I. "$B/quickstart.c" -o "$B/quickstart" -lm 2> "$B/quickstart.log" &&
       "$B/quickstart" > "$B/quickstart.out" && grep -q "^ok, " "$B/quickstart.out"; then
        pass=$((pass + 1)); echo "quickstart ($qs): $(tail -1 "$B/quickstart.out")"
    else
        echo "quickstart ($qs): FAILED"; cat "$B/quickstart.log" "$B/quickstart.out"; fail=$((fail + 1))
    fi
done

# Configuration limits (CONFIGURATION in the manual): the extremes of each
# range compile, a value past one does not (a static assertion, not a stack
# overflow at run time).
configs=$((configs + 1))
lim_ok=0
lim_bad=0
for d in "-DHRM_CHANNELS=1" "-DHRM_CHANNELS=64" "-DHRM_MAX_BREAKS=1024" "-DHRM_MAX_JUMPS=1" \
         "-DHRM_NS_INTERVALS=8 -DHRM_NS_PANELS=8" "-DHRM_GK_INTERVALS=8 -DHRM_GK_INITIAL=8" \
         "-DHRM_TAU_PANELS=16" "-DHRM_MAX_DEPTH=8" "-DHRM_SHADOW_PANELS=16"; do
    if gcc -std=c99 $WARN $d -fsyntax-only -x c -DHRM_IMPLEMENTATION hrm.h 2> "$B/limits.log"; then
        lim_ok=$((lim_ok + 1))
    else
        echo "limits: $d does not compile"; cat "$B/limits.log"
    fi
done
for d in "-DHRM_CHANNELS=0" "-DHRM_CHANNELS=1024" "-DHRM_MAX_BREAKS=0" "-DHRM_MAX_JUMPS=257" \
         "-DHRM_MAX_LIGHTS=0" "-DHRM_NS_PANELS=65" "-DHRM_GK_INITIAL=129" "-DHRM_TAU_PANELS=8" \
         "-DHRM_MAX_DEPTH=201" "-DHRM_SHADOW_PANELS=8"; do
    if gcc -std=c99 $WARN $d -fsyntax-only -x c -DHRM_IMPLEMENTATION hrm.h 2> "$B/limits.log"; then
        echo "limits: $d compiles"
    elif grep -q "hrm__assert_" "$B/limits.log"; then
        lim_bad=$((lim_bad + 1))
    else
        echo "limits: $d fails otherwise than by its static assertion"; head -5 "$B/limits.log"
    fi
done
if [ "$lim_ok" -eq 9 ] && [ "$lim_bad" -eq 10 ]; then
    pass=$((pass + 1)); echo "limits: 9 extremes compile, 10 values past them stop at their static assertion"
else
    fail=$((fail + 1))
fi

# The implementation under the stricter warnings: every implicit conversion
# that may change a value (-Wconversion, -Wsign-conversion; float and
# double, gcc and clang) and duplicate enum values (clang).
configs=$((configs + 1))
conv_ok=0
for cc in gcc clang; do
    for r in "" "-DHRM_REAL=float"; do
        if $cc -std=c99 $WARN -Wconversion -Wsign-conversion $r -fsyntax-only -x c -DHRM_IMPLEMENTATION hrm.h \
               2> "$B/conversion.log"; then
            conv_ok=$((conv_ok + 1))
        else
            echo "conversion: $cc $r"; head -20 "$B/conversion.log"
        fi
    done
done
if clang -std=c99 $WARN -Wduplicate-enum -fsyntax-only -x c -DHRM_IMPLEMENTATION hrm.h 2> "$B/conversion.log"; then
    conv_ok=$((conv_ok + 1))
else
    echo "conversion: clang -Wduplicate-enum"; head -20 "$B/conversion.log"
fi
if [ "$conv_ok" -eq 5 ]; then
    pass=$((pass + 1)); echo "conversion: -Wconversion -Wsign-conversion clean (gcc, clang; double, float), -Wduplicate-enum clean"
else
    fail=$((fail + 1))
fi

# The manual (hrm.h's top comment, its closing line included) is a reference
# of at most 300 lines besides its quick start program and its BAD INPUT
# section; the long form lives in bench/README.md ("Design notes").
configs=$((configs + 1))
man=$(awk '
    /^\*\// { print n + 1; exit }
    /---- quick start begin ----/ { skip = 1 }
    /^   BAD INPUT$/ { skip = 2; n-- }
    skip == 2 && /^   =====/ && body { skip = 0 }
    skip == 2 && !/^   =====/ && !/^   BAD INPUT$/ { body = 1 }
    !skip { n++ }
    /---- quick start end ----/ { skip = 0 }
' hrm.h)
if [ "$man" -le 300 ] && [ "$man" -ge 100 ]; then
    pass=$((pass + 1)); echo "manual: $man lines besides the quick start and BAD INPUT (at most 300)"
else
    echo "manual: $man lines besides the quick start and BAD INPUT (at most 300)"; fail=$((fail + 1))
fi

# The examples build with warnings as errors (make render and the per-ray
# example run them; here they only have to compile).
configs=$((configs + 1))
if gcc -std=c99 -O2 $WARN -I. examples/ray.c -o "$B/example_ray" -lm 2> "$B/examples.log" &&
   gcc -std=c99 -O2 $WARN -I. examples/render.c -o "$B/example_render" -lm -pthread 2>> "$B/examples.log"; then
    pass=$((pass + 1)); echo "examples: ray.c and render.c compile"
else
    echo "examples: build FAILED"; cat "$B/examples.log"; fail=$((fail + 1))
fi

wait "$stack_pid"
for sname in $STACKPROGS; do
    configs=$((configs + 1))
    if [ "$(cat "$B/$sname.rc")" = build ]; then
        echo "$sname: build failed"; cat "$B/$sname.log"; fail=$((fail + 1))
    else
        tally_out "$sname" "$(cat "$B/$sname.rc")" "$B/$sname.out"
    fi
done

wait "$gpu_pid"
if [ "$(cat "$B/gpu.rc")" -eq 0 ]; then
    if grep -q "^gpu: skipped" "$B/gpu.log"; then
        cat "$B/gpu.log"
    elif [ -x build/example_gpu ]; then
        configs=$((configs + 1)); pass=$((pass + 1))
        echo "gpu: examples/gpu.cu compiled by nvcc (sm_90, sm_75) in $(( $(cat "$B/gpu.end") - gstart )) s"
    else
        configs=$((configs + 1)); fail=$((fail + 1)); echo "gpu: no binary"; cat "$B/gpu.log"
    fi
else
    configs=$((configs + 1)); fail=$((fail + 1)); echo "gpu: nvcc build FAILED"; cat "$B/gpu.log"
fi

echo "$configs configurations"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
