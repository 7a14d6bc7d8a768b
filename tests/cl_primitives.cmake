# libicshadow_cl (libicshadow_cl/: icshadow/cl.h) on an OpenCL device, PoCL here: summed-area
# tables and min-max mipmaps against the core's, and the benchmarks' cl rows. Medium: PoCL builds
# the programs on first use.
# summed-area tables on the device (icshadow/cl.h) equal the core's bit for bit
ics_add_test(NAME test_sat_cl SOURCES test_sat_cl.c LABELS medium
  LIBS icshadow_cl_static icshadow_static NEEDS OPENCL)
# bench sat2d / sat3d with the device's table beside the CPU's, per mode
if(ICS_HAVE_OPENCL)
  set(f "[0-9.e+-]+")
  ics_cli_test(NAME cli_sat2d_cl RC 0 LABELS medium
    ARGS "bench|sat2d|--width|67|--height|33|--modes|float,compensated|--reps|1|--boxes|20|--backend|cpu,cl"
    OUT "\nsat2d,float,67,33,1,1,[^\n]*\nsat2d-cl,float,67,33,1,1,[^\n]*\nsat2d,compensated,67,33,1,1,[^\n]*,0,0,20,${f},${f}\nsat2d-cl,compensated,67,33,1,1,[^\n]*,0,0,20,${f},${f}\n$")
  ics_cli_test(NAME cli_sat3d_cl RC 0 LABELS medium
    ARGS "bench|sat3d|--width|9|--height|7|--depth|5|--modes|double|--reps|1|--boxes|20|--backend|cl"
    OUT "^kind,[^\n]*\nsat3d-cl,double,9,7,5,1,[^\n]*,0,0,20,${f},${f}\n$")
endif()
# min-max mipmaps on the device: the same trees and the same integrated sums as the core's
ics_add_test(NAME test_minmax_cl SOURCES test_minmax_cl.c LABELS medium
  LIBS icshadow_cl_static icshadow_static NEEDS OPENCL)
# bench minmax with the device's trees beside the CPU's (the sums' equality: test_minmax_cl)
if(ICS_HAVE_OPENCL)
  set(f "[0-9.e+-]+")
  ics_cli_test(NAME cli_minmax_cl RC 0 LABELS medium
    ARGS "bench|minmax|--samples|64|--rows|8|--rays|4|--reps|1|--backend|cpu,cl"
    OUT "\n64,8,4,4,${f},${f},${f},${f},[0-9]+,[0-9]+,${f},${f},${f},${f},${f},cpu,${f},${f},${f},${f}\n64,8,4,4,${f},${f},${f},${f},[0-9]+,[0-9]+,${f},${f},${f},${f},${f},cl,${f},${f},${f},${f}\n$")
endif()
