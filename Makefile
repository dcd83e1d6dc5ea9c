# exic: `make run` and `make test` work on a fresh Debian 12 machine.
# They install what is missing (Debian packages, fpm in a local venv), build, and run.

SHELL := /bin/bash
APT_PACKAGES := gfortran g++ liblapack-dev libopenblas-serial-dev libsuitesparse-dev libhdf5-dev libgmsh-dev \
                pkg-config hdf5-tools python3-venv libopenmpi-dev openmpi-bin libmetis-dev
# LAPACK and BLAS from the single-threaded OpenBLAS, whatever Debian's alternatives point
# libblas.so.3 and liblapack.so.3 at: the threaded OpenBLAS starts a pool of helper threads
# when the library loads, and they spin for about 0.1 s of processor time in every process
# (doc/decisions.md "Threads"). Found at link time (-L) and at run time (run path); fpm takes
# the flags from FPM_LDFLAGS, which the tests' own fpm calls inherit.
SERIAL_BLAS := /usr/lib/$(shell uname -m)-linux-gnu/openblas-serial
export FPM_LDFLAGS := -L$(SERIAL_BLAS) -Wl,-rpath,$(SERIAL_BLAS) $(FPM_LDFLAGS)
# MPI (doc/parallel.md): every build compiles with OpenMPI's wrapper mpifort (gfortran with the
# mpi_f08 module folder and libraries); fpm takes the compiler from FPM_FC, which the tests' and
# tools' own fpm calls inherit. The build folders are build/mpifort_*.
export FPM_FC := mpifort
VENV    := .venv
PYTHON  := $(VENV)/bin/python
FPM     := $(VENV)/bin/fpm
RELEASE_FLAGS := -O3 -march=native -funroll-loops -ffp-contract=off
RELEASE := --profile release --flag "$(RELEASE_FLAGS)"
EXAMPLE ?= inputs/examples/impact.inp
OUTDIR  ?= out

.PHONY: all doc setup deps venv build run test test-release test-viewers serial verify stress bench bench-peers taylor-ccx baseline plots install legacy-host clean help

all: build

help:
	@echo "make run      set up, build (release) and run the main example ($(EXAMPLE))"
	@echo "make test     set up and run the whole test suite (fpm test, bounds checked)"
	@echo "make test-release  the same suite built with the release flags (vectorized, no bounds checks)"
	@echo "make stress   random scenes, fuzzed decks, CFL sweeps, long runs -> doc/stability.md"
	@echo "              (about 30 minutes; STRESS_ARGS=--long for 10^6-step runs)"
	@echo "make verify   run the decks of inputs/ and regenerate doc/verification.md"
	@echo "make serial   build without OpenMP and check it gives the bits of the OpenMP build"
	@echo "              (the decks of inputs/ and 256 bodies, two threads; a few minutes)"
	@echo "make bench    run the benchmarks (against the baseline commit BASELINE, built once) and"
	@echo "              regenerate doc/performance figures"
	@echo "make bench-peers  install CalculiX (Debian) and run it on the bar on a rigid wall"
	@echo "make taylor-ccx   install CalculiX and run it on the Taylor bar (face held on the wall,"
	@echo "              5 x 50 CAX8R, explicit; about 70 minutes) -> bench/results/taylor_ccx.json,"
	@echo "              which make verify compares with exic (doc/plasticity.md section 12)"
	@echo "make plots DECK=path.inp [OUTDIR=out]   run a deck, draw its histories and contours"
	@echo "              into OUTDIR/plots"
	@echo "make test-viewers  install ParaView (Debian packages) and check it reads the field output"
	@echo "make doc     the API reference of the library from the sources' !> comments (FORD) into"
	@echo "              build/doc/api/index.html"
	@echo "make install PREFIX=dir    install the exic program, libexic.a, module files and the C header"
	@echo "make legacy-host PREFIX=dir   build examples/legacy_host against that installation"

# --- set-up -----------------------------------------------------------------
# $(call apt_install,PACKAGES): install the Debian packages of the list that are missing
apt_install = missing=""; for p in $(1); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	fi

deps:
	@$(call apt_install,$(APT_PACKAGES))

$(FPM): tools/requirements.txt | deps
	@if [ ! -x $(PYTHON) ]; then python3 -m venv $(VENV) 2>/dev/null || /usr/bin/python3 -m venv $(VENV); fi
	$(PYTHON) -m pip install -q --disable-pip-version-check -r tools/requirements.txt
	@touch $(FPM)

venv: $(FPM)

setup: deps venv

# --- build and run ----------------------------------------------------------
# fpm 0.12 rebuilds a source when it changed or when a module it uses was rebuilt in the same
# run: after a build that stopped on an error, the users of the modules it had already rebuilt
# are never rebuilt, and programs then run with objects of two layouts of one type. So a
# failed build drops every object (the next build starts clean), and the programs' own
# objects (tests, app, benchmarks) and the archive, cheap to rebuild, are dropped before
# every build.
STALE = find build -path '*/exic/*' \( -name 'test_*' -o -name 'app_*' -o -name 'bench_*' -o -name 'libexic.a' \) -delete 2>/dev/null || true
# $(call fpm_build,ARGS): fpm build ARGS; on failure remove every object and fail
fpm_build = $(FPM) build $(1) || { rm -rf build/gfortran_* build/mpifort_*; exit 1; }

build: setup
	@$(STALE)
	@$(call fpm_build,$(RELEASE))

run: build
	@mkdir -p $(OUTDIR)
	$(FPM) run $(RELEASE) exic -- $(EXAMPLE) -o $(OUTDIR)
	@echo "the exic program is $$(realpath $(EXIC))"
	@echo "(run it by that path, or 'make install PREFIX=dir' and put dir/bin on PATH)"

# fpm 0.12 can leave a stale test executable when `fpm run` rebuilt the library first: relink it.
# The legacy API tests install exic with this fpm (examples/legacy_host/build.sh).
# $(call build_tests,ARGS): the test program built with the fpm build options ARGS, the stale
# program and objects dropped first
build_tests = find build -path '*/test/exic-test' -type f -delete 2>/dev/null || true; \
	$(STALE); $(call fpm_build,$(1) --tests)

test: setup
	@$(call build_tests,)
	EXIC_FPM=$(abspath $(FPM)) $(FPM) test

# The suite built as the release binary is (the vectorized loops, which the bounds-checked
# build does not make): a result that depends on how a loop was compiled shows here.
test-release: setup
	@$(call build_tests,$(RELEASE))
	EXIC_FPM=$(abspath $(FPM)) $(FPM) test $(RELEASE)

# Optional: the `viewers` suite (ParaView reads the field output headless), which `make test`
# skips when pvpython is missing. ParaView is several hundred MB of Debian packages, so only
# this target installs it.
VIEWER_PACKAGES := paraview python3-paraview xvfb xauth
test-viewers: setup
	@$(call apt_install,$(VIEWER_PACKAGES))
	@$(call build_tests,)
	$(FPM) test exic-test -- viewers

# the release binary that `build` made
EXIC = $$($(FPM) run $(RELEASE) --runner echo exic 2>/dev/null | tail -n 1)

verify: build
	$(PYTHON) tools/verify.py --exic "$(EXIC)"

# The sources compile without OpenMP (doc/decisions.md, "Build"): a copy of them without
# fpm.toml's openmp dependency, built under build/serial, against the release build.
serial: build
	$(PYTHON) tools/check_serial.py --exic "$(EXIC)" --flags "$(RELEASE_FLAGS)"

# Stress suite (doc/stability.md, doc/stability/): 500 random scenes, 2,000 fuzzed decks, CFL
# sweeps of the seed's 7.2 and 7.3, long runs of 5e4-1e5 steps; two processes at a time, each
# run under a timeout. STRESS_ARGS passes options: --long (10^6-step runs), --seed N,
# --only scenes,fuzz,cfl,long, --scenes N, --fuzz N (tools/stress/stress.py --help).
STRESS_ARGS ?=
stress: build
	$(PYTHON) tools/stress/stress.py --exic "$(EXIC)" $(STRESS_ARGS)

plots: build
	@if [ -z "$(DECK)" ]; then echo "usage: make plots DECK=path/to/deck.inp [OUTDIR=out]"; exit 2; fi
	$(PYTHON) tools/plots.py "$(DECK)" -o "$(OUTDIR)" --exic "$(EXIC)"

# Benchmarks (doc/performance.md): release build, then every section of bench/run_bench.py
# (about 11 minutes after the build, 5 of them section impact; BENCH_ONLY=rate,output runs a
# subset, BENCH_ARGS=--quick a 2-minute smoke test, BENCH_ARGS=--big adds the 480 x 96 meshes
# to section impact). Results: bench/results/, figures: doc/perf_*.png.
# Section compare runs the release build of BASELINE (a commit, built once in a detached git
# worktree under build/baseline, with its own flags = RELEASE) side by side with this one.
BENCH_ONLY ?= machine,compare,bodies,rate,profile,output,contact,workprec,impact,stability,mpi
BASELINE   ?= 5744a35
BASE_DIR   := build/baseline-$(BASELINE)
bench: setup baseline
	$(FPM) build $(RELEASE)
	$(PYTHON) bench/run_bench.py --fpm $(FPM) --release '$(RELEASE)' --only $(BENCH_ONLY) \
	  --baseline-bindir "$$(cat $(BASE_DIR)/bindir)" $(BENCH_ARGS)

# Optional: CalculiX (Debian's calculix-ccx, installed only by this target) on the bar on a rigid
# wall of section impact (bench/peers.py; doc/performance.md section 4, "CalculiX"); its exic
# curves come from bench/results/impact.json (make bench BENCH_ONLY=impact). About 5 minutes.
PEER_PACKAGES := calculix-ccx
PEERS_ARGS ?=
bench-peers: setup
	@$(call apt_install,$(PEER_PACKAGES))
	$(PYTHON) bench/peers.py $(PEERS_ARGS)

TAYLOR_CCX_ARGS ?= --meshes 5 --elem CAX8R --explicit
taylor-ccx: setup
	@$(call apt_install,$(PEER_PACKAGES))
	$(PYTHON) bench/taylor_ccx.py $(TAYLOR_CCX_ARGS)

# the release binaries of BASELINE; $(BASE_DIR)/bindir names their folder
baseline: setup
	@if [ ! -f $(BASE_DIR)/bindir ]; then \
	  rm -rf $(BASE_DIR); git worktree prune; \
	  git worktree add --detach $(BASE_DIR) $(BASELINE) >/dev/null && \
	  ln -sfn $(abspath $(VENV)) $(BASE_DIR)/.venv && \
	  (cd $(BASE_DIR) && $(abspath $(FPM)) build $(RELEASE) >/dev/null) && \
	  (cd $(BASE_DIR) && $(abspath $(FPM)) run $(RELEASE) --runner echo exic 2>/dev/null | tail -n 1 | \
	   xargs dirname | sed "s|^|$(abspath $(BASE_DIR))/|" > bindir) || { rm -rf $(BASE_DIR); exit 1; }; \
	fi
	@echo "baseline $(BASELINE): $$(cat $(BASE_DIR)/bindir)"

# The exic program, libexic.a, the module files and the C header, nothing else (no benchmark
# program): tools/install.sh installs with fpm into build/install-stage and copies those.
# the archive is made anew (STALE drops it): one left by `make test-release` also holds the
# objects of the test helpers (test_support/, doc/decisions.md "Tests by folder")
install: setup
	@$(STALE)
	EXIC_FPM=$(abspath $(FPM)) tools/install.sh $(or $(PREFIX),$(CURDIR)/dist) $(RELEASE)

legacy-host: install
	$(MAKE) -C examples/legacy_host PREFIX=$(abspath $(or $(PREFIX),$(CURDIR)/dist)) \
	        OUT=$(abspath $(or $(PREFIX),$(CURDIR)/dist))/bin

# The API reference (FORD, pinned in tools/requirements.txt; doc/ford.md is its project file):
# every module of src/exic with its public entities and their !> comments.
doc: setup
	$(VENV)/bin/ford doc/ford.md
	@echo "the API reference: $(CURDIR)/build/doc/api/index.html"

clean:
	rm -rf build $(OUTDIR)
