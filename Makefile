# subsurf: the two commands a user needs are `make demo` and `make check`.
BUILD      ?= build
ASAN_BUILD ?= build-asan
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 300
CHECK_FUZZ_SECONDS ?= 10
# The sanitizer stage is built by clang (Debian's clang and libomp), whose
# UBSan checks float-to-integer conversions as well.
ASAN_CC    ?= clang
# The sanitizer and fuzzing trees carry line tables only (-g1, clang's
# -gline-tables-only): all that sanitizer and libFuzzer reports print;
# full -g costs ~10 % more CPU per compile (bench/RESULTS.md).
SAN_CMAKE_FLAGS = -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG"
JOBS       ?= $(shell nproc)
CTEST_JOBS ?= 2
OUT        ?= out
PREFIX     ?= /usr/local

.PHONY: all deps build build-asan build-fuzz check test test-asan fuzz fuzz-check validate \
	bench demo install clean format format-check lint

all: build

deps:
	@bash scripts/install-deps.sh

configure = cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
configure-asan = cmake -S . -B $(ASAN_BUILD) -DCMAKE_C_COMPILER=$(ASAN_CC) \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo $(SAN_CMAKE_FLAGS) -DSUBSURF_SANITIZE=ON >/dev/null

# Everything: library, CLI, plugins, every test (slow ones too) and benchmark.
build: deps
	@$(configure)
	@cmake --build $(BUILD) -j $(JOBS)

build-asan: deps
	@$(configure-asan)
	@cmake --build $(ASAN_BUILD) -j $(JOBS)

# The test stages build only what `ctest -LE slow` runs (CMake's
# check_programs target): no slow tests, no benchmarks.
test: deps
	@$(configure)
	@cmake --build $(BUILD) -j $(JOBS) --target check_programs
	cd $(BUILD) && ctest -LE slow --output-on-failure -j $(CTEST_JOBS)

# AddressSanitizer + UBSan (clang); OpenMP's runtime keeps thread pools alive at exit,
# which LeakSanitizer would report as leaks of ours.
# CTest starts the tests that took longest last time first (CTestCostData.txt);
# a fresh sanitizer tree takes the Release tree's times, so that its longest
# tests do not start last and leave one core idle at the end.
test-asan: deps
	@$(configure-asan)
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target check_programs
	@mkdir -p $(ASAN_BUILD)/Testing/Temporary
	@test -f $(ASAN_BUILD)/Testing/Temporary/CTestCostData.txt || \
	  ! test -f $(BUILD)/Testing/Temporary/CTestCostData.txt || \
	  cp $(BUILD)/Testing/Temporary/CTestCostData.txt $(ASAN_BUILD)/Testing/Temporary/
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/scripts/lsan.supp:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest -LE slow --output-on-failure -j $(CTEST_JOBS)

# libFuzzer harnesses (tests/fuzz), clang with ASan + UBSan.
build-fuzz: deps
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  $(SAN_CMAKE_FLAGS) -DSUBSURF_FUZZ=ON -DSUBSURF_WERROR=OFF >/dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzzers

# Each harness for FUZZ_SECONDS (make fuzz FUZZ_SECONDS=3600).
fuzz: build-fuzz
	bash scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

fuzz-check: build-fuzz
	bash scripts/fuzz.sh $(FUZZ_BUILD) $(CHECK_FUZZ_SECONDS)

# The C and C++ sources as .clang-format lays them out.
FORMAT_FILES = git ls-files '*.c' '*.h' '*.cpp'

format:
	@$(FORMAT_FILES) | xargs clang-format -i

# Citations a reader of the repository cannot follow: the design brief's
# sections, its seed files, issue numbers, files outside the repository. Code
# and docs cite papers by their key in docs/references.md instead.
CITATIONS = SPEC [0-9]|\(SPEC[ ;)]|[Ss]eeds? 00[0-9]|[Ii]ssues? \#?[0-9]|DESIGN\.md|\.\./shared|the seeds'

format-check: deps
	@$(FORMAT_FILES) | xargs clang-format --dry-run -Werror || \
	  { echo "format-check: run 'make format' (clang-format, .clang-format)"; exit 1; }
	@! git ls-files -z ':!Makefile' | xargs -0 grep -nIE "$(CITATIONS)" || \
	  { echo "format-check: cite papers by their docs/references.md key and equation number"; exit 1; }

# clang-tidy with .clang-tidy's checks over every library and CLI source, using
# the compile commands of a Release tree configured for it.
lint: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
	@git ls-files 'src/*.c' | xargs clang-tidy -p $(BUILD) --quiet

# Formatting, the Release build and every fast test, then the same tests under
# ASan+UBSan, then a short run of every fuzzer.
check: format-check test test-asan fuzz-check

# Slow model-versus-reference validations (minutes to hours); see README.
validate: build
	cd $(BUILD) && ctest -L slow --output-on-failure -j 1
	bash scripts/validate.sh $(BUILD) $(OUT)/validate

bench: build
	bash scripts/bench.sh $(BUILD)

demo: build
	@bash scripts/demo.sh $(BUILD) $(OUT)

# The library, its headers, a pkg-config file, the CLI and the Python module
# under PREFIX (docs/install.md).
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD)
