# dlmfsi: build, test and run the comparisons in build/. `make deps` installs the Debian packages the
# project uses (scripts/install-deps, as root) and checks every program it runs (scripts/check-tools);
# the README's two commands, `make test` and `make compare`, call it first so that they set up a fresh
# Debian 12 machine.
BUILD ?= build
JOBS ?= 2
OUT ?= results
QUICK ?= 0
FF := bin/ff

.PHONY: all deps build test compare bench evidence sanitize sanitize-scripts fuzz fresh-check clean supermesh-compare \
	install uninstall

all: build

deps:
	@scripts/install-deps
	@scripts/check-tools

build:
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > $(BUILD).configure.log 2>&1 || (cat $(BUILD).configure.log; exit 1)
	@cmake --build $(BUILD) -j $(JOBS)

# All tests: C++ unit tests (GoogleTest) and FreeFEM script tests, through ctest.
test: deps build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The main job: coupling accuracy and time, built-in quadrature vs dlmfsi, then the paper scenes, then the
# summary of the last `make evidence` run (if any).
compare: deps build
	@mkdir -p $(OUT)
	DLMFSI_BUILD=$(abspath $(BUILD)) $(FF) edp/compare_coupling.edp -out $(OUT)
	@if [ -f scripts/compare-scenes ]; then DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(OUT) scripts/compare-scenes; fi
	@OUT=$(abspath $(OUT)) scripts/evidence --summary

# Assembly speed over a sweep of sizes (built-in vs dlmfsi, threads, cost per piece, peak memory):
# CSV + PNG under $(OUT)/bench; then the rotating disk on 1 and 2 processes (time per step split into
# assembly, analysis, factorization and solve, peak memory per process) under $(OUT)/bench-mpi when the
# distributed solve is built, at n = 5 and 30 (3 times) and n = 60 (once, 20 minutes, 7.7 GB peak). About 45 + 80
# minutes; QUICK=1 for tiny sizes. STAGES="calls sweep core 3d fluid-step presets mpi" runs some of them (scripts/bench's
# docstring; calls: the first and next calls against the built-in, $(OUT)/bench/calls.md, about 10 minutes).
bench: deps build
	@cmake --build $(BUILD) --target coupling_bench coupling3d_bench -j $(JOBS)
	@if [ -z "$(STAGES)" ] || [ -n "$(filter-out mpi,$(STAGES))" ]; then \
	  echo "DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(abspath $(OUT)) QUICK=$(QUICK) scripts/bench $(filter-out mpi,$(STAGES))"; \
	  DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(abspath $(OUT)) QUICK=$(QUICK) scripts/bench $(filter-out mpi,$(STAGES)); fi
	@if [ -n "$(STAGES)" ] && [ -z "$(filter mpi,$(STAGES))" ]; then echo "STAGES=\"$(STAGES)\": scripts/bench-mpi skipped"; \
	elif [ -f $(BUILD)/plugin/dlmfsi_mumps.so ]; then \
	  echo "DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(abspath $(OUT)) QUICK=$(QUICK) scripts/bench-mpi"; \
	  DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(abspath $(OUT)) QUICK=$(QUICK) scripts/bench-mpi; \
	else echo "note: no $(BUILD)/plugin/dlmfsi_mumps.so (libmumps-dev missing): scripts/bench-mpi skipped"; fi

# dlmfsi against a driver on libsupermesh (not in Debian: built once from its sources, a clone of its GitHub
# repository unless LIBSUPERMESH_SRC names a checkout), P1 x P1 mass at two sizes in 2D and two in 3D:
# $(OUT)/bench/supermesh.txt.
supermesh-compare: deps build
	DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(abspath $(OUT)) scripts/supermesh-compare

# Accuracy against speed, the scenes' Pareto fronts and the stability map: CSV + PNG under
# $(OUT)/evidence; then the falling disk's convergence study and the FSI-3 studies (hours of CPU), and the 3D
# falling sphere's (15 minutes, 7 GB).
# STAGES="coupling scenes stability" runs some stages (about 20 minutes); QUICK=1 the same pipeline on tiny sizes.
STAGES ?=
evidence: deps build
	DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(abspath $(OUT)) QUICK=$(QUICK) scripts/evidence $(STAGES)

# AddressSanitizer + UndefinedBehaviorSanitizer build of the core, running the unit tests; the property
# test with SANITIZE_FUZZ_PAIRS pairs (the unsanitized `make test` runs 1e6; 1e6 here takes about 2 min).
SANITIZE_FUZZ_PAIRS ?= 200000
sanitize: deps
	@cmake -S . -B $(BUILD)-sanitize -DCMAKE_BUILD_TYPE=Debug -DDLMFSI_SANITIZE=ON -DDLMFSI_PLUGIN=OFF > /dev/null
	@cmake --build $(BUILD)-sanitize -j $(JOBS)
	cd $(BUILD)-sanitize && DLMFSI_FUZZ_PAIRS=$(SANITIZE_FUZZ_PAIRS) ctest --output-on-failure -j $(JOBS)

# The plugins built with AddressSanitizer + UndefinedBehaviorSanitizer and every FreeFEM script test run on them,
# the runtimes preloaded into FreeFem++-nw (scripts/sanitize-scripts; about 10 minutes on 2 cores: 6 to build,
# 5 to run).
sanitize-scripts: deps
	@JOBS=$(JOBS) scripts/sanitize-scripts $(BUILD)-asan

# libFuzzer targets for the clipper and the fluid search (tests/fuzz/fuzz_clip.cpp) and for the
# tetrahedron clipper against GMP volumes and the 3D search (tests/fuzz/fuzz_clip3d.cpp), built with clang, AddressSanitizer
# and UndefinedBehaviorSanitizer, each run for FUZZ_TIME seconds on its corpus kept in $(BUILD)-fuzz/corpus
# and corpus3d, starting from the inputs kept in tests/fuzz/corpus/ (which make test replays); a failing input
# is written to $(BUILD)-fuzz/crash-* (3d-crash-*): add it there once understood. Not part of `make test`.
FUZZ_TIME ?= 60
CLANGXX ?= clang++
FUZZ_FLAGS := -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all -Iplugin/core -Itests/core
FUZZ_SOURCES := tests/fuzz/fuzz_clip.cpp plugin/core/geometry/clip.cpp plugin/core/geometry/predicates.cpp plugin/core/geometry/exact_sign.cpp \
  plugin/core/mesh/mesh.cpp plugin/core/mesh/fluid_search.cpp
FUZZ3D_SOURCES := tests/fuzz/fuzz_clip3d.cpp plugin/core/geometry/clip3d.cpp plugin/core/geometry/predicates3d.cpp \
  plugin/core/geometry/predicates.cpp plugin/core/geometry/exact_sign.cpp plugin/core/mesh/mesh3d.cpp plugin/core/mesh/fluid_search3d.cpp \
  tests/core/reference3d.cpp
fuzz:
	@scripts/install-deps fuzz
	@scripts/check-tools fuzz
	@mkdir -p $(BUILD)-fuzz/corpus $(BUILD)-fuzz/corpus3d
	$(CLANGXX) $(FUZZ_FLAGS) $(FUZZ_SOURCES) -o $(BUILD)-fuzz/fuzz_clip
	$(CLANGXX) $(FUZZ_FLAGS) $(FUZZ3D_SOURCES) -lgmpxx -lgmp -o $(BUILD)-fuzz/fuzz_clip3d
	$(BUILD)-fuzz/fuzz_clip -max_total_time=$(FUZZ_TIME) -print_final_stats=1 \
	  -artifact_prefix=$(BUILD)-fuzz/ $(BUILD)-fuzz/corpus tests/fuzz/corpus/2d
	$(BUILD)-fuzz/fuzz_clip3d -max_total_time=$(FUZZ_TIME) -print_final_stats=1 \
	  -artifact_prefix=$(BUILD)-fuzz/3d- $(BUILD)-fuzz/corpus3d tests/fuzz/corpus/3d

# The README's two commands as a new user meets them: a bare Debian 12 root (debootstrap minbase), a clean
# clone of HEAD, `make test`, then `make install` with a script of one's own run from a fresh folder and `make
# uninstall` (tests/install/system_check), then `make compare`, in a chroot (scripts/fresh-check; root, about 20
# minutes on 2 cores).
fresh-check:
	OUT=$(abspath $(OUT)) scripts/fresh-check

# The plugins (PREFIX/lib/dlmfsi/) and the script library (PREFIX/share/dlmfsi/lib/) for plain FreeFem++,
# FreeFem++-nw and FreeFem++-mpi from any folder: their folders, and Debian's plugin and .idp folders, go into
# FreeFEM's /etc/freefem++.pref in a marked block (FF_PREF names another file); DESTDIR stages every path.
# `make uninstall` removes what PREFIX/share/dlmfsi/install-manifest.txt lists and the block (docs/install.md).
PREFIX ?= /usr/local
DESTDIR ?=
install: build
	@PREFIX=$(PREFIX) DESTDIR=$(DESTDIR) BUILD=$(abspath $(BUILD)) scripts/install

uninstall:
	@PREFIX=$(PREFIX) DESTDIR=$(DESTDIR) scripts/uninstall

clean:
	rm -rf $(BUILD) $(BUILD)-sanitize $(BUILD)-asan $(BUILD)-asan.configure.log $(BUILD)-fuzz $(BUILD).configure.log
