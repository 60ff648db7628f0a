# Convenience targets; the scripts are what the README and CI run.
.PHONY: all demo test test-slow test-sanitize test-tsan fuzz bench bench-build trade clean
FUZZ_SECONDS ?= 60
FUZZ_RUNS ?= -1
all:
	bash scripts/build.sh
demo:
	bash scripts/demo.sh
test:
	bash scripts/test.sh
test-slow:
	bash scripts/test.sh --slow
test-sanitize:
	bash scripts/test-sanitize.sh
test-tsan:
	bash scripts/test-tsan.sh
fuzz:
	FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_RUNS=$(FUZZ_RUNS) bash scripts/fuzz.sh
bench: all
	bash bench/run.sh
bench-build:
	/usr/bin/python3 bench/cold_build.py
trade: all
	/usr/bin/python3 bench/trade_atlas.py
clean:
	rm -rf build build-sanitize build-tsan out
