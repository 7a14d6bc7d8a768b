#!/bin/sh
# modules.sh — the renderer's modules (docs/architecture.md "Modules"), through the CLI:
#   missing      with ICS_MODULE_DIR an empty folder (a machine where no module loads): eval,
#                lut, make-env, fit-light and a cpu render work; --backend gl and cl and a scene
#                with a mesh file fail with exit 2, naming the module and where it was looked
#                for, and write nothing; with Assimp's module alone, the reference renders a
#                mesh scene through the meshes' own BVH, and --mc-mesh embree fails so; a
#                module that is a FIFO is refused at once (dlopen would block on it);
#   mapped       which libraries each command maps (LD_DEBUG=files lists every one the loader
#                opens, dlopen included): eval, lut and a cpu render none of LLVM, Embree, TBB,
#                Assimp, OpenCL, EGL or OSMesa; and, so that the check can fail, a gl render
#                maps LLVM or EGL and a cl render OpenCL where those modules are built.
# usage: modules.sh ICSHADOW SCENES_DIR WORK_DIR missing|mapped [gl] [cl] [assimp] [embree]
set -u
cli=$1 scenes=$2 work=$3 what=$4
shift 4
built=" $* "
fail=0
mkdir -p "$work" || exit 1
say() { echo "modules.sh: $*"; }
bad() { say "FAIL: $*"; fail=1; }

# run NAME WANT_RC ERR_REGEX ARGS...: the command's exit status and stderr
run() {
  name=$1 want=$2 pattern=$3
  shift 3
  "$cli" "$@" > "$work/$name.out" 2> "$work/$name.err" < /dev/null
  rc=$?
  [ $rc -eq "$want" ] || bad "$name: exit $rc, expected $want: $(head -c 400 "$work/$name.err")"
  if [ -n "$pattern" ] && ! grep -Eq "$pattern" "$work/$name.err"; then
    bad "$name: stderr does not match '$pattern': $(head -c 400 "$work/$name.err")"
  fi
}

if [ "$what" = missing ]; then
  empty="$work/no_modules"
  mkdir -p "$empty" && rm -f "$empty"/* "$work"/*.exr "$work"/*.glsl "$work"/*.json
  export ICS_MODULE_DIR="$empty"
  echo 0.5 | "$cli" eval ellipk > "$work/eval.out" 2> "$work/eval.err" || bad "eval: $(cat "$work/eval.err")"
  grep -q '^1.854' "$work/eval.out" || bad "eval ellipk 0.5 gave '$(cat "$work/eval.out")'"
  run lut 0 "" lut --size 32 --lang glsl -o "$work/lut.glsl"
  run make_env 0 "" make-env --lights 0.1,0.2,0.01,0.01 --size 64x32 -o "$work/env.exr"
  run fit_light 0 "" fit-light "$work/env.exr" --lights 1 -o "$work/fit.json"
  run render_cpu 0 "" render --backend cpu --resolution 32x24 -o "$work/cpu.exr"
  auto_note=""
  case $built in *" gl "*) auto_note="auto passed over gl: module icshadow-gl.so not found" ;; esac
  run render_auto 0 "$auto_note" render --verbose --resolution 32x24 -o "$work/auto.exr"
  case $built in *" gl "*)
    run render_gl 2 "module icshadow-gl.so not found \\(looked in $empty, set by ICS_MODULE_DIR\\)" \
      render --backend gl --resolution 32x24 -o "$work/gl.exr" ;;
  esac
  case $built in *" cl "*)
    run render_cl 2 "module icshadow-cl.so not found" render --backend cl --resolution 32x24 -o "$work/cl.exr" ;;
  esac
  case $built in *" assimp "*)
    run render_mesh 2 "trefoil.ply: mesh files need Assimp's reader: module icshadow-assimp.so not found" \
      render "$scenes/mesh.json" --resolution 32x24 -o "$work/mesh.exr" ;;
  esac
  case $built in *" assimp "*" embree "*|*" embree "*" assimp "*)
    only="$work/assimp_only"
    mkdir -p "$only" && rm -f "$only"/*
    cp "$(dirname "$cli")/../lib/icshadow/icshadow-assimp.so" "$only/" || bad "no Assimp module to copy"
    export ICS_MODULE_DIR="$only"
    run mc_bvh 0 "" render "$scenes/mesh.json" --backend mc --spp 1 --resolution 16x12 -o "$work/mc.exr"
    grep -q "meshes: own BVH" "$work/mc_bvh.out" || bad "mc without Embree: $(head -c 300 "$work/mc_bvh.out")"
    run mc_embree 2 "mc: meshes through Embree: module icshadow-embree.so not found" \
      render "$scenes/mesh.json" --backend mc --mc-mesh embree --spp 1 --resolution 16x12 -o "$work/mce.exr"
    [ ! -e "$work/mce.exr" ] || bad "mce.exr written after a failure" ;;
  esac
  case $built in *" gl "*) # a module that is a FIFO: refused at once, not opened (dlopen would block)
    fifo="$work/fifo_modules"
    mkdir -p "$fifo" && rm -f "$fifo"/* && mkfifo "$fifo/icshadow-gl.so"
    export ICS_MODULE_DIR="$fifo"
    run render_fifo 2 "icshadow-gl.so is not a regular file" \
      render --backend gl --resolution 16x12 -o "$work/gl.exr" ;;
  esac
  for f in gl cl mesh; do [ ! -e "$work/$f.exr" ] || bad "$f.exr written after a failure"; done
  for f in cpu auto env; do [ -s "$work/$f.exr" ] || bad "$f.exr not written"; done
  [ -s "$work/fit.json" ] && [ -s "$work/lut.glsl" ] || bad "fit-light or lut wrote nothing"
else
  heavy='libLLVM|libembree|libtbb|libassimp|libOpenCL|libEGL|libOSMesa'
  # maps NAME ARGS...: the libraries the loader opened for `icshadow ARGS` (stdin empty)
  maps() {
    name=$1
    shift
    LD_DEBUG=files "$cli" "$@" < /dev/null > /dev/null 2> "$work/$name.ld"
    grep -Eo 'file=[^ ]+' "$work/$name.ld" | sort -u | sed 's/file=//' | tr '\n' ' '
  }
  for c in "eval:eval ellipk" "lut:lut --size 32 --lang glsl -o $work/m.glsl" \
           "cpu:render --backend cpu --resolution 32x24 -o $work/m.exr"; do
    name=${c%%:*}
    libs=$(maps "$name" ${c#*:})
    [ -n "$libs" ] || bad "$name: LD_DEBUG=files listed nothing (is the loader's debug output there?)"
    echo "$libs" | grep -Eq "$heavy" && bad "$name maps $(echo "$libs" | grep -Eo "[^ ]*($heavy)[^ ]*" | tr '\n' ' ')"
    say "$name maps: $libs"
  done
  case $built in *" gl "*)
    libs=$(maps gl render --backend gl --resolution 32x24 -o "$work/m.exr")
    echo "$libs" | grep -Eq 'libLLVM|libEGL' || bad "the control: a gl render maps neither LLVM nor EGL ($libs)" ;;
  esac
  case $built in *" cl "*)
    libs=$(maps cl render --backend cl --resolution 32x24 -o "$work/m.exr")
    echo "$libs" | grep -q 'libOpenCL' || bad "the control: a cl render does not map OpenCL ($libs)" ;;
  esac
  rm -f "$work/m.exr" "$work/m.glsl"
fi
[ $fail -eq 0 ] && say "$what: all as expected"
exit $fail
