# 1D min-max mipmaps, traversal vs brute force, Jacobi SVD, epipolar rectification
# (libicshadow/src/minmax.c).
ics_add_test(NAME test_minmax SOURCES test_minmax.c LABELS fast LIBS m)
