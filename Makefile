# Convenience front end over CMake. The two set-up commands of the README:
#   make run    install missing packages, build, render the default scene with the Embree
#               reference and with ROMA (the effects it calls for: AO, direct light, GI) into
#               out/, compare them in out/compare/
#   make test   install missing packages, build, run the test suite (ctest, lavapipe, validation on)
#   make test-sanitize   the same suite, Debug build with ASan + UBSan and the shaders' loop guard
#                        (src/vulkan/loop_guard.h) in build-asan (CI runs it too)
#   make test-tsan       the thread tests (ctest label threads: test_threads) built with ThreadSanitizer
#                        in build-tsan (CI runs it too)
#   make test-fuzz       libFuzzer on the glTF loader and the scene builder, 60 s (CI runs it too)
#   make fuzz-trace      differential fuzzing of the trace against its C mirror (tests/fuzz_trace.c):
#                        FUZZ_TRACE_RAYS (1e8) random rays over random scenes and maps, seed
#                        FUZZ_TRACE_SEED (1); about 4 minutes on 2 cores; ctest runs a 60-second slice
#   make test-consumers  build the core library alone (Vulkan and glslang only); install into a temporary prefix and build two out-of-tree consumers
#                        against it (CMake package, pkg-config); then the same with the Debian
#                        packages, installed with dpkg and removed again (root or sudo; CI runs it)
#   make docs            the API reference (doxygen) in build/docs/html
#   make study           what accuracy costs in time: the accuracy runs of roma-bench on the built-in
#                        room (AO, direct light, GI, many lights), direct light, GI and many
#                        lights on the built-in blinds, unbounded AO on 2CylinderEngine and (RES 64
#                        and 128) on the bunny, dragon_res3, tabletop, spot, CesiumMan and Fox,
#                        many lights on those and 2CylinderEngine
#                        (110 to 155 minutes on 2 cores) into
#                        docs/bench and their plots into docs/images
#                        (docs/accuracy-vs-time.md), then generation and trace time as the scene grows
#                        (roma-bench --growth, under a minute); a run cut short resumes where it stopped (the points
#                        it finished are kept in build/ until the run completes); make study-small: the
#                        same at 32x24 (test_bench_accuracy runs that command in ctest)
#   make study-levels    (part of make study) AO of radius 1.5 m on the three shared game levels from
#                        their first camera: ROMA over one grid and with the cascade levels roma-render
#                        picks, screen space, Embree at equal time (about 40 minutes on 2 cores)
BUILD ?= build
JOBS  ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo
OUT ?= out
ASAN_BUILD ?= build-asan
# The shared game levels make study (study-levels) sweeps with cascade levels around each
# level's first camera, AO of radius 1.5 m.
LEVELS_DIR ?= ../shared/scenes/levels
STUDY_LEVELS = oa_dm4 aggressor ctf_compromise
# The shared scenes make study sweeps besides the built-in ones and 2CylinderEngine.
STUDY_SCENES = scenes/bunny.glb scenes/dragon_res3.glb scenes/tabletop.gltf scenes/spot.glb scenes/CesiumMan.glb \
               scenes/Fox.glb
FUZZ_BUILD ?= build-fuzz
TSAN_BUILD ?= build-tsan
FUZZ_TRACE_RAYS ?= 100000000
FUZZ_TRACE_SEED ?= 1

.PHONY: deps configure build run test test-sanitize test-tsan test-fuzz fuzz-trace test-consumers docs study study-levels study-small clean

deps:
	./install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build
	$(BUILD)/apps/roma-render --scene builtin:cornell --tracer embree \
	    --size 480x360 --spp 64 --ao-radius 0.5 --out $(OUT)/reference --stats $(OUT)/reference/stats.json
	$(BUILD)/apps/roma-render --scene builtin:cornell --tracer roma \
	    --size 480x360 --spp 16 --frames 4 --ao-radius 0.5 --out $(OUT)/roma --stats $(OUT)/roma/stats.json
	mkdir -p $(OUT)/compare
	set -e; for e in ao direct gi composed; do \
	    echo "== $$e: ROMA (left) against the Embree reference (right), over covered pixels"; \
	    $(BUILD)/apps/roma-compare $(OUT)/roma/$$e.pfm $(OUT)/reference/$$e.pfm \
	        --mask $(OUT)/reference/coverage.pfm \
	        --side-by-side $(OUT)/compare/$$e.png --heatmap $(OUT)/compare/$${e}_error.png; \
	done

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The suite in a Debug build with AddressSanitizer (leak checks included) and
# UndefinedBehaviorSanitizer; sanitizer options for the tests: tests/CMakeLists.txt.
test-sanitize: deps
	cmake -S . -B $(ASAN_BUILD) -DROMA_SANITIZE=ON -DROMA_LOOP_GUARD=ON -DCMAKE_BUILD_TYPE=Debug
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ctest --output-on-failure -j $(JOBS)

# The thread tests with ThreadSanitizer (a report fails the test: halt_on_error); only their
# targets are built. They run without the validation layer there: its locks would hide races
# (tests/test_threads.c); make test runs them with it.
test-tsan: deps
	cmake -S . -B $(TSAN_BUILD) -DROMA_TSAN=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
	cmake --build $(TSAN_BUILD) -j $(JOBS) --target test_threads
	cd $(TSAN_BUILD) && TSAN_OPTIONS=halt_on_error=1 ctest --output-on-failure -L threads

# The libFuzzer target for the glTF loader and the scene builder, built with clang
# (ASan + UBSan) and run for ROMA_FUZZ_SECONDS (60) from the seeds in tests/fuzz.
test-fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DROMA_FUZZ=ON -DROMA_BUILD_APPS=OFF \
	    -DCMAKE_BUILD_TYPE=RelWithDebInfo
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_scene
	cd $(FUZZ_BUILD) && ctest --output-on-failure -L fuzz || \
	    { grep -E 'ERROR: libFuzzer|SUMMARY|Test unit written|^Base64' Testing/Temporary/LastTest.log; exit 1; }

fuzz-trace: build
	ROMA_VALIDATION=1 $(BUILD)/tests/fuzz_trace --seconds 0 --rays $(FUZZ_TRACE_RAYS) --seed $(FUZZ_TRACE_SEED) \
	    --rays-per-case 1048576

test-consumers: build
	bash tests/consumers/run.sh core . $(BUILD)/consumers/core
	bash tests/consumers/run.sh install $(BUILD) $(BUILD)/consumers/install
	bash tests/consumers/run.sh deb $(BUILD) $(BUILD)/consumers/deb

study-levels: build
	for l in $(STUDY_LEVELS); do \
	    $(BUILD)/apps/roma-bench --accuracy --scene $(LEVELS_DIR)/$$l.glb \
	        --camera "$$(sed -n 1p $(LEVELS_DIR)/$$l.cameras)" --ao-radius 1.5 --cascades auto --no-baselines \
	        --runs 3 --csv docs/bench/$${l}_accuracy.csv --plot docs/images/accuracy_vs_time_$${l}_ao.png \
	        --cache $(BUILD)/study_$$l.cache > docs/bench/$${l}_accuracy.txt && \
	        rm -f $(BUILD)/study_$$l.cache || exit 1; done

study: build study-levels
	$(BUILD)/apps/roma-bench --accuracy --ao-radius 0.5 --runs 3 --csv docs/bench/cornell_accuracy.csv \
	    --plot docs/images/accuracy_vs_time_cornell_ao.png --cache $(BUILD)/study_cornell.cache \
	    > docs/bench/cornell_accuracy.txt
	rm -f $(BUILD)/study_cornell.cache
	$(BUILD)/apps/roma-bench --accuracy --effect direct --runs 3 --csv docs/bench/cornell_direct_accuracy.csv \
	    --plot docs/images/accuracy_vs_time_cornell_direct.png --cache $(BUILD)/study_cornell_direct.cache \
	    > docs/bench/cornell_direct_accuracy.txt
	rm -f $(BUILD)/study_cornell_direct.cache
	$(BUILD)/apps/roma-bench --accuracy --effect gi --runs 3 --csv docs/bench/cornell_gi_accuracy.csv \
	    --plot docs/images/accuracy_vs_time_cornell_gi.png --cache $(BUILD)/study_cornell_gi.cache \
	    > docs/bench/cornell_gi_accuracy.txt
	rm -f $(BUILD)/study_cornell_gi.cache
	$(BUILD)/apps/roma-bench --accuracy --effect lights --runs 3 --csv docs/bench/cornell_lights_accuracy.csv \
	    --plot docs/images/accuracy_vs_time_cornell_lights.png --cache $(BUILD)/study_cornell_lights.cache \
	    > docs/bench/cornell_lights_accuracy.txt
	rm -f $(BUILD)/study_cornell_lights.cache
	$(BUILD)/apps/roma-bench --accuracy --scene builtin:blinds --effect direct --runs 3 \
	    --csv docs/bench/blinds_direct_accuracy.csv --plot docs/images/accuracy_vs_time_blinds_direct.png \
	    --cache $(BUILD)/study_blinds_direct.cache > docs/bench/blinds_direct_accuracy.txt
	rm -f $(BUILD)/study_blinds_direct.cache
	$(BUILD)/apps/roma-bench --accuracy --scene builtin:blinds --effect gi --runs 3 \
	    --csv docs/bench/blinds_gi_accuracy.csv --plot docs/images/accuracy_vs_time_blinds_gi.png \
	    --cache $(BUILD)/study_blinds_gi.cache > docs/bench/blinds_gi_accuracy.txt
	rm -f $(BUILD)/study_blinds_gi.cache
	$(BUILD)/apps/roma-bench --accuracy --scene builtin:blinds --effect lights --runs 3 \
	    --csv docs/bench/blinds_lights_accuracy.csv --plot docs/images/accuracy_vs_time_blinds_lights.png \
	    --cache $(BUILD)/study_blinds_lights.cache > docs/bench/blinds_lights_accuracy.txt
	rm -f $(BUILD)/study_blinds_lights.cache
	$(BUILD)/apps/roma-bench --accuracy --scene scenes/2CylinderEngine.glb --runs 3 --csv docs/bench/engine_accuracy.csv \
	    --plot docs/images/accuracy_vs_time_engine_ao.png --cache $(BUILD)/study_engine.cache \
	    > docs/bench/engine_accuracy.txt
	rm -f $(BUILD)/study_engine.cache
	for f in $(STUDY_SCENES); do s=$$(basename $${f%.*}) && \
	    $(BUILD)/apps/roma-bench --accuracy --scene $$f --res 64,128 --runs 3 --csv docs/bench/$${s}_accuracy.csv \
	        --plot docs/images/accuracy_vs_time_$${s}_ao.png --cache $(BUILD)/study_$$s.cache \
	        > docs/bench/$${s}_accuracy.txt && rm -f $(BUILD)/study_$$s.cache || exit 1; done
	$(BUILD)/apps/roma-bench --accuracy --effect lights --scene scenes/2CylinderEngine.glb --runs 3 \
	    --csv docs/bench/engine_lights_accuracy.csv --plot docs/images/accuracy_vs_time_engine_lights.png \
	    --cache $(BUILD)/study_engine_lights.cache > docs/bench/engine_lights_accuracy.txt
	rm -f $(BUILD)/study_engine_lights.cache
	for f in $(STUDY_SCENES); do s=$$(basename $${f%.*}) && \
	    $(BUILD)/apps/roma-bench --accuracy --effect lights --scene $$f --runs 3 \
	        --csv docs/bench/$${s}_lights_accuracy.csv --plot docs/images/accuracy_vs_time_$${s}_lights.png \
	        --cache $(BUILD)/study_$${s}_lights.cache > docs/bench/$${s}_lights_accuracy.txt && \
	        rm -f $(BUILD)/study_$${s}_lights.cache || exit 1; done
	$(BUILD)/apps/roma-bench --growth scenes/spot.glb,scenes/dragon_res3.glb,scenes/bunny.glb,scenes/dragon_res2.glb \
	    --res 64,128,256 --runs 5 --csv docs/bench/growth.csv --plot docs/images/generation_and_trace_growth.png \
	    > docs/bench/growth.txt
	cat docs/bench/cornell_accuracy.txt docs/bench/cornell_direct_accuracy.txt docs/bench/cornell_gi_accuracy.txt \
	    docs/bench/cornell_lights_accuracy.txt docs/bench/blinds_direct_accuracy.txt docs/bench/blinds_gi_accuracy.txt \
	    docs/bench/blinds_lights_accuracy.txt docs/bench/engine_accuracy.txt \
	    $(foreach f,$(STUDY_SCENES),docs/bench/$(basename $(notdir $(f)))_accuracy.txt) \
	    docs/bench/engine_lights_accuracy.txt \
	    $(foreach f,$(STUDY_SCENES),docs/bench/$(basename $(notdir $(f)))_lights_accuracy.txt) \
	    docs/bench/growth.txt $(foreach l,$(STUDY_LEVELS),docs/bench/$(l)_accuracy.txt)

study-small: build
	mkdir -p $(OUT)/study
	$(BUILD)/apps/roma-bench --small --accuracy --ao-radius 0.5 --csv $(OUT)/study/accuracy.csv \
	    --plot $(OUT)/study/accuracy.png
	$(BUILD)/apps/roma-bench --small --accuracy --effect direct --csv $(OUT)/study/direct_accuracy.csv \
	    --plot $(OUT)/study/direct_accuracy.png
	$(BUILD)/apps/roma-bench --small --accuracy --effect gi --csv $(OUT)/study/gi_accuracy.csv \
	    --plot $(OUT)/study/gi_accuracy.png
	$(BUILD)/apps/roma-bench --small --accuracy --effect lights --csv $(OUT)/study/lights_accuracy.csv \
	    --plot $(OUT)/study/lights_accuracy.png

docs: configure
	cmake --build $(BUILD) --target docs

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) $(OUT)
