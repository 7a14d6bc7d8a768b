/* consumer.c — a tiny program built against an installed libicshadow (pkg-config and
 * find_package(icshadow)) by tests/install/run.sh. Exits 0 when the library answers. */
#include <icshadow.h>
#include <math.h>
#include <stdio.h>

int main(void) {
  /* K(m = 1/2) = Gamma(1/4)^2 / (4 sqrt(pi)) = 1.854074677301371918433850347195... (DLMF 19.6.E?) */
  const double k_half = 1.8540746773013719;
  double k = ics_ellint_k(0.5);
  ics_ellipse_shape shape;
  double xy[4];
  ics_status st = ics_ellipse_kernel(0.8, 0.2, 30.0, 2, 0.0, &shape, xy);
  printf("K(0.5) = %.17g, kernel: %s, a = %.6g, b = %.6g\n", k, ics_status_str(st), shape.a,
         shape.b);
  /* pulls exr.o in: a static link must bring OpenEXR's library along (Requires.private /
   * find_dependency) when libicshadow was built with it */
  printf("OpenEXR I/O: %s\n", ics_exr_available() ? "yes" : "no");
  /* an object made and freed through the exported lifecycle functions */
  ics_image *img = NULL;
  ics_status si = ics_image_create(&img, 4, 2, 3);
  int zero = si == ICS_OK && img->width == 4 && img->data[4 * 2 * 3 - 1] == 0.0f;
  ics_image_destroy(img);
  printf("libicshadow %d.%d.%d, image: %s\n", ICS_VERSION_MAJOR, ICS_VERSION_MINOR,
         ICS_VERSION_PATCH, ics_status_str(si));
  if (fabs(k - k_half) > 4e-16 * k_half || st != ICS_OK || !zero) return 1;
  return 0;
}
