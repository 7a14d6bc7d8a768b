# Occlusion textures (libicshadow/src/occtex.c): prefilters vs direct box averages, slicing,
# combinations, the exact shadow of a planar occluder, fading, bad input.
ics_add_test(NAME test_occtex SOURCES test_occtex.c LABELS fast LIBS m)
