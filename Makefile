# Convenience front end over CMake. The two set-up commands of the README:
#   make run    install missing packages, build, render the default scene into out/
#   make test   install missing packages, build, run the test suite (ctest, lavapipe, validation on)
BUILD ?= build
JOBS  ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=RelWithDebInfo
OUT ?= out

.PHONY: deps configure build run test clean

deps:
	./install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build
	$(BUILD)/apps/roma-render --scene builtin:cornell --effects ao,direct,gi,lights \
	    --tracer embree --size 480x360 --spp 64 --ao-radius 0.5 --out $(OUT) --stats $(OUT)/stats.json

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) $(OUT)
