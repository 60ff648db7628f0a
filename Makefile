# Convenience targets; the scripts are what the README and CI run.
.PHONY: all demo test test-slow test-sanitize fuzz bench clean
FUZZ_SECONDS ?= 60
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
fuzz:
	FUZZ_SECONDS=$(FUZZ_SECONDS) bash scripts/fuzz.sh
bench: all
	bash bench/run.sh
clean:
	rm -rf build build-sanitize out
