#!/usr/bin/env bash
# gallery.sh CLI SCENES — every example scene renders (the scenes of docs/gallery.md): each
# SCENES/*.json at 48 x 36 with --png into a scratch folder, exit 0, a PNG written and named in
# the summary; and again under --model blocker (the gallery's second picture), exit 0. A scene that reads a mesh is skipped, named with the reason, when the binary was
# built without Assimp (its "mesh files need Assimp" message); the others are still checked, and
# the test then exits 77 (skipped) when they passed. Without libpng nothing can be checked: 77.
set -u
cli=$1 scenes=$2
. "$(dirname "$0")/checks.sh"
T="timeout 60"
n=0 skipped=()
for s in "$scenes"/*.json; do
  [ -e "$s" ] || continue
  name=$(basename "$s" .json)
  n=$((n + 1))
  $T "$cli" render "$s" --resolution 48x36 --png "$dir/$name.png" > "$dir/$name.out" 2> "$dir/$name.err"
  rc=$?
  if [ "$rc" -ne 0 ] && grep -q "PNG previews need libpng" "$dir/$name.err"; then
    echo "SKIPPED: PNG previews need libpng (not found at build time)"
    exit 77
  fi
  if [ "$rc" -ne 0 ] && grep -q "mesh files need Assimp" "$dir/$name.err"; then
    echo "SKIPPED $name: mesh files need Assimp (not found at build time)"
    skipped+=("$name")
    continue
  fi
  expect "[ $rc -eq 0 ] && [ \"\$(head -c 4 '$dir/$name.png' | tail -c 3)\" = PNG ] && grep -q '\"png\": \"[^\"]*$name.png\"' '$dir/$name.out'"
  [ "$rc" -eq 0 ] || { echo "$name: exit $rc"; cat "$dir/$name.err"; }
  # the gallery's second picture: the same scene under render.model blocker
  $T "$cli" render "$s" --resolution 48x36 --model blocker --png "$dir/${name}_blocker.png" \
    > "$dir/${name}_blocker.out" 2> "$dir/${name}_blocker.err"
  rc=$?
  expect "[ $rc -eq 0 ] && grep -q '\"model\": \"blocker\"' '$dir/${name}_blocker.out'"
  [ "$rc" -eq 0 ] || { echo "$name, blocker: exit $rc"; cat "$dir/${name}_blocker.err"; }
done
expect "[ $n -gt 0 ]" # an empty or wrong folder is a failure, not a pass
echo "gallery: $n scenes, ${#skipped[@]} skipped${skipped[*]:+ (${skipped[*]})}"
if [ "$fail" -eq 0 ] && [ "${#skipped[@]}" -gt 0 ]; then
  echo "gallery: $pass passed, 0 failed; skipped: ${skipped[*]}"
  exit 77
fi
finish gallery
