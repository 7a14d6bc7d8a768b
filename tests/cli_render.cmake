# CLI tests for `icshadow render` and `icshadow plan`: --help, the default scene, the contract
# example, the plan's JSON, and bad input refused with the problem named, exit 2 and no output file.
if(ICS_HAVE_RENDER)
set(rd ${CMAKE_CURRENT_BINARY_DIR}/tmp/cli_render)
file(MAKE_DIRECTORY ${rd})
set(disk ${CMAKE_SOURCE_DIR}/scenes/disk.json)
ics_cli_test(NAME cli_render_help RC 0 ARGS "render|--help" OUT "usage: icshadow render \\[SCENE\\].*--backend")
ics_cli_test(NAME cli_plan_help RC 0 ARGS "plan|--help" OUT "usage: icshadow plan \\[SCENE\\].*omitted")
# the table in order: gl first when built (auto takes it only on a GPU), then cpu, ..., mc last
if(ICS_HAVE_GL)
  set(ics_first_backends "gl +[^\n]*auto picks it on a GPU[^\n]*\n +--gl-context auto\\|egl\\|osmesa \\(default: \\$ICS_GL_CONTEXT\\)\n +--gl-ldi [^\n]*\ncpu ")
  set(ics_built "gl cpu")
else()
  set(ics_first_backends "cpu ")
  set(ics_built "cpu")
endif()
ics_cli_test(NAME cli_render_backends RC 0 ARGS "render|--backends" OUT "^${ics_first_backends}.*\nmc ")
# the default scene, small: a JSON summary naming the backend and the passes' times
ics_cli_test(NAME cli_render_default RC 0 ARGS "render|--resolution|64x48|--png|${rd}/default.png"
  OUT "^{\"scene\": \"default\", \"backend\": \"cpu\".*\"resolution\": \\[64, 48\\].*\"ms_convolution\": [0-9.e+-]+.*\"png\": ")
ics_cli_test(NAME cli_render_disk RC 0 ARGS "render|${disk}|-o|${rd}/disk.exr|--threads|1"
  OUT "\"scene\": \"[^\"]*disk.json\".*\"threads\": 1, \"resolution\": \\[128, 128\\].*\"slabs\": 101,")
ics_cli_test(NAME cli_plan_disk RC 0 ARGS "plan|${disk}"
  OUT "\"slabs\": 101,.*\"memory_bytes\": [0-9]+,.*\"passes\": \\[.*\"name\": \"layered_depth_image\", \"bytes\": [0-9]+.*\"light\": 0, \"taps\": [0-9]+.*\"omitted\": \\[.*\"name\": \"detail\", \"reason\": \"no material has volumetric detail\"")
ics_cli_test(NAME cli_plan_print_scene RC 0 ARGS "plan|--print-scene" OUT "\"camera\": .*\"objects\"")
# bad input: exit 2, the problem named, no output file left
ics_cli_test(NAME cli_render_missing_scene RC 2 ARGS "render|/nonexistent/scene.json|-o|${rd}/m.exr"
  ERR "icshadow render: /nonexistent/scene.json: cannot open scene file" NOFILE ${rd}/m.exr)
ics_cli_test(NAME cli_render_nothing RC 2 ARGS "render|${disk}" ERR "nothing to write: give -o OUT.exr and/or --png OUT.png [(]or only measure: --compare REF.exr or --reference N[)]")
ics_cli_test(NAME cli_render_unknown_option RC 2 ARGS "render|--bogus" ERR "icshadow render: unknown option '--bogus'")
ics_cli_test(NAME cli_render_bad_kernel RC 2 ARGS "render|${disk}|--kernel|box|-o|${rd}/k.exr"
  ERR "--kernel: unknown value 'box' \\(expected ellipse, poisson, gauss, tophat\\)" NOFILE ${rd}/k.exr)
ics_cli_test(NAME cli_render_bad_resolution RC 2 ARGS "render|--resolution|0x10|-o|${rd}/r.exr"
  ERR "--resolution: expected WxH with W, H in 1..16384" NOFILE ${rd}/r.exr)
ics_cli_test(NAME cli_render_bad_backend RC 2 ARGS "render|--backend|vulkan|-o|${rd}/b.exr"
  ERR "--backend: no backend named 'vulkan' \\(built: ${ics_built}" NOFILE ${rd}/b.exr)
ics_cli_test(NAME cli_render_stdout RC 2 ARGS "render|-o|-" ERR "not to stdout")
ics_cli_test(NAME cli_render_bad_slab RC 2 ARGS "render|--slab-spacing|-1|-o|${rd}/s.exr"
  ERR "--slab-spacing: must be > 0" NOFILE ${rd}/s.exr)
file(WRITE ${rd}/syntax.json "{\"camera\": {\"eye\": [0, 0, 2],,}}\n")
ics_cli_test(NAME cli_render_syntax RC 2 ARGS "render|${rd}/syntax.json|-o|${rd}/x.exr"
  ERR "syntax.json:1:30: " NOFILE ${rd}/x.exr)
file(WRITE ${rd}/negvar.json "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [8, 8]}, \"render\": {\"slab_spacing\": 0.1, \"d1\": 1}, \"lights\": [{\"mean\": [0, 0], \"var\": [-1, 0]}], \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.5, \"material\": \"m\"}]}\n")
ics_cli_test(NAME cli_render_negative_variance RC 2 ARGS "render|${rd}/negvar.json|-o|${rd}/v.exr"
  ERR "negvar.json: lights\\[0\\].var: expected \\[varx, vary\\], finite and >= 0" NOFILE ${rd}/v.exr)
file(WRITE ${rd}/huge.json "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [16384, 16384]}, \"render\": {\"slab_spacing\": 0.01, \"d1\": 1, \"memory_limit_mib\": 100}, \"lights\": [{\"mean\": [0, 0], \"var\": [1e-6, 1e-6]}], \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.5, \"material\": \"m\"}]}\n")
ics_cli_test(NAME cli_render_over_budget RC 2 ARGS "render|${rd}/huge.json|-o|${rd}/h.exr"
  ERR "the plan needs at least [0-9.]+ MiB .* over render.memory_limit_mib = 100 \\(render.model auto, planned as blocker: render.model patel takes less\\)" NOFILE ${rd}/h.exr)
# the hint only where a cheaper model may fit (memory, work): not on the slab count's limit
ics_cli_test(NAME cli_render_slab_limit_no_hint RC 2 ARGS "render|--resolution|32x24|--slab-spacing|0.00001|-o|${rd}/sl.exr"
  ERR "exceed the limit 65536: increase render.slab_spacing\n$" NOFILE ${rd}/sl.exr)
ics_cli_test(NAME cli_plan_over_budget RC 2 ARGS "plan|${rd}/huge.json" ERR "over render.memory_limit_mib")
# a limit of 1e-320 MiB under a 1 x 1 view: the plan's size in digits that are not all 0 (the
# review's "needs at least 0.0 MiB")
file(WRITE ${rd}/tiny_limit.json "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [1, 1]}, \"render\": {\"slab_spacing\": 0.1, \"d1\": 1, \"memory_limit_mib\": 1e-320}, \"lights\": [{\"mean\": [0, 0], \"var\": [1e-3, 1e-3]}], \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.5, \"material\": \"m\"}]}\n")
ics_cli_test(NAME cli_plan_tiny_limit RC 2 ARGS "plan|${rd}/tiny_limit.json"
  ERR "the plan needs at least 0[.]0*[1-9][0-9]* MiB .* over render.memory_limit_mib = 9.99989e-321")
ics_cli_test(NAME cli_plan_print_scene_with_scene RC 2 ARGS "plan|${disk}|--print-scene" ERR "give no SCENE")
# render.model: --model overrides it, the plan and the summary name it, a bad one is refused
ics_cli_test(NAME cli_plan_model RC 0 ARGS "plan|--model|surface|--resolution|32x24" OUT "\"model\": \"surface\"")
ics_cli_test(NAME cli_render_model RC 0 ARGS "render|--model|solid|--resolution|32x24|-o|${rd}/model.exr"
  OUT "\"model\": \"solid\"")
# render.model auto, the default: blocker on cpu, said in the plan and the summary
ics_cli_test(NAME cli_plan_model_auto RC 0 ARGS "plan|--resolution|32x24"
  OUT "\"model\": \"blocker\",\n  \"model_auto\": true")
ics_cli_test(NAME cli_render_model_auto RC 0 ARGS "render|--resolution|32x24|-o|${rd}/model_auto.exr"
  OUT "\"model\": \"blocker\", \"model_auto\": true")
ics_cli_test(NAME cli_render_model_patel RC 0 ARGS "render|--model|patel|--resolution|32x24|-o|${rd}/model_patel.exr"
  OUT "\"model\": \"patel\", \"model_auto\": false")
ics_cli_test(NAME cli_render_model_bad RC 2 ARGS "render|--model|exact|--resolution|8x6|-o|${rd}/mb.exr"
  ERR "--model: unknown value 'exact' \\(expected patel, solid, surface, blocker, auto\\)" NOFILE ${rd}/mb.exr)
ics_cli_test(NAME cli_render_model_blocker RC 0 ARGS "render|--model|blocker|--resolution|32x24|-o|${rd}/mblk.exr"
  OUT "\"model\": \"blocker\"")
endif()
if(ICS_HAVE_RENDER)
ics_cli_test(NAME cli_bench_slab RC 0 ARGS "bench|slab|--sizes|32|--slabs|8|--threads|1|--reps|1|--kernels|ellipse2,gauss19"
  OUT "^backend,kernel,samples,mode,width,height,slabs,threads,ns_per_px_slab,ns_min,ns_max,floor_ns_per_px,floor_ratio,error,reps,simd,work,occluder,active,ms_render,ms_render_min,ms_render_max\ncpu,ellipse2,2,[a-z]+,32,32,8,1,[0-9.e+-]+,.*,(scalar|sse2|neon|avx2|avx512),dense,edge,1,[0-9.e+-]+,[0-9.e+-]+,[0-9.e+-]+\ncpu,gauss19,19,")
# both works side by side on the stripes that leave nothing to skip (the skip row counts fewer or
# as many updates), and bad values of the two options
ics_cli_test(NAME cli_bench_slab_work RC 0 ARGS "bench|slab|--sizes|64|--slabs|8|--threads|1|--reps|1|--kernels|ellipse2|--work|dense,skip|--occluder|stripes"
  OUT "\ncpu,ellipse2,2,[a-z]+,64,64,8,1,[^\n]*,-,1,[a-z0-9]+,dense,stripes,1,[^\n]*\ncpu,ellipse2,2,[a-z]+,64,64,8,1,[^\n]*,-,1,[a-z0-9]+,skip,stripes,(1|0[.][0-9]+),")
# whole frames, the three works side by side (a small resolution, one repetition)
ics_cli_test(NAME cli_bench_frame RC 0 ARGS "bench|frame|--resolution|32x24|--reps|1|--spp|1|--threads|1"
  OUT "^scene,width,height,work,model,threads,simd,cpu,ms_frame,ms_min,ms_max,ms_first,ms_plan,ms_render,ms_convolution,ms_shading,ms_detail,active,vs_mc\ndefault,32,24,skip,blocker,1,(scalar|sse2|neon|avx2|avx512),[^,]*,[^\n]*,0[.][0-9]+,[0-9.e+-]+\ndefault,32,24,dense,blocker,1,[a-z0-9]+,[^\n]*,1,[0-9.e+-]+\ndefault,32,24,mc,-,1,-,[^\n]*,1\n$")
# --model and --slab-spacing override the scene's (the default scene as it was: Patel's at 0.015)
ics_cli_test(NAME cli_bench_frame_model RC 0 ARGS "bench|frame|--resolution|32x24|--reps|1|--threads|1|--work|skip|--model|patel|--slab-spacing|0.015"
  OUT "\ndefault,32,24,skip,patel,1,")
ics_cli_test(NAME cli_bench_frame_bad_model RC 2 ARGS "bench|frame|--model|exact" ERR "--model: unknown value 'exact' \\(expected patel, solid, surface, blocker, auto\\)")
ics_cli_test(NAME cli_bench_frame_bad_spacing RC 2 ARGS "bench|frame|--slab-spacing|0" ERR "--slab-spacing: must be > 0")
# the spacing reaches the plan: 1e-5 asks for more slabs than the limit
ics_cli_test(NAME cli_bench_frame_spacing_applied RC 2 ARGS "bench|frame|--resolution|32x24|--reps|1|--work|skip|--slab-spacing|0.00001"
  ERR "slab_spacing 1e-05\\) exceed the limit 65536")
ics_cli_test(NAME cli_bench_frame_help RC 0 ARGS "bench|frame|--help" OUT "Monte-Carlo reference")
ics_cli_test(NAME cli_bench_frame_bad_work RC 2 ARGS "bench|frame|--work|skip,skip" ERR "--work: expected some of skip, dense, mc")
ics_cli_test(NAME cli_bench_frame_bad_res RC 2 ARGS "bench|frame|--resolution|32x" ERR "--resolution: expected WxH")
ics_cli_test(NAME cli_bench_frame_no_scene RC 2 ARGS "bench|frame|${CMAKE_CURRENT_BINARY_DIR}/no_such_scene.json" ERR "no_such_scene.json")
ics_cli_test(NAME cli_bench_slab_bad_work RC 2 ARGS "bench|slab|--work|sparse" ERR "--work: expected dense, skip or dense,skip, got 'sparse'")
ics_cli_test(NAME cli_bench_slab_bad_occluder RC 2 ARGS "bench|slab|--occluder|disk" ERR "--occluder: expected edge or stripes, got 'disk'")
ics_cli_test(NAME cli_bench_slab_help RC 0 ARGS "bench|slab|--help" OUT "memcpy floor")
ics_cli_test(NAME cli_bench_slab_bad_kernel RC 2 ARGS "bench|slab|--kernels|box" ERR "--kernels: unknown member 'box'")
ics_cli_test(NAME cli_bench_slab_bad_size RC 2 ARGS "bench|slab|--sizes|8" ERR "--sizes: expected integers in 16..4096")
endif()
if(ICS_HAVE_RENDER)
ics_cli_test(NAME cli_render_two_scenes RC 2 ARGS "render|${disk}|${disk}|-o|${rd}/t.exr" ERR "give one SCENE \\(got 2\\)" NOFILE ${rd}/t.exr)
ics_cli_test(NAME cli_render_directory RC 2 ARGS "render|${rd}|-o|${rd}/dir.exr" ERR "cannot open scene file: not a regular file [(]a directory[)]" NOFILE ${rd}/dir.exr)
ics_cli_test(NAME cli_render_png_as_exr RC 2 ARGS "render|-o|${rd}/p.png" ERR "-o writes OpenEXR; give the PNG preview with --png" NOFILE ${rd}/p.png)
ics_cli_test(NAME cli_render_kernel_out_of_proportion RC 2 ARGS "render|${disk}|--slab-spacing|1e5|-o|${rd}/k2.exr"
  ERR "light 0: its per-slab kernel is .* out of proportion" NOFILE ${rd}/k2.exr)
endif()
if(ICS_HAVE_RENDER)
# AOVs: named in the summary; refused without an EXR or with an unknown name
ics_cli_test(NAME cli_render_aov RC 0 ARGS "render|${disk}|--resolution|32x32|--aov|visibility,depth|-o|${rd}/aov.exr"
  OUT "\"aovs\": \\[\"light0.V\", \"Z\"\\]")
ics_cli_test(NAME cli_render_aov_unknown RC 2 ARGS "render|${disk}|--aov|normal|-o|${rd}/aov2.exr"
  ERR "--aov normal: 'normal' is not an AOV \\(visibility, depth, stderr, all\\)" NOFILE ${rd}/aov2.exr)
ics_cli_test(NAME cli_render_aov_png_only RC 2 ARGS "render|${disk}|--aov|depth|--png|${rd}/aov3.png"
  ERR "AOVs go into the EXR; give -o OUT.exr" NOFILE ${rd}/aov3.png)
endif()
if(ICS_HAVE_RENDER)
# the Monte-Carlo reference: its stops, its standard errors, and refusals
ics_cli_test(NAME cli_render_mc RC 0 ARGS "render|${disk}|--backend|mc|--spp|4|--resolution|32x32|--aov|all|-o|${rd}/mc.exr"
  OUT "\"backend\": \"mc\".*\"spp\": 4, \"noise\": [0-9.e+-]+.*\"aovs\": \\[\"light0.V\", \"Z\", \"stderr.R\", \"stderr.G\", \"stderr.B\", \"stderr.A\", \"stderr.light0.V\"\\]")
ics_cli_test(NAME cli_render_spp_without_mc RC 2 ARGS "render|${disk}|--spp|4|-o|${rd}/mc2.exr"
  ERR "--spp: only the Monte-Carlo reference takes a stop \\(give --backend mc\\)" NOFILE ${rd}/mc2.exr)
ics_cli_test(NAME cli_render_mc_mesh_without_mc RC 2 ARGS "render|${disk}|--mc-mesh|bvh|-o|${rd}/mc7.exr"
  ERR "--mc-mesh: only the Monte-Carlo reference takes it" NOFILE ${rd}/mc7.exr)
ics_cli_test(NAME cli_render_mc_mesh_bad RC 2 ARGS "render|${disk}|--backend|mc|--mc-mesh|kd-tree|-o|${rd}/mc8.exr"
  ERR "--mc-mesh kd-tree: expected auto, embree or bvh" NOFILE ${rd}/mc8.exr)
ics_cli_test(NAME cli_render_mc_bad_time RC 2 ARGS "render|${disk}|--backend|mc|--time|0|-o|${rd}/mc3.exr"
  ERR "--time: must be > 0 seconds" NOFILE ${rd}/mc3.exr)
ics_cli_test(NAME cli_render_mc_negative_noise RC 2 ARGS "render|${disk}|--backend|mc|--noise|-0.1|-o|${rd}/mc6.exr"
  ERR "--noise: must be > 0" NOFILE ${rd}/mc6.exr)
ics_cli_test(NAME cli_render_mc_nan_time RC 2 ARGS "render|${disk}|--backend|mc|--time|nan|-o|${rd}/mc7.exr"
  ERR "--time" NOFILE ${rd}/mc7.exr)
ics_cli_test(NAME cli_render_mc_bad_spp RC 2 ARGS "render|${disk}|--backend|mc|--spp|0|-o|${rd}/mc4.exr"
  ERR "--spp: expected an integer in 1..16777216" NOFILE ${rd}/mc4.exr)
ics_cli_test(NAME cli_render_stderr_on_cpu RC 2 ARGS "render|${disk}|--aov|stderr|-o|${rd}/mc5.exr"
  ERR "backend cpu does not make the AOV stderr \\(only mc estimates a standard error\\)" NOFILE ${rd}/mc5.exr)
endif()
if(ICS_HAVE_RENDER)
# error against a reference: in the same run (--reference N) and from a file (--compare REF.exr)
ics_cli_test(NAME cli_render_reference RC 0 ARGS "render|${disk}|--resolution|32x32|--reference|8|-o|${rd}/cmp.exr"
  OUT "\"compare\": {\"reference\": \"mc\", \"reference_backend\": \"mc\", \"reference_device\": \"CPU, [0-9]+ threads? \\(Monte Carlo\\)\", \"reference_spp\": 8, \"ms_reference\": [0-9.e+-]+, \"reference_noise\": [0-9.e+-]+, \"rmse\": [0-9.e+-]+, \"rmse_beyond_noise\": [0-9.e+-]+, \"max_error\": [0-9.e+-]+, \"max_at\": \\[[0-9]+, [0-9]+\\], \"psnr_db\": [0-9.e+-]+}")
ics_cli_test(NAME cli_render_compare_missing RC 2 ARGS "render|${disk}|--compare|${rd}/nonexistent.exr|-o|${rd}/cmp2.exr"
  ERR "--compare: .*nonexistent.exr: cannot open" NOFILE ${rd}/cmp2.exr)
ics_cli_test(NAME cli_render_reference_of_mc RC 2 ARGS "render|${disk}|--backend|mc|--reference|4|-o|${rd}/cmp6.exr"
  ERR "--reference: this render is the Monte-Carlo reference itself" NOFILE ${rd}/cmp6.exr)
ics_cli_test(NAME cli_render_diff_png_alone RC 2 ARGS "render|${disk}|--diff-png|${rd}/diff0.png"
  ERR "--diff-png: give --compare REF.exr or --reference N" NOFILE ${rd}/diff0.png)
ics_cli_test(NAME cli_render_diff_png RC 0 ARGS "render|${disk}|--resolution|32x32|--reference|4|--diff-png|${rd}/diff.png"
  OUT "\"diff_png\": \"[^\"]*diff.png\".*\"compare\": {\"reference\": \"mc\"")
ics_cli_test(NAME cli_render_compare_both RC 2 ARGS "render|${disk}|--compare|${rd}/x.exr|--reference|4|-o|${rd}/cmp3.exr"
  ERR "give --compare or --reference, not both" NOFILE ${rd}/cmp3.exr)
endif()
if(ICS_HAVE_RENDER)
# against the file cli_render_mc wrote (32 x 32, with its standard errors and summary)
set_tests_properties(cli_render_mc PROPERTIES FIXTURES_SETUP mc_exr)
ics_cli_test(NAME cli_render_compare_file RC 0 ARGS "render|${disk}|--resolution|32x32|--compare|${rd}/mc.exr|--png|${rd}/cmp4.png"
  OUT "\"compare\": {\"reference\": \"[^\"]*mc.exr\", \"reference_backend\": \"mc\", \"reference_device\": \"CPU, [0-9]+ threads? \\(Monte Carlo\\)\", \"reference_spp\": 4, \"ms_reference\": [0-9.e+-]+, \"reference_noise\": [0-9.e+-]+,")
ics_cli_test(NAME cli_render_compare_size RC 2 ARGS "render|${disk}|--compare|${rd}/mc.exr|-o|${rd}/cmp5.exr"
  ERR "--compare: .*mc.exr is 32x32, the render 128x128" NOFILE ${rd}/cmp5.exr)
set_tests_properties(cli_render_compare_file cli_render_compare_size PROPERTIES FIXTURES_REQUIRED mc_exr)
# references that are not: a NaN pixel, R and G only, truncated (written by test_exr --write-bad)
add_test(NAME cli_render_bad_refs COMMAND test_exr --write-bad . WORKING_DIRECTORY ${rd})
set_tests_properties(cli_render_bad_refs PROPERTIES LABELS fast FIXTURES_SETUP render_bad_refs)
foreach(bad "nan;channel G is NaN" "rg;wrong channel set: missing B|has no R, G, B channels" "trunc;corrupt or truncated")
  list(GET bad 0 name)
  list(GET bad 1 err)
  ics_cli_test(NAME cli_render_compare_${name} RC 2 ARGS "render|${disk}|--compare|${rd}/${name}.exr|-o|${rd}/cmp_${name}.exr"
    ERR "--compare: .*(${err})" NOFILE ${rd}/cmp_${name}.exr)
  set_tests_properties(cli_render_compare_${name} PROPERTIES FIXTURES_REQUIRED render_bad_refs)
endforeach()
# outputs that are inputs (every spelling of the same file) or each other, and FIFOs as every
# kind of input: refused at once; the mesh reader dies with a killed parent
add_test(NAME cli_input_output_paths COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/input_output_paths.sh
  $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_input_output_paths PROPERTIES LABELS fast)
# meshes that cannot make a surface (NaN, infinite, zero area, overflow under the transform) and
# Assimp out of memory: each named
add_test(NAME cli_mesh_messages COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/mesh_messages.sh
  $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_mesh_messages PROPERTIES LABELS fast SKIP_RETURN_CODE 77)
# files outside the scene's folder ("..", absolute, symbolic links, an OBJ's material library):
# refused unless --allow-outside-paths
add_test(NAME cli_outside_paths COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/outside_paths.sh
  $<TARGET_FILE:icshadow_cli> ${CMAKE_SOURCE_DIR}/tests/data)
set_tests_properties(cli_outside_paths PROPERTIES LABELS fast)
# every example scene (scenes/*.json, docs/gallery.md) renders at 48 x 36 with a PNG; a scene
# with a mesh is skipped, named, when Assimp was not found (then the test exits 77)
add_test(NAME cli_gallery COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/gallery.sh
  $<TARGET_FILE:icshadow_cli> ${CMAKE_SOURCE_DIR}/scenes)
set_tests_properties(cli_gallery PROPERTIES LABELS fast SKIP_RETURN_CODE 77)
# a light buffer one pixel wide with runs of 16 (two run choices for a 1-pixel row: the per-thread
# scratch once held one word; ASan caught the overflow in the vector loops)
file(WRITE ${rd}/narrow.json [=[
{"camera": {"eye": [0, 0, 2], "target": [0, 0, 0], "height": 3, "resolution": [1, 72]},
 "render": {"slab_spacing": 0.05, "d1": 1, "max_pad": 0, "rotation_run": 16},
 "lights": [{"mean": [0.3, -0.1], "var": [0.02, 0.01]}],
 "materials": {"black": {"color": [0, 0, 0]}, "white": {}},
 "objects": [{"shape": "disk", "center": [0, 0, 0], "normal": [0, 0, 1], "radius": 0.5, "material": "black"},
             {"shape": "rect", "center": [0, 0, -1], "normal": [0, 0, 1], "size": [3, 3], "material": "white"}]}
]=])
ics_cli_test(NAME cli_render_narrow_runs RC 0 ARGS "render|${rd}/narrow.json|--threads|2|-o|${rd}/narrow.exr"
  OUT "\"light_buffer\": \\[1, 72\\]")
# a colour of 1e30 under a light of 1e30 (each within its own bound): refused at parse time,
# naming the material, where it used to render fully and then fail at the write (non-finite)
file(WRITE ${rd}/overflow.json [=[
{"camera": {"eye": [0, 0, 2], "target": [0, 0, 0], "height": 3, "resolution": [16, 16]},
 "render": {"slab_spacing": 0.05, "d1": 1},
 "lights": [{"mean": [0.3, -0.1], "var": [0.02, 0.01], "weight": 1e30}],
 "materials": {"bright": {"color": [1e30, 1e30, 1e30]}},
 "objects": [{"shape": "rect", "center": [0, 0, -1], "normal": [0, 0, 1], "size": [3, 3], "material": "bright"}]}
]=])
ics_cli_test(NAME cli_render_overflow RC 2 ARGS "render|${rd}/overflow.json|-o|${rd}/overflow.exr"
  ERR "materials.bright: a colour of 1e[+]30 under lights of 1e[+]30 .* the image would overflow" NOFILE ${rd}/overflow.exr)
# an extinction of 14 under a transfer extinction scale of 1e308 (each within its own range):
# refused at parse time, naming the material, where it rendered fully and then failed at the
# write with a NaN pixel on cpu, cl and gl; the bound at its edge renders finite
file(WRITE ${rd}/extinction_overflow.json [=[
{"camera": {"eye": [0, 0, 2], "target": [0, 0, 0], "height": 3, "resolution": [16, 16]},
 "render": {"slab_spacing": 0.05, "d1": 1},
 "lights": [{"mean": [0.3, -0.1], "var": [0.02, 0.01]}],
 "materials": {"white": {"color": [1, 1, 1]},
               "fog": {"extinction": 14, "detail": {"function": "perlin"},
                       "transfer": [[0, 1, 1, 1, 1e308], [1, 1, 1, 1, 1e308]]}},
 "objects": [{"shape": "rect", "center": [0, 0, -1], "normal": [0, 0, 1], "size": [3, 3], "material": "white"},
             {"shape": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "fog"}]}
]=])
ics_cli_test(NAME cli_render_extinction_overflow RC 2
  ARGS "render|${rd}/extinction_overflow.json|-o|${rd}/extinction_overflow.exr"
  ERR "materials.fog: its extinction reaches inf per world unit .* over 1e[+]100: the render would overflow"
  NOFILE ${rd}/extinction_overflow.exr)
file(READ ${rd}/extinction_overflow.json ics_json)
string(REPLACE "\"extinction\": 14" "\"extinction\": 1" ics_json "${ics_json}")
string(REPLACE "1e308" "1e100" ics_json "${ics_json}")
# (8 overlapping volumes at the bound: their sum, colours and path lengths stay finite)
string(REPLACE "{\"shape\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.5, \"material\": \"fog\"}"
  "{\"shape\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.5, \"material\": \"fog\"}, {\"shape\": \"sphere\", \"center\": [0.01, 0, 0], \"radius\": 0.5, \"material\": \"fog\"}, {\"shape\": \"sphere\", \"center\": [0.02, 0, 0], \"radius\": 0.5, \"material\": \"fog\"}, {\"shape\": \"sphere\", \"center\": [0.03, 0, 0], \"radius\": 0.5, \"material\": \"fog\"}, {\"shape\": \"sphere\", \"center\": [0, 0.01, 0], \"radius\": 0.5, \"material\": \"fog\"}, {\"shape\": \"sphere\", \"center\": [0, 0.02, 0], \"radius\": 0.5, \"material\": \"fog\"}, {\"shape\": \"sphere\", \"center\": [0, 0.03, 0], \"radius\": 0.5, \"material\": \"fog\"}, {\"shape\": \"sphere\", \"center\": [0, 0, 0.01], \"radius\": 0.5, \"material\": \"fog\"}"
  ics_json "${ics_json}")
file(WRITE ${rd}/extinction_edge.json "${ics_json}")
ics_cli_test(NAME cli_render_extinction_edge RC 0
  ARGS "render|${rd}/extinction_edge.json|-o|${rd}/extinction_edge.exr"
  OUT "\"exr\": ")
# messages that name the key: d1 and slab_spacing past 1e100 (1e308 overflowed in the plan,
# "argument out of range"), fov_deg below 1e-6 ("variance is negative"), and a UTF-8 byte-order
# mark, which is skipped (it was refused with the raw glyph)
file(READ ${disk} ics_disk_text)
string(REPLACE "\"d1\": 1.0" "\"d1\": 1e308" ics_text "${ics_disk_text}")
file(WRITE ${rd}/d1_huge.json "${ics_text}")
ics_cli_test(NAME cli_render_d1_huge RC 2 ARGS "plan|${rd}/d1_huge.json" ERR "render.d1: 1e[+]308 is over 1e100")
string(REPLACE "\"projection\": \"orthographic\"" "\"projection\": \"perspective\", \"fov_deg\": 1e-300" ics_text "${ics_disk_text}")
string(REPLACE "\"height\": 3.0, " "" ics_text "${ics_text}")
file(WRITE ${rd}/fov_tiny.json "${ics_text}")
ics_cli_test(NAME cli_render_fov_tiny RC 2 ARGS "plan|${rd}/fov_tiny.json" ERR "camera.fov_deg: 1e-300 is out of range \\[1e-6, 170\\)")
string(ASCII 239 187 191 ics_bom)
file(WRITE ${rd}/bom.json "${ics_bom}${ics_disk_text}")
ics_cli_test(NAME cli_render_bom RC 0 ARGS "plan|${rd}/bom.json" OUT "\"scene\": \"[^\"]*bom.json\"")
# a scene's grids read only where an object uses them, grids and meshes held to the memory limit
add_test(NAME cli_scene_memory COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/scene_memory.sh
  $<TARGET_FILE:icshadow_cli> ${CMAKE_SOURCE_DIR}/tests/data)
set_tests_properties(cli_scene_memory PROPERTIES LABELS fast)
# the plan's work: the detail's octaves, the perspective classes and the geometry pass too
add_test(NAME cli_plan_work COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/plan_work.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_plan_work PROPERTIES LABELS fast)
# the Monte-Carlo reference's work bounded before it starts, --time a hard stop
add_test(NAME cli_mc_bounded COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/mc_bounded.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_mc_bounded PROPERTIES LABELS fast)
# ICS_SIMD forces the CPU backend's vector path: a name it lacks is refused with the paths it
# has; scalar runs anywhere and the summary says which path ran
foreach(simd "bogus;2;no such path [(]this processor has: auto, scalar" "scalar;0;\"device\": \"CPU, [0-9]+ threads?, scalar\"")
  list(GET simd 0 name)
  list(GET simd 1 rc)
  list(GET simd 2 re)
  if(rc EQUAL 0)
    set(stream OUT)
  else()
    set(stream ERR)
  endif()
  add_test(NAME cli_render_simd_${name} COMMAND ${CMAKE_COMMAND} -E env ICS_SIMD=${name}
    ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:icshadow_cli> "-DARGS=render|--resolution|16x12|-o|${rd}/simd_${name}.exr"
    -DRC=${rc} "-D${stream}=${re}" -P ${CMAKE_SOURCE_DIR}/tests/cli/expect.cmake)
  set_tests_properties(cli_render_simd_${name} PROPERTIES LABELS fast)
endforeach()
# ICS_PIECE_BATCH takes 0 or 1 (the lone volume pieces one by one, or a row at a time): anything
# else is refused, naming both, and nothing is written
add_test(NAME cli_render_piece_batch_bogus COMMAND ${CMAKE_COMMAND} -E env ICS_PIECE_BATCH=yes
  ${CMAKE_COMMAND} -DCLI=$<TARGET_FILE:icshadow_cli> "-DARGS=render|--resolution|16x12|-o|${rd}/piece_batch.exr"
  -DRC=2 "-DERR=ICS_PIECE_BATCH=yes: 0 [(]the lone volume pieces one by one[)] or 1"
  -DNOFILE=${rd}/piece_batch.exr -P ${CMAKE_SOURCE_DIR}/tests/cli/expect.cmake)
set_tests_properties(cli_render_piece_batch_bogus PROPERTIES LABELS fast)
endif()
