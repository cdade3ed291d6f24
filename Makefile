# seatwin — all set-up happens here: `make demo` and `make test` create .venv when
# missing, install the Debian packages the project needs (when run as root) and the
# package with its dependencies.
PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed
# Debian packages: Mesa EGL for headless rasterising, Chromium to check the HTML report, ROS 1's own rosbag
# (ros_comm, for /usr/bin/python3) to check that ROS reads seatwin's ROS 1 bags.
DEB_PACKAGES := libegl1 libgl1-mesa-dri libgl1 chromium python3-rosbag

.PHONY: demo test test-fast lint deb venv clean

$(STAMP): pyproject.toml
	@$(MAKE) --no-print-directory deb
	@test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -e '.[test]'
	@touch $(STAMP)

venv: $(STAMP)

deb:
	@if [ "$$(id -u)" = "0" ] && command -v apt-get >/dev/null; then \
	  missing=""; for p in $(DEB_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	  if [ -n "$$missing" ]; then echo "installing Debian packages:$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing >/dev/null; fi; \
	else echo "not root: make sure these Debian packages are installed: $(DEB_PACKAGES)"; fi

demo: $(STAMP)
	rm -rf runs/demo
	$(VENV)/bin/seatwin demo --out runs/demo

# Tests run on TEST_WORKERS pytest-xdist workers (one per core of a 2-core machine); --dist loadgroup keeps
# the tests of one xdist_group (a chain of README commands, the Ray tests) on one worker. TEST_WORKERS=0: one process.
TEST_WORKERS ?= 2
PYTEST := $(PY) -m pytest -n $(TEST_WORKERS) --dist loadgroup

# The whole suite, after lint. Tests run even when lint fails; the target fails if either
# does. pytest's exit status 5 (no test collected) is reported as such.
test: $(STAMP)
	@lint=0; $(MAKE) --no-print-directory lint || lint=$$?; \
	$(PYTEST) -q --durations=25; rc=$$?; \
	if [ $$rc -eq 5 ]; then echo "no tests were collected"; fi; \
	if [ $$lint -ne 0 ]; then echo "make test: lint failed (see above; 'make lint' shows it again)"; fi; \
	if [ $$rc -ne 0 ]; then exit $$rc; fi; exit $$lint

# The fast lane: everything not marked slow (long tests, end to end runs on ../shared/data).
test-fast: $(STAMP)
	$(PYTEST) -q --durations=10 -m "not slow"

lint: $(STAMP)
	$(VENV)/bin/ruff check src tests benchmarks
	$(VENV)/bin/ruff format --check src tests benchmarks

clean:
	rm -rf $(VENV) runs build *.egg-info
