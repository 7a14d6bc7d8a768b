#!/usr/bin/env bash
# The gl backend on a GPU, in one short run (docs/backend_gl.md "On a GPU"):
#   1. builds the renderer (Release, gl backend required) into BUILD (default build-gpu);
#   2. checks that an EGL device that is not Mesa's software one is there, and that the gl backend
#      on it agrees with the cpu backend (test_render_gl: every scene and variant, max 1e-5, RMS
#      1e-6), and that its layered depth image built on the device is the plan's (test_gl_ldi);
#   3. renders the Fig. 11 setup (paper_figs/patel_fig11.py's disk over a receiver, high
#      variance) at 768 x 768 per kernel - 2- and 3-sample ellipse, Poisson 8 and 16, 19 x 19
#      Gaussian - REPS times on cpu, gl and gl-ldi (gl with --gl-ldi device: the layered depth
#      image rebuilt on the device every frame, as Patel's is), and prints a CSV: kernel,
#      backend, median ms per frame (the render; the plan's geometry pass apart), min, max, fps,
#      the device LDI's share (gl-ldi), Patel's GTX 480 fps (a different
#      scene, renderer and machine: only the ordering compares), the gl image's max difference to
#      the cpu image.
# usage: scripts/gpu_fig11.sh [REPS]   (environment: BUILD, JOBS; ICS_FIG11_ANY_DEVICE=1 runs
# steps 2 and 3 on whatever device the gl backend gets, llvmpipe too, to try the script itself;
# ICS_FIG11_PREBUILT=DIR skips step 1 and takes icshadow, test_render_gl and test_gl_ldi from DIR,
# for a GPU machine without the build's packages: build them elsewhere, carry them with their
# shared libraries, and set LD_LIBRARY_PATH)
set -euo pipefail
cd "$(dirname "$0")/.."
reps=${1:-5}
build=${BUILD:-build-gpu}
jobs=${JOBS:-$(nproc)}
bin=${ICS_FIG11_PREBUILT:-$build/bin}
if [ -z "${ICS_FIG11_PREBUILT:-}" ]; then
  for tool in cmake cc python3; do
    command -v "$tool" >/dev/null || { echo "gpu_fig11: $tool is missing (scripts/deps.sh installs it)" >&2; exit 2; }
  done
  mkdir -p "$build"
  log="$build/gpu_fig11_configure.log"
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DICS_ENFORCE_JANSSON=ON -DICS_ENABLE_GL=ON \
    -DICS_ENFORCE_MITSUBA=OFF \
    -DICS_MITSUBA_PYTHON= >"$log" 2>&1 ||
    { tail -20 "$log" >&2; echo "gpu_fig11: configuration failed (log: $log)" >&2; exit 2; }
  grep -q "gl backend: ON" "$log" ||
    { echo "gpu_fig11: the gl backend is not built (needs libegl-dev and libgl-dev, or libosmesa6-dev)" >&2; exit 2; }
  cmake --build "$build" -j "$jobs" --target icshadow_cli test_render_gl test_gl_ldi >/dev/null
fi
cli="$bin/icshadow"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export ICS_GL_CONTEXT=egl MESA_SHADER_CACHE_DIR="$tmp/mesa_cache"

# 2. a GPU, and agreement on it
"$cli" render --backend gl --resolution 64x64 -o "$tmp/probe.exr" >"$tmp/probe.json"
device=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["device"])' "$tmp/probe.json")
echo "gpu_fig11: gl device: $device" >&2
if [[ "$device" != *egl-device* ]]; then
  if [ "${ICS_FIG11_ANY_DEVICE:-0}" = 1 ]; then
    echo "gpu_fig11: not a GPU; going on (ICS_FIG11_ANY_DEVICE=1)" >&2
  else
    echo "gpu_fig11: no GPU: the gl backend runs on '$device' (EGL lists Mesa's software device only)" >&2
    exit 3
  fi
fi
"$bin/test_render_gl" gl scenes/*.json >&2
"$bin/test_gl_ldi" tests/data scenes/*.json >&2

# 3. Fig. 11 at 768^2 per kernel, gl and cpu side by side
python3 - "$tmp/fig11.json" <<'EOF'
import json, sys
sys.path.insert(0, "paper_figs/lib")
from fig11_setup import HIGH_VAR, scene  # the setup of paper_figs/patel_fig11.py
json.dump(scene(HIGH_VAR, 768), open(sys.argv[1], "w"))
EOF
echo "kernel,backend,ms_median,ms_min,ms_max,fps,patel_gtx480_fps,max_diff_to_cpu,ldi_device_ms_median"
for m in ellipse:2:22.58 ellipse:3:20.34 poisson:8:11.83 poisson:16:6.71 gauss:19:0.48; do
  IFS=: read -r kernel samples patel <<<"$m"
  for b in cpu gl gl-ldi; do
    opts=(--backend "${b%-ldi}")
    [ "$b" = gl-ldi ] && opts+=(--gl-ldi device)
    for r in $(seq "$reps"); do
      "$cli" render "$tmp/fig11.json" "${opts[@]}" --kernel "$kernel" --samples "$samples" \
        -o "$tmp/$b.exr" >"$tmp/$b.$r.json"
    done
  done
  "$cli" render "$tmp/fig11.json" --backend gl --kernel "$kernel" --samples "$samples" \
    -o "$tmp/gl.exr" --compare "$tmp/cpu.exr" >"$tmp/cmp.json"
  python3 - "$tmp" "$reps" "$kernel$samples" "$patel" <<'EOF'
import json, statistics, sys
tmp, reps, name, patel = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
diff = json.load(open(f"{tmp}/cmp.json"))["compare"]["max_error"]
for b in ("cpu", "gl", "gl-ldi"):
    runs = [json.load(open(f"{tmp}/{b}.{r}.json")) for r in range(1, reps + 1)]
    ms = [j["ms_render"] for j in runs]
    med = statistics.median(ms)
    ldi = statistics.median([j["ms_geometry_device"] for j in runs]) if b == "gl-ldi" else None
    print(f"{name},{b},{med:.2f},{min(ms):.2f},{max(ms):.2f},{1000 / med:.2f},{patel},"
          + (f"{diff:.3g}" if b == "gl" else "") + "," + (f"{ldi:.2f}" if ldi is not None else ""))
EOF
done
