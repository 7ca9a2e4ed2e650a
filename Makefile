# tightfit — top-level entry points. `make demo` and `make test` install the Debian
# packages (scripts/install-deps.sh), build in Release and run.
JOBS ?= $(shell nproc)
BUILD ?= build/release
ASAN_BUILD ?= build/asan
WERROR ?= $(if $(CI),ON,OFF)
DEMO_OUT ?= out/demo
# Ninja schedules the object files of all targets together (Make waits for each layer's
# library before compiling the next layer): the build keeps both cores busy.
GENERATOR ?= Ninja
# A build folder configured with another generator is configured afresh.
configure = if [ -f $(1)/CMakeCache.txt ] && ! grep -qx 'CMAKE_GENERATOR:INTERNAL=$(GENERATOR)' $(1)/CMakeCache.txt; \
	  then rm -rf $(1)/CMakeCache.txt $(1)/CMakeFiles; fi; cmake -S . -B $(1) -G '$(GENERATOR)'

.PHONY: deps build build-asan test test-asan test-memcheck demo bench fuzz clean format format-check check-naming

deps:
	bash scripts/install-deps.sh

build: deps
	$(call configure,$(BUILD)) -DCMAKE_BUILD_TYPE=Release -DTIGHTFIT_WERROR=$(WERROR)
	cmake --build $(BUILD) -j $(JOBS)

build-asan: deps
	$(call configure,$(ASAN_BUILD)) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O1 \
	  -DTIGHTFIT_SANITIZE=ON -DTIGHTFIT_BUILD_BENCH=OFF -DTIGHTFIT_WERROR=OFF
	cmake --build $(ASAN_BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# Fast tests only (names ending in Slow are skipped) under AddressSanitizer + UBSan.
# Warnings are not errors in this build: GCC 12 gives false -Wmaybe-uninitialized and
# -Wrestrict positives at -O1 with sanitizers; the Release build enforces -Werror.
test-asan: build-asan
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp \
	  ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS) -E 'Slow'

# The reader, parser and physics-kernel tests of the Release build under valgrind's
# memcheck (scripts/memcheck.sh): no second build, so CI runs it on every change.
test-memcheck: build
	JOBS=$(JOBS) bash scripts/memcheck.sh $(CURDIR)/$(BUILD)

demo: build
	bash scripts/demo.sh $(BUILD)/tightfit $(DEMO_OUT)

# libFuzzer on every reader (scripts/fuzz.sh): FUZZ_SECONDS per target (default 60),
# FUZZ_JOBS targets at once (default 1).
fuzz: build
	bash scripts/fuzz.sh

bench: build
	bash scripts/bench.sh $(BUILD)

# clang-format (.clang-format) over every C++ file in git; format-check fails on any
# file it would change (CI), check-naming runs clang-tidy's naming rules (.clang-tidy)
# over the sources of the Release build (scripts/check_naming.py; CONTRIBUTING.md).
format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

format-check: deps
	git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run -Werror

check-naming: build
	python3 scripts/check_naming.py $(BUILD) --jobs $(JOBS)

clean:
	rm -rf build out
