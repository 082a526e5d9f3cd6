# Fuzzing: libFuzzer targets with AddressSanitizer and UndefinedBehaviorSanitizer for the OBJ/MTL
# loader (fuzz_obj), the scene JSON reader (fuzz_scene_json) and the memory-image reader and
# validator with the golden model behind it (fuzz_image). Not part of CI.
#
#   make fuzz                      every target for FUZZ_SECONDS (default 60) seconds, one after
#                                  the other; fails when one finds something
#   make fuzz FUZZ_SECONDS=300 FUZZ_TARGETS=fuzz_image
#   make fuzz-build                only build the fuzzers (into $(BUILD)/fuzz/)
#   FUZZ_FRESH=1                   start from the seed corpus again; FUZZ_SKIP_KNOWN=1 leaves the
#                                  saved findings out; FUZZ_ARGS adds libFuzzer options
#
# Included from the top Makefile (`include tests/fuzz/fuzz.mk`); also usable alone from the
# repository root: `make -f tests/fuzz/fuzz.mk fuzz`. Like every target it installs what it needs
# first (clang and its libFuzzer/sanitizer runtimes, the libraries' -dev packages) through apt-get.
#
# The targets compile the project sources they need (tb/scene/*.cpp, tb/golden/{camera,geometry,
# render}.cpp, tinyobjloader's implementation) directly with clang, -ffp-contract=off as in the
# CMake build, -fsanitize=address,undefined (every UB report fatal) and the fuzzer's coverage
# instrumentation; the constants come from `tb/gen_constants.py docs/spec.toml $(BUILD)/fuzz/gen`.
# render.cpp (render_golden) also holds the OpenImageIO image writer, which the fuzzers never call:
# fuzz_image links OpenImageIO (pkg-config) only to resolve it. (--gc-sections cannot drop it: the
# sanitizers' metadata keeps its sections alive.)
#
# A run (tests/fuzz/run_fuzzer.sh) copies tests/fuzz/corpus/<target>/ (never written to) into
# $(BUILD)/fuzz/work/<target>/corpus/, which is kept between runs (FUZZ_FRESH=1 starts from the
# seeds again), runs the fuzzer with -rss_limit_mb=2048 -timeout=10 -max_len=<per target> and
# prints, per target, the seconds it ran, the executions, cov/ft of libFuzzer's last status line
# and what it found: crash-*/leak-*/timeout-*/oom-* files in
# $(BUILD)/fuzz/work/<target>/artifacts/, the log in $(BUILD)/fuzz/work/<target>/fuzz.log. Saved
# findings live in the seed corpus as crash-<description> and fail the run until their bug is fixed
# (FUZZ_SKIP_KNOWN=1 leaves them out). Dictionaries of keywords: tests/fuzz/<target>.dict.
# fuzz_image's seeds also come fresh from gen_seed_images (tiny scenes compiled by the current
# compiler) before every run, so they follow changes of the image format.
#
# Replaying or minimising one input by hand:
#   build/fuzz/fuzz_obj tests/fuzz/corpus/fuzz_obj/crash-...
#   build/fuzz/fuzz_obj -minimize_crash=1 -runs=100000 -exact_artifact_path=min.txt INPUT

FUZZ_MK_GOAL := $(.DEFAULT_GOAL)
FUZZ_MK_FIRST := $(words $(MAKEFILE_LIST))

BUILD        ?= build
PYTHON       ?= python3
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= fuzz_obj fuzz_scene_json fuzz_image
# The LLVM release whose clang and compiler-rt (libFuzzer, ASan, UBSan) are used: Debian bookworm
# has 14 (clang-14, libclang-rt-14-dev).
FUZZ_LLVM    ?= 14
FUZZ_CXX     ?= clang++-$(FUZZ_LLVM)
# More libFuzzer options for every target (e.g. FUZZ_ARGS=-use_value_profile=1).
FUZZ_ARGS    ?=
# 1: start from the seeds again (empty the kept working corpus); 1: leave the saved findings
# (seeds named crash-*) out of the run.
FUZZ_FRESH      ?= 0
FUZZ_SKIP_KNOWN ?= 0

FUZZ_SRC  := $(patsubst %/,%,$(dir $(lastword $(MAKEFILE_LIST))))
FUZZ_ROOT := $(abspath $(FUZZ_SRC)/../..)
FUZZ_DIR  := $(BUILD)/fuzz
FUZZ_OBJ  := $(FUZZ_DIR)/obj
FUZZ_GEN  := $(FUZZ_DIR)/gen
FUZZ_WORK := $(FUZZ_DIR)/work

FUZZ_DEB_PKGS := clang-$(FUZZ_LLVM) libclang-rt-$(FUZZ_LLVM)-dev python3 pkg-config \
                 libtinyobjloader-dev nlohmann-json3-dev libglm-dev zlib1g-dev libopenimageio-dev
FUZZ_SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

FUZZ_SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_CXXFLAGS := -std=c++17 -O1 -g -fno-omit-frame-pointer -ffp-contract=off \
                 $(FUZZ_SANITIZE) -fsanitize=fuzzer-no-link \
                 -DTINYOBJLOADER_USE_DOUBLE -DRC_SOURCE_DIR='"/nonexistent/raycore-fuzz"' \
                 -I$(FUZZ_ROOT)/tb/scene -I$(FUZZ_ROOT)/tb/golden -I$(FUZZ_ROOT)/tb/fp \
                 -I$(FUZZ_GEN) \
                 -MMD -MP
FUZZ_LDFLAGS  := $(FUZZ_SANITIZE)
FUZZ_LIBS     := -lz -lpthread
# Evaluated when fuzz_image is linked, after fuzz-deps has installed pkg-config and OpenImageIO.
FUZZ_OIIO_LIBS = $(shell pkg-config --libs OpenImageIO)

# The project sources (rc_scene's list in tb/scene/CMakeLists.txt is every .cpp there) and the
# golden model's parts the image target needs.
FUZZ_SCENE_SRCS  := $(sort $(wildcard $(FUZZ_ROOT)/tb/scene/*.cpp))
FUZZ_GOLDEN_SRCS := $(addprefix $(FUZZ_ROOT)/tb/golden/,camera.cpp geometry.cpp render.cpp)
FUZZ_LIB_OBJS := $(patsubst $(FUZZ_ROOT)/tb/scene/%.cpp,$(FUZZ_OBJ)/scene_%.o,$(FUZZ_SCENE_SRCS)) \
                 $(FUZZ_OBJ)/tinyobj_impl.o
FUZZ_GOLDEN_OBJS := $(patsubst $(FUZZ_ROOT)/tb/golden/%.cpp,$(FUZZ_OBJ)/golden_%.o,\
                      $(FUZZ_GOLDEN_SRCS))
FUZZ_BINS := $(addprefix $(FUZZ_DIR)/,fuzz_obj fuzz_scene_json fuzz_image gen_seed_images)

# Per target: the longest input libFuzzer makes (the image seeds are a few KiB; the Cornell box
# image is the largest) and its dictionary.
FUZZ_MAX_LEN_fuzz_obj        := 4096
FUZZ_MAX_LEN_fuzz_scene_json := 4096
FUZZ_MAX_LEN_fuzz_image      := 8192

.PHONY: fuzz fuzz-build fuzz-deps fuzz-seed-images

fuzz-deps:
	@missing=""; \
	for p in $(FUZZ_DEB_PKGS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || \
	    missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make fuzz-deps: installing$$missing"; \
	  $(FUZZ_SUDO) apt-get update -qq && \
	  $(FUZZ_SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $$missing; \
	fi

$(FUZZ_GEN)/rc_constants.hpp: $(FUZZ_ROOT)/docs/spec.toml $(FUZZ_ROOT)/tb/gen_constants.py \
                              | fuzz-deps
	$(PYTHON) $(FUZZ_ROOT)/tb/gen_constants.py $(FUZZ_ROOT)/docs/spec.toml $(FUZZ_GEN)

$(FUZZ_OBJ)/scene_%.o: $(FUZZ_ROOT)/tb/scene/%.cpp $(FUZZ_GEN)/rc_constants.hpp | fuzz-deps
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -c $< -o $@

$(FUZZ_OBJ)/golden_%.o: $(FUZZ_ROOT)/tb/golden/%.cpp $(FUZZ_GEN)/rc_constants.hpp | fuzz-deps
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -c $< -o $@

$(FUZZ_OBJ)/%.o: $(FUZZ_SRC)/%.cpp $(FUZZ_GEN)/rc_constants.hpp | fuzz-deps
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -c $< -o $@

$(FUZZ_DIR)/fuzz_obj $(FUZZ_DIR)/fuzz_scene_json: $(FUZZ_DIR)/%: $(FUZZ_OBJ)/%.o $(FUZZ_LIB_OBJS)
	$(FUZZ_CXX) $(FUZZ_LDFLAGS) -fsanitize=fuzzer $^ $(FUZZ_LIBS) -o $@

$(FUZZ_DIR)/fuzz_image: $(FUZZ_OBJ)/fuzz_image.o $(FUZZ_LIB_OBJS) $(FUZZ_GOLDEN_OBJS)
	$(FUZZ_CXX) $(FUZZ_LDFLAGS) -fsanitize=fuzzer $^ $(FUZZ_OIIO_LIBS) $(FUZZ_LIBS) -o $@

$(FUZZ_DIR)/gen_seed_images: $(FUZZ_OBJ)/gen_seed_images.o $(FUZZ_LIB_OBJS)
	$(FUZZ_CXX) $(FUZZ_LDFLAGS) -fsanitize=fuzzer-no-link $^ $(FUZZ_LIBS) -o $@

-include $(wildcard $(FUZZ_OBJ)/*.d)

fuzz-build: fuzz-deps $(FUZZ_BINS)

# Fresh images from the current compiler and image format, into the working corpus of fuzz_image.
fuzz-seed-images: $(FUZZ_DIR)/gen_seed_images
	@mkdir -p $(FUZZ_WORK)/fuzz_image/gen-seeds
	@$(FUZZ_DIR)/gen_seed_images $(FUZZ_WORK)/fuzz_image/gen-seeds > /dev/null

fuzz: fuzz-build fuzz-seed-images
	@echo "make fuzz: $(FUZZ_TARGETS), $(FUZZ_SECONDS) s each (results in $(FUZZ_WORK)/<target>/)"
	@failed=""; \
	for t in $(FUZZ_TARGETS); do \
	  case $$t in \
	    fuzz_obj) max_len=$(FUZZ_MAX_LEN_fuzz_obj); extra="" ;; \
	    fuzz_scene_json) max_len=$(FUZZ_MAX_LEN_fuzz_scene_json); extra="" ;; \
	    fuzz_image) max_len=$(FUZZ_MAX_LEN_fuzz_image); extra="$(FUZZ_WORK)/fuzz_image/gen-seeds" ;; \
	    *) echo "make fuzz: unknown target '$$t' (fuzz_obj, fuzz_scene_json, fuzz_image)"; exit 2 ;; \
	  esac; \
	  dict=""; [ -f $(FUZZ_SRC)/$$t.dict ] && dict="-dict=$(FUZZ_SRC)/$$t.dict"; \
	  FUZZ_FRESH=$(FUZZ_FRESH) FUZZ_SKIP_KNOWN=$(FUZZ_SKIP_KNOWN) \
	    bash $(FUZZ_SRC)/run_fuzzer.sh $$t $(FUZZ_DIR)/$$t $(FUZZ_SRC)/corpus/$$t $(FUZZ_WORK)/$$t \
	    $(FUZZ_SECONDS) $$max_len $$extra -- $$dict $(FUZZ_ARGS) || failed="$$failed $$t"; \
	done; \
	if [ -n "$$failed" ]; then echo "make fuzz: findings in$$failed"; exit 1; fi; \
	echo "make fuzz: nothing found"

# Included from another makefile: keep its default goal; used alone: `fuzz` is the default.
ifeq ($(FUZZ_MK_FIRST),1)
.DEFAULT_GOAL := fuzz
else
.DEFAULT_GOAL := $(FUZZ_MK_GOAL)
endif
