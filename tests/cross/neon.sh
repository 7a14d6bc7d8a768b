#!/usr/bin/env bash
# neon.sh SRC OUT CC QEMU — the cpu backend's NEON loops (gpu/backends/cpu/propagate_neon.c)
# built with Debian's AArch64 cross compiler and run under qemu-user: test_render_propagate,
# which needs only the propagation sources and the core library, compiled for AArch64 with the
# flags gpu/CMakeLists.txt gives those files, must find the neon path, run it, and pass (every
# path against the engine, to 4 float ulps). The vector source is one file for every
# instruction set, so this is how a change to it is checked on the architecture the machine
# running the suite lacks. The detail functions' NEON build (detail_neon.c) is compiled too (its
# values are checked against the scalar ones by test_render_detail on every path it runs on), and
# the batched volume pieces' vector exp, expm1 and log are run (test_render_vec_math).
set -u
src=$1 out=$2 cc=$3 qemu=$4
mkdir -p "$out" || exit 1
inc=(-I"$src/gpu" -I"$src/gpu/backends/cpu" -I"$src/gpu/core" -I"$src/gpu/include" -I"$src/libicshadow/include"
     -I"$src/libicshadow/src" -I"$src/tests")
objs=()
for f in "$src"/libicshadow/src/*.c "$src"/gpu/backends/cpu/propagate.c \
         "$src"/gpu/backends/cpu/propagate_{sse2,avx2,avx512}.c "$src"/gpu/backends/cpu/simd_path.c \
         "$src"/gpu/core/slab_taps.c "$src"/gpu/core/slab_choice.c "$src"/tests/test_render_propagate.c; do
  o=$out/$(basename "$f" .c).o
  "$cc" -std=c11 -O2 -ffp-contract=off "${inc[@]}" -c "$f" -o "$o" || { echo "FAILED: $cc on $f"; exit 1; }
  objs+=("$o")
done
"$cc" -std=c11 -O2 -ffp-contract=fast "${inc[@]}" -c "$src/gpu/backends/cpu/propagate_neon.c" \
  -o "$out/propagate_neon.o" || { echo "FAILED: $cc on propagate_neon.c"; exit 1; }
"$cc" -std=c11 -O2 -ffp-contract=off -Wall -Werror "${inc[@]}" -c "$src/gpu/backends/cpu/detail_neon.c" \
  -o "$out/detail_neon.o" || { echo "FAILED: $cc on detail_neon.c"; exit 1; }
# the vector build, not the stand-in a file makes where its instruction set is not targeted
"${cc%gcc}nm" "$out/detail_neon.o" | grep -q " t noise$" ||
  { echo "FAILED: detail_neon.c did not build its NEON loops"; exit 1; }
"$cc" -o "$out/test_render_propagate" "${objs[@]}" "$out/propagate_neon.o" -lm -lpthread ||
  { echo "FAILED: linking for AArch64"; exit 1; }
# the batched volume pieces' exp, expm1 and log (piece_neon.c, vec_math.h): test_render_vec_math
# against long double (quadruple precision on AArch64)
mobjs=()
for f in "$src"/gpu/backends/cpu/piece_{batch,sse2,avx2,avx512,neon}.c "$src"/tests/test_render_vec_math.c; do
  o=$out/$(basename "$f" .c).o
  "$cc" -std=c11 -O2 -ffp-contract=off -Wall -Werror "${inc[@]}" -c "$f" -o "$o" ||
    { echo "FAILED: $cc on $f"; exit 1; }
  mobjs+=("$o")
done
"${cc%gcc}nm" "$out/piece_neon.o" | grep -q " t first_mean$" ||
  { echo "FAILED: piece_neon.c did not build its NEON loops"; exit 1; }
for o in "${objs[@]}"; do [[ $o == */test_render_propagate.o ]] || mobjs+=("$o"); done
"$cc" -o "$out/test_render_vec_math" "${mobjs[@]}" "$out/propagate_neon.o" -lm -lpthread ||
  { echo "FAILED: linking test_render_vec_math for AArch64"; exit 1; }
sysroot=$(dirname "$(dirname "$("$cc" -print-file-name=libc.so.6)")")
"$qemu" -L "$sysroot" "$out/test_render_propagate" > "$out/run.log" 2>&1; rc=$?
cat "$out/run.log"
grep -q "(neon, apron 8" "$out/run.log" || { echo "FAILED: the neon path did not run"; exit 1; }
"$qemu" -L "$sysroot" "$out/test_render_vec_math" > "$out/vec_math.log" 2>&1; mrc=$?
cat "$out/vec_math.log"
grep -q "^log, neon:" "$out/vec_math.log" || { echo "FAILED: the neon vec_math did not run"; exit 1; }
[ $rc -ne 0 ] && exit $rc
exit $mrc
