# Thin front door over CMake + CTest. See README.md.
BUILD      ?= build
ASAN_BUILD ?= build-asan
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 600
PREFIX     ?= /usr/local
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
PYTHON     ?= /usr/bin/python3
CMAKE_ARGS ?=

.PHONY: all deps mitsuba configure test test-asan test-fuzz fuzz demo figs notebooks bench analysis python error-vs-time error-by-effect gallery install clean

all: configure
	cmake --build $(BUILD) -j $(JOBS)

deps:
	scripts/deps.sh

# the packages of one job only (scripts/deps.sh JOB): a user without root who lacks a package
# the job does not use can still run it
deps-%:
	scripts/deps.sh $*

# Mitsuba 3 for the outside check (tests/mitsuba.cmake): a virtual environment under the build
# tree with Debian's numpy and matplotlib, the PyPI wheel pinned (PyPI must be reachable).
# `make test MITSUBA=0` leaves the check out (it is then reported as skipped, with the reason).
MITSUBA      ?= 1
MITSUBA_PIN   = 3.9.1
MITSUBA_VENV  = $(BUILD)/mitsuba-venv
MITSUBA_PROBE = import mitsuba as m; assert m.__version__ == "$(MITSUBA_PIN)"; m.set_variant("scalar_rgb")
mitsuba: deps
	@$(MITSUBA_VENV)/bin/python -c '$(MITSUBA_PROBE)' 2>/dev/null || { \
	  echo "== Mitsuba $(MITSUBA_PIN) into $(MITSUBA_VENV) (PyPI)"; \
	  $(PYTHON) -m venv --system-site-packages $(MITSUBA_VENV) && \
	  $(MITSUBA_VENV)/bin/pip install --quiet --disable-pip-version-check mitsuba==$(MITSUBA_PIN) && \
	  $(MITSUBA_VENV)/bin/python -c '$(MITSUBA_PROBE)'; }

ifeq ($(MITSUBA),1)
TEST_MITSUBA = mitsuba
ENFORCE_MITSUBA = -DICS_ENFORCE_MITSUBA=ON -UICS_MITSUBA_PYTHON
else
TEST_MITSUBA =
ENFORCE_MITSUBA = -DICS_ENFORCE_MITSUBA=OFF -DICS_MITSUBA_PYTHON=
endif

configure:
	@test -f $(BUILD)/CMakeCache.txt || cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

# `make test` runs after scripts/deps.sh has installed every component, so a missing one is a
# configuration error there, never a silently skipped test.
ENFORCE = -DICS_ENFORCE_MPFR=ON -DICS_ENFORCE_OPENCL=ON -DICS_ENFORCE_OPENEXR=ON \
          -DICS_ENFORCE_JANSSON=ON -DICS_ENFORCE_GLSLANG=ON -DICS_ENFORCE_PNG=ON \
          -DICS_ENFORCE_ASSIMP=ON -DICS_ENFORCE_EMBREE=ON -DICS_ENFORCE_GL=ON

# Release build: fast + medium labels; then the same fast tests under ASan+UBSan (the Mitsuba
# check is medium: it does not run there).
test: deps $(TEST_MITSUBA)
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(ENFORCE) $(ENFORCE_MITSUBA) $(CMAKE_ARGS)
	cmake --build $(BUILD) -j $(JOBS)
	cd $(BUILD) && ctest --output-on-failure -L 'fast|medium' -j $(JOBS)
	$(MAKE) test-asan
	$(MAKE) test-fuzz

# The libFuzzer harnesses (fuzz/, clang with ASan+UBSan), a few seconds each from their seed
# corpora; `make fuzz FUZZ_SECONDS=N` runs each for N seconds (default 600) and prints
# executions, coverage and findings.
FUZZ_TARGETS = fuzz_exr_read fuzz_lights_spec fuzz_lights_file fuzz_scene_json fuzz_mesh_file
test-fuzz:
	CC=clang cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=Debug -DICS_FUZZ=ON -DICS_ENFORCE_OPENEXR=ON -DICS_ENFORCE_ASSIMP=ON \
	  -DICS_ENFORCE_JANSSON=ON -DICS_MITSUBA_PYTHON= $(CMAKE_ARGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(FUZZ_TARGETS)
	cd $(FUZZ_BUILD) && ctest --output-on-failure -L fuzz -j $(JOBS)

fuzz: deps-fuzz
	CC=clang cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=Debug -DICS_FUZZ=ON -DICS_ENFORCE_OPENEXR=ON -DICS_ENFORCE_ASSIMP=ON \
	  -DICS_ENFORCE_JANSSON=ON -DICS_MITSUBA_PYTHON= $(CMAKE_ARGS)
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(FUZZ_TARGETS)
	@for h in $(FUZZ_TARGETS); do fuzz/run.sh $(FUZZ_BUILD)/bin/$$h fuzz/corpus/$${h#fuzz_} $(FUZZ_SECONDS) || exit 1; done

test-asan:
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DICS_SANITIZE=ON $(ENFORCE) -DICS_MITSUBA_PYTHON= $(CMAKE_ARGS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ctest --output-on-failure -L 'fast' -j $(JOBS)

# The main job on embedded defaults (no input files): the default scene rendered with the slab
# renderer (its plan, the image as EXR + PNG, the time per pass), then the numerics behind it:
# LUT report and header, the elliptical kernel of a light, CLT convergence of the Dirac kernel,
# isolines correct vs iterative, and an environment map of three Fig. 14-like lights fitted back
# to Gaussian lights.
DEMO_LIGHTS = -0.55,0.35,0.08,0.08,0,1,0.2,1,0.2:0.6,0.3,0.32,0.32,0,2,1,0.2,0.1:0.05,-0.6,0.3,0.002,-70,1,0.15,0.25,1
demo: deps-demo all
	@mkdir -p out
	@echo "== the default scene: its render plan (icshadow plan), then the render (icshadow render)"
	$(BUILD)/bin/icshadow plan -o out/default_plan.json
	@echo "wrote out/default_plan.json"
	$(BUILD)/bin/icshadow render -o out/default.exr --png out/default.png
	@echo "wrote out/default.exr and out/default.png"
	@echo "== lookup-table error against size and evaluation time (icshadow lut --report)"
	$(BUILD)/bin/icshadow lut --report
	@echo "== example GLSL header (icshadow lut --size 64 --lang glsl)"
	$(BUILD)/bin/icshadow lut --size 64 --lang glsl -o out/icshadow_lut_64.glsl
	@echo "wrote out/icshadow_lut_64.glsl"
	@echo "== 2-sample elliptical kernel for a light with variances (0.8, 0.2) rotated 30 degrees"
	$(BUILD)/bin/icshadow kernel ellipse --varx 0.8 --vary 0.2 --angle 30 --samples 2
	@echo "== CLT: sup distance of n steps on an edge to the Gaussian cdf (top-hat, then Dirac; 36 px^2)"
	$(BUILD)/bin/icshadow clt --kernel tophat --var 36 --steps 1,10,100,1000 --rate
	$(BUILD)/bin/icshadow clt --kernel dirac --var 36 --steps 1,10,100,1000 --rate
	@echo "== half-shadow isoline at d = 4 (d1 = 1) for a skewed light: correct vs iterative"
	$(BUILD)/bin/icshadow isoline --light 'mix:0.8,0,0.25;0.2,2,0.25' --level 0.5 --distance 4 --d1 1 --slab 0.0625 --model correct
	$(BUILD)/bin/icshadow isoline --light 'mix:0.8,0,0.25;0.2,2,0.25' --level 0.5 --distance 4 --d1 1 --slab 0.0625 --model iterative
	@echo "== environment map of three Gaussian lights over a sky, fitted back with K = 4"
	$(BUILD)/bin/icshadow make-env --lights '$(DEMO_LIGHTS)' --sky 0.02,0.03,0.05 --size 512x256 -o out/demo_env.exr
	$(BUILD)/bin/icshadow fit-light out/demo_env.exr --lights 4 -o out/demo_lights.json
	@echo "wrote out/demo_env.exr and out/demo_lights.json"

# Every paper_figs/*.py takes --cli and --out and writes PNG + CSV.
figs: deps-figs all
	@set -e; for f in paper_figs/*.py; do echo "== $$f"; $(PYTHON) $$f --cli $(BUILD)/bin/icshadow --out out/figs; done

# Execute notebooks/iterative_shadows.ipynb headless into out/notebooks (kernel python3 = /usr/bin/python3 through
# the repo's kernel spec in notebooks/kernels; the CLI path goes in as ICSHADOW_CLI). The absolute
# paths come from the shell, quoted: $(CURDIR) and $(abspath) split a checkout path with blanks.
notebooks: deps-notebooks python
	JUPYTER_PATH="$$(pwd)/notebooks" PYDEVD_DISABLE_FILE_VALIDATION=1 PYTHONPATH="$$(cd "$(BUILD)" && pwd)/python-pkg" ICSHADOW_CLI="$$(cd "$(BUILD)" && pwd)/bin/icshadow" $(PYTHON) -m nbconvert \
	  --to notebook --execute --ExecutePreprocessor.kernel_name=python3 --ExecutePreprocessor.timeout=600 \
	  --output-dir out/notebooks notebooks/iterative_shadows.ipynb

# Every bench/*.cmake adds a bench_* program to the `benchmarks` target; the peer primitives are
# benchmarked by `icshadow bench KIND`. Each prints CSV.
BENCH_KINDS ?= sat2d sat3d minmax occtex
bench: deps-bench all
	cmake --build $(BUILD) --target benchmarks -j $(JOBS)
	@set -e; for b in $(BUILD)/bin/bench_*; do echo "== $$b"; $$b; done
	@b=cpu; if $(BUILD)/bin/icshadow render --backends | grep '^cl ' | grep -qv 'not available'; then b=cpu,cl; fi; \
	  set -e; for k in $(BENCH_KINDS); do \
	    case $$k in sat2d|sat3d|minmax) o="--backend $$b";; *) o=;; esac; \
	    echo "== icshadow bench $$k $$o"; $(BUILD)/bin/icshadow bench $$k $$o; done
	@echo "== icshadow bench sat3d --lights (CSAT / SSAT against brute-force marching)"
	$(BUILD)/bin/icshadow bench sat3d --lights
	@echo "== icshadow bench minmax --scene noise (a hard, forest-like scene)"
	$(BUILD)/bin/icshadow bench minmax --scene noise
	@echo "== icshadow bench minmax --svd-table (error of the N-term SVD integrand)"
	$(BUILD)/bin/icshadow bench minmax --svd-table
	@echo "== icshadow bench frame (the default scene: skipping, dense and Monte Carlo at 16 spp, side by side)"
	$(BUILD)/bin/icshadow bench frame --resolution 320x240,768x768 --reps 5
	@# cl when built and available; gl only where auto takes it (a GPU): on llvmpipe it would add
	@# a quarter of an hour at 50-120 ns/px/slab (docs/backend_gl.md; `--backend cpu,gl` by hand)
	@b=cpu; if $(BUILD)/bin/icshadow render --backends | grep '^cl ' | grep -qv 'not available'; then b=cpu,cl; fi; \
	  if $(BUILD)/bin/icshadow render --resolution 8x8 -o $(BUILD)/bench_probe.exr 2>/dev/null | grep -q '"backend": "gl"'; then b=$$b,gl; fi; \
	  echo "== icshadow bench slab --backend $$b (the slab step per kernel member, backends side by side)"; \
	  $(BUILD)/bin/icshadow bench slab --backend $$b

# Stability sweep of the exact functions: max ulp error vs MPFR and ns per call per region, and
# the scipy comparison; 5000 inputs per region, the size docs/analysis.md and README quote.
ANALYSIS_SAMPLES = 5000
analysis: deps-analysis all
	@mkdir -p out/analysis
	$(BUILD)/bin/stability_sweep --samples $(ANALYSIS_SAMPLES) --progress > out/analysis/stability.csv.tmp
	mv out/analysis/stability.csv.tmp out/analysis/stability.csv
	$(PYTHON) analysis/peer_accuracy.py --cli $(BUILD)/bin/icshadow --samples $(ANALYSIS_SAMPLES) --out out/analysis/peer_accuracy.csv
	@echo "wrote out/analysis/stability.csv and out/analysis/peer_accuracy.csv"

# The Python package (python/, docs/python.md) over this build's libraries, into $(PY_PKG): the
# analysis drivers import it from there (PYTHONPATH). A user's own install: README "Using it
# from Python" (a virtual environment and pip install ./python).
PY_PKG = $(BUILD)/python-pkg
python: deps-python all
	rm -rf "$(PY_PKG)"
	ICSHADOW_BUILD_DIR="$$(cd "$(BUILD)" && pwd)" $(PYTHON) -m pip install --quiet --disable-pip-version-check --root-user-action=ignore \
	  --no-build-isolation --no-index --no-deps --target "$(PY_PKG)" ./python
	@echo "icshadow package in $(PY_PKG): PYTHONPATH=$(PY_PKG) python3 -c 'import icshadow'"

# Error against run time on the default scene (docs/results.md): a 1024-spp Monte-Carlo
# reference (made once: out/analysis/error_vs_time_ref.exr), then every configuration and the
# reference itself at 4..256 spp, interleaved over 3 rounds. 5 to 25 minutes on a 2-core VM, by its load.
error-vs-time: deps python
	@mkdir -p out/analysis
	PYTHONPATH="$$(cd "$(BUILD)" && pwd)/python-pkg" $(PYTHON) analysis/error_vs_time.py --ref out/analysis/error_vs_time_ref.exr \
	  --csv out/analysis/error_vs_time.csv --plot out/analysis/error_vs_time.png \
	  --images out/analysis/error_vs_time_images.png

# the models' error by effect (render.model patel, solid, surface) on the default scene, two
# solid-object scenes and Patel's Fig. 18-21 against the Monte-Carlo reference (docs/results.md;
# about 5 minutes)
error-by-effect: deps-figs all
	$(PYTHON) analysis/error_by_effect.py --cli $(BUILD)/bin/icshadow --out out/analysis

# the gallery (docs/gallery.md): every scenes/*.json rendered into docs/images/gallery/, under its
# own settings and under --model blocker, with their frame times (median of 3) and their errors
# against the Monte-Carlo reference; about 6 minutes
gallery: deps-demo all
	$(PYTHON) analysis/gallery.py --cli $(BUILD)/bin/icshadow

install: all
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) out
