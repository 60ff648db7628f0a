# Convenience targets; the scripts are what the README and CI run.
.PHONY: all demo test test-slow bench clean
all:
	bash scripts/build.sh
demo:
	bash scripts/demo.sh
test:
	bash scripts/test.sh
test-slow:
	bash scripts/test.sh --slow
bench: all
	bash bench/run.sh
clean:
	rm -rf build out
