/* test_image.c — float images (icshadow/image.h): creation limits, the bad-pixel finder, and
 * the RGB difference against values computed by hand (one channel of one pixel off by 0.2 in a
 * 7 x 5 image: RMSE 0.2 / sqrt(105), max 0.2 at that pixel and channel, PSNR 10 log10(105 / 0.04);
 * identical images: RMSE 0, PSNR infinite; 3- against 4-channel images; sizes that differ). */
#include <math.h>

#include "icshadow.h"
#include "testutil.h"

int main(void) {
  ics_image *a = NULL, *b = NULL, *c = NULL;
  CHECK(ics_image_create(&a, 0, 5, 3) == ICS_ERR_SIZE && a == NULL, "width 0 refused");
  CHECK(ics_image_create(&a, 7, 5, 2) == ICS_ERR_INVALID_ARG && a == NULL, "2 channels refused");
  CHECK(ics_image_create(&a, 7, 5, 3) == ICS_OK && ics_image_create(&b, 7, 5, 4) == ICS_OK &&
            ics_image_create(&c, 5, 7, 3) == ICS_OK, "create");
  for (int p = 0; p < 35; p++) {
    for (int k = 0; k < 3; k++) a->data[p * 3 + k] = 0.5f, b->data[p * 4 + k] = 0.5f;
    b->data[p * 4 + 3] = 0.25f; /* alpha is not compared */
  }
  ics_image_diff d;
  CHECK(ics_image_diff_rgb(a, b, &d) == ICS_OK && d.rmse == 0 && d.max_abs == 0 && isinf(d.psnr),
        "identical RGB: rmse %g, psnr %g", d.rmse, d.psnr);
  b->data[(2 * 7 + 4) * 4 + 1] = 0.7f; /* pixel (4, 2), G */
  CHECK(ics_image_diff_rgb(a, b, &d) == ICS_OK, "diff");
  double e = (double)0.7f - 0.5;
  CHECK(fabs(d.rmse - e / sqrt(105)) < 1e-15 && d.max_abs == e && d.max_x == 4 && d.max_y == 2 &&
            d.max_channel == 1 && fabs(d.psnr - 10 * log10(105 / (e * e))) < 1e-12,
        "one value off: rmse %.17g, max %.17g at (%d, %d) ch %d, psnr %.17g", d.rmse, d.max_abs,
        d.max_x, d.max_y, d.max_channel, d.psnr);
  CHECK(ics_image_diff_rgb(a, c, &d) == ICS_ERR_INVALID_ARG, "different sizes refused");
  CHECK(ics_image_diff_rgb(a, NULL, &d) == ICS_ERR_INVALID_ARG, "NULL refused");
  int i, j, k;
  CHECK(ics_image_find_bad(a, &i, &j, &k) == 1, "finite image");
  a->data[(3 * 7 + 1) * 3 + 2] = -1;
  CHECK(ics_image_find_bad(a, &i, &j, &k) == 0 && i == 1 && j == 3 && k == 2, "negative found");
  ics_image_destroy(a), ics_image_destroy(b), ics_image_destroy(c);
  return test_summary("test_image");
}
