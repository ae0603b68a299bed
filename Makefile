# dlmfsi: build, test and run the comparisons. Every target installs missing Debian packages first
# (scripts/install-deps, as root) and builds in build/.
BUILD ?= build
JOBS ?= 2
OUT ?= results
QUICK ?= 0
FF := bin/ff

.PHONY: all deps build test compare bench evidence sanitize clean

all: build

deps:
	@scripts/install-deps

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > $(BUILD).configure.log 2>&1 || (cat $(BUILD).configure.log; exit 1)
	@cmake --build $(BUILD) -j $(JOBS)

# All tests: C++ unit tests (GoogleTest) and FreeFEM script tests, through ctest.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The main job: coupling accuracy and time, built-in quadrature vs dlmfsi, then the paper scenes.
compare: build
	@mkdir -p $(OUT)
	DLMFSI_BUILD=$(abspath $(BUILD)) $(FF) edp/compare_coupling.edp -out $(OUT)
	@if [ -f scripts/compare-scenes ]; then DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(OUT) scripts/compare-scenes; fi

# Assembly speed over a sweep of sizes (built-in vs dlmfsi, threads, cost per piece, peak memory):
# CSV + PNG under $(OUT)/bench. QUICK=1 for tiny sizes.
bench: build
	DLMFSI_BUILD=$(abspath $(BUILD)) OUT=$(abspath $(OUT)) QUICK=$(QUICK) scripts/bench

# AddressSanitizer + UndefinedBehaviorSanitizer build of the core, running the unit tests.
sanitize: deps
	@cmake -S . -B $(BUILD)-sanitize -DCMAKE_BUILD_TYPE=Debug -DDLMFSI_SANITIZE=ON -DDLMFSI_PLUGIN=OFF > /dev/null
	@cmake --build $(BUILD)-sanitize -j $(JOBS)
	cd $(BUILD)-sanitize && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) $(BUILD)-sanitize $(BUILD).configure.log
