# slipwalk — the two commands a fresh machine needs: `make reproduce` and `make test`.
# Every target depends on `deps`, which installs the Debian packages that are missing (and only
# those), saying what it installs.

BUILD     ?= build
JOBS      ?= $(shell nproc)
CMAKE_ARGS ?=
ifeq ($(CI),true)
CMAKE_ARGS += -DSLIPWALK_WERROR=ON
endif

DEBIAN_PACKAGES := cmake g++ make pkg-config git \
  libeigen3-dev libsundials-dev libgsl-dev libboost-dev \
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev \
  libmujoco-dev \
  python3 python3-matplotlib python3-numpy python3-markdown chromium

.PHONY: all deps build test reproduce reproduce-quick bench format format-check tidy clean

all: build

deps:
	@missing=""; for p in $(DEBIAN_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	else \
	  echo "make deps: all Debian packages present"; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

reproduce: build
	$(BUILD)/bin/slipwalk reproduce

reproduce-quick: build
	$(BUILD)/bin/slipwalk reproduce --quick

# The built report as a reader sees it, in headless Chromium (reports/site/check_pages.py):
# images load, nothing is wider than the page, no text below 8 pt; screenshots in reports/out/screens.
.PHONY: report-check
report-check: reproduce
	/usr/bin/python3 reports/site/check_pages.py reports/out

bench: build
	@for b in $(BUILD)/bin/bench_*; do echo "== $$b"; $$b --benchmark_min_time=0.2; done

format:
	find lib sweeps tests bench -name '*.[ch]pp' | xargs clang-format -i

format-check:
	find lib sweeps tests -name '*.[ch]pp' | xargs clang-format --dry-run --Werror

tidy: build
	find lib sweeps -name '*.cpp' | xargs -P $(JOBS) -n 4 clang-tidy -p $(BUILD) --quiet

clean:
	rm -rf $(BUILD)
