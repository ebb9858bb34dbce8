# slipwalk — the two commands a fresh machine needs: `make reproduce` and `make test`.
# Every target depends on `deps`, which installs the Debian packages that are missing (and only
# those), saying what it installs; `make test` on `deps-test`, which adds the page checks' browser.

BUILD     ?= build
JOBS      ?= $(shell nproc)
CMAKE_ARGS ?=
ifeq ($(CI),true)
CMAKE_ARGS += -DSLIPWALK_WERROR=ON
endif
# Ninja starts a layer's files while the layer below links (Make waits at every library). A build
# folder keeps the generator it was made with.
export CMAKE_GENERATOR ?= Ninja
# ccache (Debian's package) when present, never required: a rebuild of unchanged sources, in this
# folder or a fresh clone's (paths below the clone are hashed relative to it), comes from its
# cache. The sloppiness lets it cache the files built with a precompiled header (their
# __DATE__/__TIME__ are not used); a build run without it (cmake --build by hand) compiles them
# uncached. A build folder keeps the launcher it was configured with.
CCACHE := $(shell command -v ccache 2>/dev/null)
ifneq ($(CCACHE),)
CMAKE_ARGS += -DCMAKE_C_COMPILER_LAUNCHER=$(CCACHE) -DCMAKE_CXX_COMPILER_LAUNCHER=$(CCACHE)
export CCACHE_SLOPPINESS ?= pch_defines,time_macros,include_file_mtime,include_file_ctime
export CCACHE_BASEDIR ?= $(CURDIR)
endif

DEBIAN_PACKAGES := cmake ninja-build g++ make pkg-config git \
  libeigen3-dev libsundials-dev libgsl-dev libboost-dev \
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev \
  libceres-dev \
  openmpi-bin libopenmpi-dev \
  libmujoco-dev \
  python3 python3-matplotlib python3-numpy python3-scipy python3-markdown
# Only `make test` and `make report-check` need these: headless Chromium reads the built pages
# (reports/site/check_pages.py). It is a third of the packages' install time, off the
# reproduction's path.
DEBIAN_TEST_PACKAGES := chromium

.PHONY: all deps deps-test build build-cli test reproduce reproduce-quick bench format format-check tidy \
  clean sanitize sanitize-quick fuzz

all: build

# install_missing(packages): installs those of `packages` that are missing, saying which.
define install_missing
	@missing=""; for p in $(1); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make $@: installing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	else \
	  echo "make $@: all Debian packages present"; \
	fi
endef

deps:
	$(call install_missing,$(DEBIAN_PACKAGES))

deps-test:
	$(call install_missing,$(DEBIAN_PACKAGES) $(DEBIAN_TEST_PACKAGES))

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# The reproduction runs one binary: `slipwalk` and the library under it, not the ~110 test and
# benchmark executables (`make test` builds those).
build-cli: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target slipwalk

test: deps-test build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Exits 1 when a sweep point failed (listed by study and kind), after writing everything else.
# REPRODUCE_ARGS adds options, e.g. `make reproduce REPRODUCE_ARGS=--full` for the long variants.
REPRODUCE_ARGS ?=
reproduce: build-cli
	$(BUILD)/bin/slipwalk reproduce $(REPRODUCE_ARGS)

reproduce-quick: build-cli
	$(BUILD)/bin/slipwalk reproduce --quick $(REPRODUCE_ARGS)

# The built report as a reader sees it, in headless Chromium (reports/site/check_pages.py):
# images load, nothing is wider than the page, no text below 8 pt; screenshots in reports/out/screens.
.PHONY: report-check
report-check: deps-test reproduce
	/usr/bin/python3 reports/site/check_pages.py reports/out

bench: build
	@for b in $(BUILD)/bin/bench_*; do echo "== $$b"; $$b --benchmark_min_time=0.2; done

format:
	find lib sweeps tests bench -name '*.[ch]pp' | xargs clang-format -i

format-check:
	find lib sweeps tests -name '*.[ch]pp' | xargs clang-format --dry-run --Werror

# clang-tidy reads its own compile database, configured without precompiled headers (clang cannot
# read GCC's): configuring takes seconds and builds nothing.
TIDY_BUILD ?= build-tidy
tidy: deps
	cmake -S . -B $(TIDY_BUILD) -DCMAKE_BUILD_TYPE=Release -DSLIPWALK_PCH=OFF -DSLIPWALK_UNITY=OFF $(CMAKE_ARGS) >/dev/null
	find lib sweeps -name '*.cpp' | xargs -P $(JOBS) -n 4 clang-tidy -p $(TIDY_BUILD) --quiet

# Everything under AddressSanitizer + UBSan (g++), in its own build folder: asserts on (no
# NDEBUG), -O1 and line tables for readable reports. Tests that time or count allocations skip
# there and say why (SLIPWALK_SANITIZED). `sanitize` runs the whole suite; `sanitize-quick` (CI)
# builds and runs the label sanitize_quick of tests/CMakeLists.txt: the readers, the contact and
# friction searches and the fuzz replay.
SANITIZE_BUILD ?= build-sanitize
SANITIZE_ENV := ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

$(SANITIZE_BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1" \
	  -DSLIPWALK_SANITIZE=ON -DSLIPWALK_BENCHMARKS=OFF $(CMAKE_ARGS)

sanitize: deps $(SANITIZE_BUILD)/CMakeCache.txt
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	cd $(SANITIZE_BUILD) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS)

sanitize-quick: deps $(SANITIZE_BUILD)/CMakeCache.txt
	cmake --build $(SANITIZE_BUILD) -j $(JOBS) --target sanitize_quick
	cd $(SANITIZE_BUILD) && $(SANITIZE_ENV) ctest --output-on-failure -j $(JOBS) -L sanitize_quick

# libFuzzer (clang): every tests/fuzz/fuzz_<name>.cpp for FUZZ_SECONDS each, from a copy of its
# seed corpus and regressions in $(FUZZ_BUILD)/corpus/<name> (new inputs stay there, never in the
# source tree); crashes land in $(FUZZ_BUILD)/artifacts/<name>/. FUZZERS picks some.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZERS      ?= $(patsubst tests/fuzz/fuzz_%.cpp,%,$(wildcard tests/fuzz/fuzz_*.cpp))

$(FUZZ_BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1" \
	  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DSLIPWALK_FUZZ=ON \
	  -DBUILD_TESTING=OFF -DSLIPWALK_BENCHMARKS=OFF -DSLIPWALK_MUJOCO=OFF $(CMAKE_ARGS)

fuzz: deps $(FUZZ_BUILD)/CMakeCache.txt
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZERS))
	@failed=""; for f in $(FUZZERS); do \
	  corpus=$(FUZZ_BUILD)/corpus/$$f; mkdir -p $$corpus $(FUZZ_BUILD)/artifacts/$$f; \
	  cp -n tests/fuzz/corpus/$$f/* $$corpus/ 2>/dev/null || true; \
	  cp -n tests/fuzz/regressions/$$f/* $$corpus/ 2>/dev/null || true; \
	  echo "== fuzz_$$f for $(FUZZ_SECONDS) s"; \
	  $(SANITIZE_ENV) $(FUZZ_BUILD)/bin/fuzz_$$f $$corpus -max_total_time=$(FUZZ_SECONDS) \
	    -timeout=10 -rss_limit_mb=4096 -max_len=65536 -print_final_stats=1 \
	    -artifact_prefix=$(FUZZ_BUILD)/artifacts/$$f/ || failed="$$failed $$f"; \
	done; \
	if [ -n "$$failed" ]; then echo "make fuzz: failures in:$$failed (inputs in $(FUZZ_BUILD)/artifacts/)"; exit 1; fi

clean:
	rm -rf $(BUILD)
