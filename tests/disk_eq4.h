/* disk_eq4.h — Patel's Eq. 4 for a disk, by an independent quadrature, for the renderer's tests:
 * the fraction of a Gaussian light N(m, S) (in distance-scaled tan-plane units) that a disk of
 * radius R centred at the origin blocks, P(|q| < R) for q ~ N(m, S): Gauss-Legendre in the
 * radius, the trapezoid rule (exact for trigonometric polynomials, spectrally accurate here) in
 * the angle. Call gl_init(GL_N) once first. */
#ifndef ICS_TEST_DISK_EQ4_H
#define ICS_TEST_DISK_EQ4_H

#include <math.h>

#include "icshadow/constants.h"

#define GL_N 48
static double gl_x[GL_N], gl_w[GL_N];

static inline void gl_init(int n) {
  for (int i = 0; i < n; i++) {
    double x = cos(ICS_PI * (i + 0.75) / (n + 0.5)), p0 = 1, p1 = x, dp = 1;
    for (int it = 0; it < 100; it++) {
      p0 = 1, p1 = x;
      for (int k = 2; k <= n; k++) {
        double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1);
      double dx = p1 / dp;
      x -= dx;
      if (fabs(dx) < 1e-16) break;
    }
    gl_x[i] = x;
    gl_w[i] = 2 / ((1 - x * x) * dp * dp);
  }
}

/* P(|q| < R) for q ~ N(m, S) */
static inline double p_disk(double mx, double my, const double S[3], double R) {
  double det = S[0] * S[2] - S[1] * S[1], i0 = S[2] / det, i1 = -S[1] / det, i2 = S[0] / det;
  double sum = 0;
  const int nt = 256;
  for (int a = 0; a < GL_N; a++) {
    double r = 0.5 * R * (gl_x[a] + 1), wr = 0.5 * R * gl_w[a], s = 0;
    for (int b = 0; b < nt; b++) {
      double th = 2 * ICS_PI * b / nt, x = r * cos(th) - mx, y = r * sin(th) - my;
      s += exp(-0.5 * (i0 * x * x + 2 * i1 * x * y + i2 * y * y));
    }
    sum += wr * r * s * 2 * ICS_PI / nt;
  }
  return sum / (2 * ICS_PI * sqrt(det));
}

#endif
