# manylods - build, test and demo.
#
#   make demo        build and run examples/instant_radiosity on its built-in
#                    scene; writes its images into build/demo/
#   make docs-images regenerate the pictures the README shows (docs/*.png)
#   make test        first tests/deps.sh (installs the Debian packages the tests
#                    need when run as root, else stops with the apt-get line),
#                    then every test: gcc -O2, clang with ASan+UBSan and the
#                    threaded ones with TSan, the compile matrix, examples/minimal
#                    and every example on a tiny scene (tests/check_examples.c),
#                    every examples/*.c compiled as C++11 (tests/compile/examples_cxx.sh),
#                    bench --selftest, README.md's benchmark figures against
#                    docs/ (tests/check_readme_figures.sh), the Vulkan tests; ends with
#                    "N passed, M failed".  Each program has a time limit,
#                    600 s times a factor tests/run.sh measures on a slow or
#                    busy machine (or TEST_TIMEOUT_FACTOR=F, given)
#   make test-only   the same tests without the package check
#   make test-fast   only the tests built with gcc -O2
#   make tsan        only the threaded tests under ThreadSanitizer (TSAN_TESTS)
#   make matrix      only the compile matrix (tests/compile/matrix.sh)
#   make fuzz        tests/deps.sh, then every libFuzzer harness
#                    fuzz/fuzz_NAME.c (make fuzz-only: without the package
#                    check; clang's libFuzzer is libclang-rt-14-dev): replays each
#                    fuzz/crashes/NAME/, then fuzzes each on a copy of
#                    fuzz/corpus/NAME/ for its share of FUZZ_SECONDS (60 in
#                    all); ends with "N passed, M failed" counting harnesses
#   make fuzz-corpus regenerate fuzz/corpus/pipeline/ with fuzz/make_corpus.c
#   make bench       tests/deps.sh, then the benchmark (bench/bench.c, needs
#                    Embree 3: Debian's libembree-dev); prints its tables and writes
#                    docs/BENCHMARKS.md, docs/bench.csv, docs/bench.svg,
#                    docs/views.svg, docs/bench_figures.txt; then rewrites
#                    README.md's benchmark block from them (as make readme-figures)
#   make bench-quick a smaller sweep, written under build/bench/
#   make readme-figures
#                    README.md's benchmark block (between its bench:begin and
#                    bench:end markers) from docs/bench_figures.txt, without a run
#   make clean       remove build/
#
# CC, CXX, CLANG and CLANGXX may be overridden (make test CC=gcc-13).  V=1
# shows the compiler command lines.  Everything built lands under build/.

ifeq ($(origin CC),default)
CC = gcc
endif
ifeq ($(origin CXX),default)
CXX = g++
endif
CLANG ?= clang
CLANGXX ?= clang++
export CC CXX CLANG CLANGXX

BUILD    := build
WARNINGS := -Wall -Wextra -pedantic
CFLAGS   ?=
LDLIBS   := -lm -pthread
TEST_CFLAGS := -std=c99 -O2 $(WARNINGS) -I. $(CFLAGS)
SAN_CFLAGS  := -std=c99 -fsanitize=address,undefined -fno-sanitize-recover=all -g -O1 \
               -fno-omit-frame-pointer $(WARNINGS) -I. $(CFLAGS)
# ThreadSanitizer: the tests that run the built-in thread pool.  (Add
# test_extremes to TSAN_TESTS for the extremes table: clean, but 2.5
# minutes under TSan on two cores, so `make test` leaves it out.)
TSAN_TESTS  ?= test_build test_cut test_refit test_splat test_megaviews
TSAN_CFLAGS := -std=c99 -fsanitize=thread -g -O1 $(WARNINGS) -I. $(CFLAGS)
# libFuzzer with ASan and UBSan.  No comparison tracing (trace-cmp): it
# tripled the time per input, and the harness reads its fields through
# modular arithmetic that comparison hints do not help with.
FUZZ_SECONDS ?= 60
FUZZ_HARNESSES := $(patsubst fuzz/fuzz_%.c,%,$(sort $(wildcard fuzz/fuzz_*.c)))
FUZZ_PROGRAMS  := $(FUZZ_HARNESSES:%=$(BUILD)/fuzz/fuzz_%)
# Every harness links the Vulkan loader where there is one (the Vulkan
# harness needs it; without it that harness fails to build and counts failed).
FUZZ_LDLIBS     = -lm -pthread $(if $(filter 1,$(HAVE_VULKAN)),$(VULKAN_LIBS))
FUZZ_CFLAGS  := -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
                -fno-sanitize-coverage=trace-cmp $(WARNINGS) -I. $(CFLAGS)
EXAMPLE_CFLAGS := -std=c99 -O2 $(WARNINGS) $(CFLAGS)
DEMO_DEFINES ?= -DMANYLODS_PTHREADS
# The benchmark: portable -O2 (no -march=native), Embree for the reference.
BENCH_OPT    := -std=c99 -O2
BENCH_CFLAGS := $(BENCH_OPT) $(WARNINGS) $(CFLAGS) -DBENCH_FLAGS='"$(BENCH_OPT)"' \
                -DBENCH_VK_HEADER='"$(CURDIR)/manylods_vk.h"' \
                -DBENCH_EXAMPLES='"$(abspath $(BUILD)/examples)"'
BENCH_LDLIBS := -lembree3 -lm -pthread
# bench/bench.c includes its protocol files (one translation unit): they are
# prerequisites here, not programs of their own.
BENCH_DEPS   := bench/bench.c bench/protocol_single.c bench/protocol_targets.c bench/protocol_vulkan.c \
                bench/protocol_sweep.c bench/protocol_views.c bench/report.c bench/cut_avx2.c \
                $(wildcard bench/*.h) manylods.h examples/scenes.h examples/meshio.h examples/sampling_summary.h
# On x86-64 the bench also links a second copy of the library built with
# -mavx2 -mfma (bench/cut_avx2.c) and reports its cut beside this build's.
BENCH_AVX2   := $(if $(findstring x86_64,$(shell $(CC) -dumpmachine 2>/dev/null)),1)
BENCH_EXTRA  = $(if $(BENCH_AVX2),-DBENCH_AVX2 $(BUILD)/bench/cut_avx2.o)
# Test programs build in parallel: with the caller's -jN if given, else on
# every core.
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
PARALLEL = $(if $(findstring jobserver,$(MAKEFLAGS)),,-j$(JOBS))

# tests/test_vulkan.c, tests/test_f64_vulkan.c and tests/test_lookup_vulkan.c
# link the Vulkan loader: built by their own rules below.
TEST_SOURCES := $(filter-out tests/test_vulkan.c tests/test_f64_vulkan.c tests/test_lookup_vulkan.c,$(sort $(wildcard tests/test_*.c)))
TEST_NAMES   := $(TEST_SOURCES:tests/%.c=%)
GCC_TESTS    := $(TEST_NAMES:%=$(BUILD)/gcc/%)
SAN_TESTS    := $(TEST_NAMES:%=$(BUILD)/san/%)
TSAN_PROGRAMS := $(TSAN_TESTS:%=$(BUILD)/tsan/%)
# ThreadSanitizer runs test_megaviews' and test_cut's groups that use
# threads (their other groups run single-threaded, in the gcc and sanitizer
# builds: under TSan they checked nothing more, and took 16 of test_cut's
# 26 s there).  test_cut's pools: skip, one_view, threads.
TSAN_ARGS_test_megaviews := threads groups
TSAN_ARGS_test_cut := skip one_view threads
# The sanitizer builds of the tests that run for a second or so, without
# optimisation: clang took 12-14 s on each at -O1 (the implementation,
# instrumented), 2.5-3.5 s at -O0, and each runs in under 5 s; -O0 checks
# every access, as -O1 does or more.
SAN_O0_TESTS := test_app test_errors test_overflow test_sample
TSAN_RUN := $(foreach t,$(TSAN_TESTS),$(if $(TSAN_ARGS_$(t)),--args "$(TSAN_ARGS_$(t))") $(BUILD)/tsan/$(t))
HEADERS      := manylods.h $(wildcard tests/*.h) $(wildcard examples/*.h) shaders/f64.glsl

# LeakSanitizer on, and a readable report from UBSan.
export ASAN_OPTIONS ?= detect_leaks=1:abort_on_error=0
export UBSAN_OPTIONS ?= print_stacktrace=1
# A data race ends the program at once (exit status 66), which counts as a failure.
export TSAN_OPTIONS ?= halt_on_error=1

ifeq ($(V),1)
Q :=
say = @true
else
Q := @
say = @printf '  %-6s %s\n'
endif

# The Vulkan companion: its test needs the Vulkan headers and loader
# (Debian: libvulkan-dev) at build time, a device (mesa-vulkan-drivers) and
# the validation layer (vulkan-validationlayers) at run time, which
# tests/deps.sh brings; without them the Vulkan tests fail.  Only
# MANYLODS_REQUIRE_VULKAN=0, given by hand, turns that into a skip that
# counts nothing (SKIP in the report, never a pass).
export MANYLODS_REQUIRE_VULKAN ?= 1
VULKAN_LIBS ?= -lvulkan
HAVE_VULKAN := $(shell printf '\043include <vulkan/vulkan.h>\nint main(void) { return 0; }\n' | \
                 $(CC) -x c - $(VULKAN_LIBS) -o /dev/null 2>/dev/null && echo 1)
ifeq ($(HAVE_VULKAN),1)
# make bench adds the Vulkan path (on lavapipe) next to the CPU's
BENCH_CFLAGS += -DBENCH_VULKAN
BENCH_LDLIBS += $(VULKAN_LIBS)
BENCH_DEPS   += manylods_vk.h
# test_vulkan's two groups as two programs side by side, the one with
# emulated doubles first (lavapipe compiles its shaders for minutes); so
# test_lookup_vulkan's two forms
VULKAN_TEST := --args emulated $(BUILD)/vulkan/test_vulkan --args native $(BUILD)/vulkan/test_vulkan \
               --args emulated $(BUILD)/vulkan/test_lookup_vulkan $(BUILD)/vulkan/test_f64_vulkan \
               --args native $(BUILD)/vulkan/test_lookup_vulkan tests/check_vulkan_example.sh
VULKAN_PROGRAMS := $(BUILD)/vulkan/test_vulkan $(BUILD)/vulkan/test_f64_vulkan $(BUILD)/vulkan/test_lookup_vulkan \
                   $(BUILD)/examples/vulkan_minimal
else
VULKAN_TEST := tests/vulkan_missing.sh
VULKAN_PROGRAMS :=
endif

.PHONY: all demo test test-only fuzz-only test-fast tsan matrix fuzz fuzz-corpus bench bench-quick clean test-programs fast-programs \
        shaders vulkan vulkan-minimal docs-images readme-figures
.DELETE_ON_ERROR:

# The examples that show the paper's applications (examples/*.c with app.h).
EXAMPLES := $(BUILD)/examples/instant_radiosity $(BUILD)/examples/point_based_gi $(BUILD)/examples/reflections
EXAMPLE_DEPS := $(HEADERS) bench/metrics.h

all: $(EXAMPLES) $(BUILD)/examples/minimal

demo: $(BUILD)/examples/instant_radiosity
	$(Q)$(BUILD)/examples/instant_radiosity --out $(BUILD)/demo

# The README's pictures: each example's default run, the images it shows
# copied into docs/ (the large atlas and mosaic stay in build/docs-images/).
DOCS_IMAGES := instant_radiosity.png instant_radiosity_compare.png instant_radiosity_maps.png \
               point_based_gi.png point_based_gi_indirect.png reflections_compare.png
docs-images: $(EXAMPLES)
	$(Q)$(BUILD)/examples/instant_radiosity --out $(BUILD)/docs-images
	$(Q)$(BUILD)/examples/point_based_gi --out $(BUILD)/docs-images
	$(Q)$(BUILD)/examples/reflections --out $(BUILD)/docs-images
	$(Q)cp $(addprefix $(BUILD)/docs-images/,$(DOCS_IMAGES)) docs/

# First what the tests need (tests/deps.sh: installs the missing Debian
# packages as root, else stops with the apt-get line), then, in a new make
# that sees them, the tests.
test:
	$(Q)tests/deps.sh
	$(Q)$(MAKE) --no-print-directory test-only

# The tests without the check of packages.  Build what can be built (-k),
# then let tests/run.sh count a program that did not build as a failure: the
# last line is always the total.
# The programs start in this order, as many at once as there are processors
# (tests/run.sh), the longest first: Vulkan on lavapipe, then the matrix.
# run.sh is make's own child (exec, not under a shell that a ^C ends at
# once): GNU make 4.3, interrupted while its child dies of the same
# signal, reaps that child twice and stops with "wait: No child
# processes"; run.sh stops its programs first, then exits.
test-only:
	-$(Q)$(MAKE) --no-print-directory -s -k $(PARALLEL) test-programs
	$(Q)exec tests/run.sh \
	    --section "Vulkan (manylods_vk.h against the CPU, validation layer on; shaders/ against the embedded SPIR-V)" \
	    $(VULKAN_TEST) tests/check_shaders.sh tests/check_twins.sh tests/compile/vulkan.sh \
	    --section "compile matrix" tests/compile/matrix.sh \
	    --section "tests, $(CC) -O2" $(GCC_TESTS) \
	    --section "tests, $(CLANG) -fsanitize=address,undefined -O1" $(SAN_TESTS) \
	    --section "threaded tests, $(CLANG) -fsanitize=thread -O1" $(TSAN_RUN) \
	    --section "examples (each on a tiny scene: runs, valid PNGs, accuracy; each compiled as C++11)" \
	    --check $(BUILD)/examples/minimal $(BUILD)/examples/check_examples tests/compile/examples_cxx.sh \
	    --section "benchmark (bench --selftest: compiles, checks cuts and metrics against Embree)" \
	    --check $(BUILD)/bench/selftest \
	    --section "README.md's benchmark figures (its block against docs/bench_figures.txt, docs/BENCHMARKS.md; none outside it)" \
	    tests/check_readme_figures.sh

# The Vulkan tests alone.
vulkan: $(VULKAN_PROGRAMS)
	$(Q)exec tests/run.sh --section "Vulkan" $(VULKAN_TEST) tests/check_shaders.sh tests/check_twins.sh tests/compile/vulkan.sh

# examples/vulkan_minimal: the cut and splat on a Vulkan device, the atlas as a PNG.
vulkan-minimal: $(BUILD)/examples/vulkan_minimal
	$(Q)$(BUILD)/examples/vulkan_minimal $(BUILD)/vulkan_atlas.png

$(BUILD)/examples/vulkan_minimal: examples/vulkan_minimal.c manylods.h manylods_vk.h examples/png.h examples/progress.h \
                                  examples/scenes.h
	$(say) CC $@
	$(Q)mkdir -p $(@D)
	$(Q)$(CC) $(EXAMPLE_CFLAGS) $< -o $@ $(VULKAN_LIBS) $(LDLIBS)

# Compile shaders/*.comp and embed the SPIR-V in manylods_vk.h (glslang-tools, spirv-tools).
shaders:
	$(Q)shaders/embed.sh

$(BUILD)/vulkan/test_vulkan: tests/test_vulkan.c manylods_vk.h $(HEADERS)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(TEST_CFLAGS) $< -o $@ $(VULKAN_LIBS) $(LDLIBS)

# shaders/f64.glsl on the device (it compiles tests/f64_check.comp when run).
$(BUILD)/vulkan/test_f64_vulkan: tests/test_f64_vulkan.c manylods_vk.h $(HEADERS)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(TEST_CFLAGS) $< -o $@ $(VULKAN_LIBS) $(LDLIBS)

# shaders/lookup.glsl on the device against mlod_atlas_lookup and
# mlod_atlas_shadow (it compiles tests/lookup_check.comp when run).
$(BUILD)/vulkan/test_lookup_vulkan: tests/test_lookup_vulkan.c manylods_vk.h $(HEADERS)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(TEST_CFLAGS) $< -o $@ $(VULKAN_LIBS) $(LDLIBS)

test-fast:
	-$(Q)$(MAKE) --no-print-directory -s -k $(PARALLEL) fast-programs
	$(Q)exec tests/run.sh --section "tests, $(CC) -O2" $(GCC_TESTS)

tsan:
	-$(Q)$(MAKE) --no-print-directory -s -k $(PARALLEL) $(TSAN_PROGRAMS)
	$(Q)exec tests/run.sh --section "threaded tests, $(CLANG) -fsanitize=thread -O1" $(TSAN_RUN)

matrix:
	$(Q)tests/compile/matrix.sh

# Not part of `make test` (it takes FUZZ_SECONDS); .ci/run calls it.  Every
# fuzz/fuzz_NAME.c is a harness (seeds in fuzz/corpus/NAME/, regression
# inputs in fuzz/crashes/NAME/); FUZZ_SECONDS is split evenly among them.
fuzz:
	$(Q)tests/deps.sh
	$(Q)$(MAKE) --no-print-directory fuzz-only

fuzz-only:
	-$(Q)$(MAKE) --no-print-directory -s -k $(FUZZ_PROGRAMS)
	$(Q)fuzz/run_all.sh $(BUILD)/fuzz $(FUZZ_SECONDS) $(FUZZ_HARNESSES)

fuzz-corpus: $(BUILD)/fuzz/make_corpus
	$(Q)rm -f fuzz/corpus/pipeline/seed-*
	$(Q)mkdir -p fuzz/corpus/pipeline && $(BUILD)/fuzz/make_corpus fuzz/corpus/pipeline

test-programs: $(GCC_TESTS) $(SAN_TESTS) $(TSAN_PROGRAMS) $(BUILD)/examples/minimal $(BUILD)/bench/selftest \
               $(EXAMPLES) $(BUILD)/examples/check_examples \
               $(VULKAN_PROGRAMS)
fast-programs: $(GCC_TESTS)

$(BUILD)/gcc/%: tests/%.c $(HEADERS)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(TEST_CFLAGS) $< -o $@ $(LDLIBS)

$(BUILD)/san/%: tests/%.c $(HEADERS)
	$(say) CLANG $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CLANG) $(if $(filter $*,$(SAN_O0_TESTS)),$(patsubst -O1,-O0,$(SAN_CFLAGS)),$(SAN_CFLAGS)) $< -o $@ $(LDLIBS)

$(BUILD)/tsan/%: tests/%.c $(HEADERS)
	$(say) CLANG $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CLANG) $(TSAN_CFLAGS) $< -o $@ $(LDLIBS)

$(FUZZ_PROGRAMS): $(BUILD)/fuzz/fuzz_%: fuzz/fuzz_%.c $(HEADERS) $(wildcard fuzz/*.h) manylods_vk.h
	$(say) CLANG $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CLANG) $(FUZZ_CFLAGS) $< -o $@ $(FUZZ_LDLIBS)

$(BUILD)/fuzz/make_corpus: fuzz/make_corpus.c
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) -std=c99 -O2 $(WARNINGS) $(CFLAGS) $< -o $@

$(BUILD)/examples/minimal: examples/minimal.c manylods.h
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(EXAMPLE_CFLAGS) $< -o $@ $(LDLIBS)

$(EXAMPLES): $(BUILD)/examples/%: examples/%.c $(EXAMPLE_DEPS)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(EXAMPLE_CFLAGS) $(DEMO_DEFINES) $< -o $@ $(LDLIBS)

# Runs the examples above (they must be built first) from the repository root.
$(BUILD)/examples/check_examples: tests/check_examples.c $(HEADERS) | $(EXAMPLES)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(TEST_CFLAGS) -DEXAMPLES_DIR='"$(BUILD)/examples"' $< -o $@ $(LDLIBS)

bench:
	$(Q)tests/deps.sh
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bench/bench $(BUILD)/examples/instant_radiosity
	$(Q)$(BUILD)/bench/bench --out docs
	$(Q)bench/readme_figures.sh --update README.md docs/bench_figures.txt

# README.md's figures from the last make bench's files: bench/readme_figures.sh
# formats docs/bench_figures.txt into the block between the README's markers.
readme-figures:
	$(Q)bench/readme_figures.sh --update README.md docs/bench_figures.txt

bench-quick:
	$(Q)tests/deps.sh
	$(Q)$(MAKE) --no-print-directory $(BUILD)/bench/bench $(BUILD)/examples/instant_radiosity
	$(Q)$(BUILD)/bench/bench --quick --out $(BUILD)/bench

$(BUILD)/bench/cut_avx2.o: bench/cut_avx2.c bench/cut_avx2.h manylods.h
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(BENCH_CFLAGS) -mavx2 -mfma -c $< -o $@

$(BUILD)/bench/bench: $(BENCH_DEPS) $(if $(BENCH_AVX2),$(BUILD)/bench/cut_avx2.o)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(BENCH_CFLAGS) $< $(BENCH_EXTRA) -o $@ $(BENCH_LDLIBS)

# The same program, --selftest by default: what `make test` runs.
$(BUILD)/bench/selftest: $(BENCH_DEPS) $(if $(BENCH_AVX2),$(BUILD)/bench/cut_avx2.o)
	$(say) CC $@
	$(Q)mkdir -p $(@D) && rm -f $@
	$(Q)$(CC) $(BENCH_CFLAGS) -DBENCH_SELFTEST $< $(BENCH_EXTRA) -o $@ $(BENCH_LDLIBS)

clean:
	rm -rf $(BUILD)
