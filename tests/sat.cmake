# Summed-area tables, CSAT and SSAT (libicshadow/src/sat.c, csat.c, ssat.c, volume.c;
# docs/sat.md): box sums against brute force, documented error bounds per precision mode,
# CSAT/SSAT against shadow-ray marching.
ics_add_test(NAME test_sat SOURCES test_sat.c LABELS fast LIBS m)
