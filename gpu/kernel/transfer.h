/* transfer.h — a volume's transfer function (ics_material_transfer, docs/renderer.md "Detail"):
 * rows of (v, r, g, b, extinction scale) with v increasing, linear between rows and constant
 * beyond them (no rows: the material's colour, scale max(v, 0)); and its pre-integration over a
 * piece whose detail value runs linearly from vf to vb (ics_material_preintegrate): the
 * extinction-weighted colour and mean scale, Simpson's rule (exact: colour x scale is quadratic
 * on each linear piece) between the breakpoints in order. Object ob's rows are read through
 * ICS_NTRANSFER(ob) and ICS_TRANSFER(ob, i) (double i of its rows), its colour through
 * ICS_COLOR(ob, c). Shared kernel source (lang.h): the cpu backend, slab.cl and slab.comp
 * compile this one text. */
#ifndef ICS_KERNEL_TRANSFER_H
#define ICS_KERNEL_TRANSFER_H
#include "kernel/lang.h"

/* the colour at detail value v into rgb; returns the extinction scale */
ICS_FN double ics_k_transfer(ICS_VIEW_PARAM int ob, double v, ICS_OUT double rgb[3]) {
  int n = ICS_NTRANSFER(ob);
  if (n == 0) {
    for (int c = 0; c < 3; c++) rgb[c] = ICS_COLOR(ob, c);
    return v > 0 ? v : 0.0;
  }
  int k = 0;
  if (v <= ICS_TRANSFER(ob, 0)) {
    k = -1;
  } else if (v >= ICS_TRANSFER(ob, 5 * (n - 1))) {
    k = n - 1;
  } else {
    while (k + 1 < n && ICS_TRANSFER(ob, 5 * (k + 1)) <= v) k++;
  }
  if (k < 0 || k == n - 1) {
    int row = 5 * (k < 0 ? 0 : n - 1);
    for (int c = 0; c < 3; c++) rgb[c] = ICS_TRANSFER(ob, row + 1 + c);
    return ICS_TRANSFER(ob, row + 4);
  }
  int r0 = 5 * k, r1 = r0 + 5;
  double a = (v - ICS_TRANSFER(ob, r0)) / (ICS_TRANSFER(ob, r1) - ICS_TRANSFER(ob, r0));
  for (int c = 0; c < 3; c++)
    rgb[c] = ICS_TRANSFER(ob, r0 + 1 + c) +
             a * (ICS_TRANSFER(ob, r1 + 1 + c) - ICS_TRANSFER(ob, r0 + 1 + c));
  return ICS_TRANSFER(ob, r0 + 4) + a * (ICS_TRANSFER(ob, r1 + 4) - ICS_TRANSFER(ob, r0 + 4));
}

/* adds the integrals over [a, b] of c_k(v) s(v) (acc[0..2]) and s(v) (acc[3]) for a transfer
 * function linear on [a, b] */
ICS_FN void ics_k_linear_piece(ICS_VIEW_PARAM int ob, double a, double b, ICS_INOUT double acc[4]) {
  double ca[3], cm[3], cb[3], h = b - a;
  double sa = ics_k_transfer(ICS_VIEW_ARG ob, a, ca);
  double sm = ics_k_transfer(ICS_VIEW_ARG ob, 0.5 * (a + b), cm);
  double sb = ics_k_transfer(ICS_VIEW_ARG ob, b, cb);
  acc[3] += h * (sa + 4 * sm + sb) / 6;
  for (int c = 0; c < 3; c++) acc[c] += h * (ca[c] * sa + 4 * cm[c] * sm + cb[c] * sb) / 6;
}

/* the piece's colour into rgb; returns its mean extinction scale */
ICS_FN double ics_k_preintegrate(ICS_VIEW_PARAM int ob, double vf, double vb,
                                 ICS_OUT double rgb[3]) {
  double lo = ICS_FMIN(vf, vb), hi = ICS_FMAX(vf, vb);
  if (!(hi - lo > ICS_DBL_CONST(1e-12, 1e-12lf) * (1 + ICS_FABS(hi))))
    return ics_k_transfer(ICS_VIEW_ARG ob, 0.5 * (vf + vb), rgb);
  /* breakpoints: the rows' values inside (lo, hi), and 0 when there are no rows (max(v, 0)
   * bends there) */
  int n = ICS_NTRANSFER(ob);
  double acc[4], prev = lo;
  for (int c = 0; c < 4; c++) acc[c] = 0.0;
  if (n == 0) {
    if (lo < 0 && hi > 0) {
      ics_k_linear_piece(ICS_VIEW_ARG ob, prev, 0.0, acc);
      prev = 0.0;
    }
  } else {
    for (int i = 0; i < n; i++) {
      double v = ICS_TRANSFER(ob, 5 * i);
      if (v > lo && v < hi) {
        ics_k_linear_piece(ICS_VIEW_ARG ob, prev, v, acc);
        prev = v;
      }
    }
  }
  ics_k_linear_piece(ICS_VIEW_ARG ob, prev, hi, acc);
  if (!(acc[3] > 0)) {
    ics_k_transfer(ICS_VIEW_ARG ob, 0.5 * (vf + vb), rgb);
    return 0.0;
  }
  for (int c = 0; c < 3; c++) rgb[c] = acc[c] / acc[3];
  return acc[3] / (hi - lo);
}

#endif
