/* consumer_cl.c — a program that builds a summed-area table on an OpenCL device against an
 * installed libicshadow_cl (pkg-config icshadow-cl and find_package(icshadow COMPONENTS cl)),
 * built by tests/install/run.sh: a 5 x 3 table in double, its last entry the sum of the data.
 * Exits 0 when the table is right, or when this machine has no OpenCL device (ics_cl_create says
 * why; the point is then the link), 1 otherwise. */
#include <icshadow/cl.h>
#include <stdio.h>

int main(void) {
  char msg[2048] = "";
  ics_cl *cl = NULL;
  if (ics_cl_create(&cl, msg, sizeof msg) != ICS_OK) {
    printf("consumer_cl: linked; no OpenCL device here: %s\n", msg);
    return 0;
  }
  float data[15];
  double table[15], sum = 0;
  for (int i = 0; i < 15; i++) data[i] = (float)(i + 1), sum += i + 1;
  ics_status st = ics_cl_sat_build(cl, data, 5, 3, 1, ICS_SAT_DOUBLE, 0, table, NULL, NULL, msg, sizeof msg);
  printf("consumer_cl: %s, status %s, last entry %g (sum %g)\n", ics_cl_device(cl), ics_status_str(st),
         st == ICS_OK ? table[14] : -1.0, sum);
  ics_cl_destroy(cl);
  return st == ICS_OK && table[14] == sum ? 0 : 1;
}
