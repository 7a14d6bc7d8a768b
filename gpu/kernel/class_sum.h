/* class_sum.h — a perspective slab step's class sum (gpu/backends/cpu/propagate.c class_sum): the
 * taps of class (bx, by) of Q x Q at pixel (nx, ny), reading channel c of the source with
 * every index clamped to the buffer (class Q is class 0 of the next pixel). The including
 * program defines ICS_TAP_X(m), ICS_TAP_Y(m), ICS_TAP_W(m) (tap m's offsets and weight),
 * ICS_SRC(c, i) (channel c at buffer index i), ICS_AT(x, y) (a pixel's buffer index), ICS_BW
 * and ICS_BH (the buffer's size). Shared kernel source (lang.h) for slab.cl and slab.comp. */
#ifndef ICS_KERNEL_CLASS_SUM_H
#define ICS_KERNEL_CLASS_SUM_H
#include "kernel/lang.h"

ICS_FN int ics_k_clampi(int v, int hi) { return v < 0 ? 0 : v > hi ? hi : v; }

ICS_FN float ics_k_class_sum(ICS_VIEW_PARAM int c, int n, int Q, int bx, int by, int nx, int ny) {
  if (bx == Q) bx = 0, nx++;
  if (by == Q) by = 0, ny++;
  int base = (by * Q + bx) * n;
  ICS_PRECISE float acc = 0.0;
  for (int m = base; m < base + n; m++)
    acc += ICS_TAP_W(m) * ICS_SRC(c, ICS_AT(ics_k_clampi(nx + ICS_TAP_X(m), ICS_BW - 1),
                                            ics_k_clampi(ny + ICS_TAP_Y(m), ICS_BH - 1)));
  return acc;
}

#endif
