# Thin driver over CMake. `make figures` and `make test` are the front door.
BUILD      ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc)
# One test more than cores: many tests wait on a child (a figgen run, a
# browser, mpirun's ranks between polls), and a third test fills those
# gaps; on 2 cores the suite took 126 s with -j 2 and 109 s with -j 3.
TEST_JOBS  ?= $(shell expr $$(nproc) + 1)
CMAKE_ARGS ?=
MAKEFLAGS  += --no-print-directory

.PHONY: all deps build figures gallery-check readme-thumbnails test test-without-osmesa test-sanitize fuzz bench goldens install clean

all: build

deps:
	@scripts/deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_ARGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# Regenerates every figure described under figures/ into out/; only the
# figures whose description or program changed are rendered again. Builds
# only what it runs: the program and the modules it opens (the figures
# target depends on them), not the tests or benchmarks.
figures: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) --target figures -j $(JOBS)

# The gallery make figures wrote (out/index.html), every figure in it, checked
# in Debian's headless Chromium as `make test` checks a small one; the
# screenshot is build/test-artifacts/gallery-full.png.
gallery-check: figures
	@mkdir -p $(BUILD)/test-artifacts
	/usr/bin/python3 tests/browser/gallery_in_browser.py --gallery out --screenshot $(BUILD)/test-artifacts/gallery-full.png

# The README's grid: docs/thumbs/ID.png, 240 x 180 at most, from out/.
readme-thumbnails: figures
	$(BUILD)/figgen thumbnails --from out --to docs/thumbs --width 240 --height 180

# A test that hangs fails with its name after 10 minutes instead of using up
# CI's time (the longest takes about 20 s, under the sanitizers 55 s).
test: build
	ctest --test-dir $(BUILD) --output-on-failure --timeout 600 -j $(TEST_JOBS)

# figgen where OSMesa is gone (Mesa 25.1 removed it): REMOVES Debian's
# libosmesa6 from this machine, then checks that --gl osmesa is refused,
# renders every catalog figure through EGL and runs the golden tests under
# EGL. For a throwaway machine: ../shared/tools/fresh-debian-check test-without-osmesa
test-without-osmesa: build
	scripts/test-without-osmesa.sh $(BUILD) $(JOBS)

# The whole suite built with AddressSanitizer and UndefinedBehaviorSanitizer
# (RelWithDebInfo, into build-sanitize/). Leaks inside Mesa's OSMesa are
# suppressed (tests/sanitize/lsan.supp says why); nothing else is.
# intercept_tls_get_addr=0: GCC 12's LeakSanitizer follows the dynamic TLS
# blocks of dlopen'ed libraries (Mesa and LLVM, opened at run time) through
# __tls_get_addr, and under Debian 12's glibc it was handed a bogus range and
# crashed in its own tracer ("Tracer caught signal 11") at exit; static TLS,
# stacks, globals and the heap are still scanned.
# max_malloc_fill_size, malloc_fill_byte: ASan's allocator ignores glibc's
# M_PERTURB, which keeps libx264's reads of memory it never wrote the same
# in every process (media/ffmpeg.cpp, SameFreshMemory); filling every
# allocation does the same under ASan, so films are the same bytes there
# too (without it, segments encoded side by side differed 1 run in 6).
SANITIZE_BUILD ?= build-sanitize
test-sanitize: deps
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFIGGEN_SANITIZE=ON $(CMAKE_ARGS)
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:intercept_tls_get_addr=0:max_malloc_fill_size=2147483647:malloc_fill_byte=85 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitize/lsan.supp:print_suppressions=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(SANITIZE_BUILD) --output-on-failure --timeout 600 -j $(JOBS)

# libFuzzer over the parsers users type into (descriptions, --set, snowflake
# rule codes, L-systems, Ready's files; tests/fuzz/), built with clang into
# build-fuzz/, each target FUZZ_SECONDS (default 600) in turn. The committed
# seeds are copied into build-fuzz/corpus/ first, so what the fuzzer adds
# stays there; a crash is written to build-fuzz/crashes/TARGET/ and stops the
# run. READY_PATTERNS=DIR (Ready's Patterns/ folder, from a clone of
# GollyGang/ready; its files are not ours to commit) adds every pattern file
# under it to ready_pattern's seeds.
FUZZ_BUILD     ?= build-fuzz
FUZZ_SECONDS   ?= 600
FUZZ_TARGETS   ?= description set snowflake_rule lsystem output_name parts caption_text vtk_arrays ready_pattern kernel mesh
READY_PATTERNS ?=
fuzz:
	@scripts/deps.sh fuzz
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DFIGGEN_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	@if [ -n "$(READY_PATTERNS)" ]; then \
	  mkdir -p $(FUZZ_BUILD)/corpus/ready_pattern && \
	  find "$(READY_PATTERNS)" -name '*.vt[iu]' | while read -r f; do \
	    cp "$$f" "$(FUZZ_BUILD)/corpus/ready_pattern/ready-$$(echo "$$f" | sha256sum | cut -c1-16)"; done; \
	  echo "ready_pattern: seeded with $$(find "$(READY_PATTERNS)" -name '*.vt[iu]' | wc -l) of Ready's pattern files"; \
	fi
	@for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_BUILD)/corpus/$$t $(FUZZ_BUILD)/crashes/$$t && \
	  cp -n tests/fuzz/corpus/$$t/* $(FUZZ_BUILD)/corpus/$$t/ && \
	  echo "fuzz_$$t: $(FUZZ_SECONDS) s" && \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitize/lsan.supp:print_suppressions=0 \
	  $(FUZZ_BUILD)/tests/fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ_BUILD)/crashes/$$t/ $(FUZZ_BUILD)/corpus/$$t \
	    > $(FUZZ_BUILD)/fuzz_$$t.log 2>&1 || { tail -40 $(FUZZ_BUILD)/fuzz_$$t.log; exit 1; }; \
	  grep -E "^Done|stat::number_of_executed_units|cov:" $(FUZZ_BUILD)/fuzz_$$t.log | tail -3; \
	done

# Kernel throughput (Google Benchmark), then run time against error, the
# book's numpy/scipy/matplotlib route side by side and whole-pipeline times
# (`make figures` from clean among them): bench/results/, out/bench-pareto.png.
# Then every figure's memory estimate against its peak RSS, over the catalog
# and scaled variants up to the largest documented values
# (tests/app/test_memory_estimates.cpp): bench/results/memory.txt. Last,
# twenty renders of tc7-1 from one Python process against twenty figgen
# processes (bench/python_renders.py): bench/results/python.json. And figgen
# beside Ready's rdy (RDY=path, default build-rdy/rdy; skipped without it):
# Gray-Scott formulas, and with READY_PATTERNS=DIR (Ready's Patterns/)
# SmoothLife, Life on meshes and the bunny (bench/ready_speed.py):
# bench/results/ready.json.
bench: build
	@scripts/deps.sh bench || echo "figgen: the book's route will be skipped" >&2
	cmake --build $(BUILD) --target figgen_bench figgen_accuracy -j $(JOBS)
	mkdir -p bench/results
	$(BUILD)/bench/figgen_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
	  --benchmark_out=bench/results/benchmarks.json --benchmark_out_format=json
	$(BUILD)/bench/figgen_accuracy --results bench/results --figures out
	FIGGEN_MEMORY_TABLE=bench/results/memory.txt $(BUILD)/tests/figgen_tests "[memory-sweep]"
	PYTHONPATH=$(BUILD)/python /usr/bin/python3 bench/python_renders.py $(BUILD)/figgen | tee bench/results/python.json
	READY_PATTERNS=$(READY_PATTERNS) /usr/bin/python3 bench/ready_speed.py $(BUILD)/figgen $${RDY:-build-rdy/rdy} | tee bench/results/ready.json

# Rewrites the image-checksum goldens under tests/golden/ from this machine's
# renderer. Explicit only: CI never runs it.
goldens: build
	$(BUILD)/tests/figgen_goldens tests/golden

# figgen into $(PREFIX)/bin, the descriptions into $(PREFIX)/share/figgen/figures.
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(FUZZ_BUILD) out
