# The two quick-start commands: `make demo` and `make test`; `make cohort-demo` meshes a small cohort (docs/cohorts.md).
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
DEMO_OUT ?= out/demo
COHORT_OUT ?= out/cohort-demo
# Coarse enough for a quick demo, fine enough for the automatic landmarks of the bundled CT to be plausible.
COHORT_EDGE_LENGTH ?= 3

.PHONY: deps configure build demo cohort-demo test bench fuzz clean

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release > $(BUILD_DIR).configure.log 2>&1 || (cat $(BUILD_DIR).configure.log; exit 1)

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

# Exit code 3 means the mesh was written but still has inverted or flat cells: reported, not a build failure.
demo: build
	@$(BUILD_DIR)/bin/facehex run -o $(DEMO_OUT) || [ $$? -eq 3 ]

cohort-demo: build
	@bash scripts/cohort-demo.sh $(COHORT_OUT) $(JOBS) $(COHORT_EDGE_LENGTH)

test: build
	cd $(BUILD_DIR) && xvfb-run -a -s "-screen 0 1600x1000x24" ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD_DIR)/bin/facehex bench

# Every reader under libFuzzer for FUZZ_SECONDS each (default 600), in build-fuzz/ (docs/robustness.md).
fuzz:
	@bash scripts/install-deps.sh fuzz
	@bash scripts/fuzz.sh

clean:
	rm -rf $(BUILD_DIR) $(BUILD_DIR).configure.log
