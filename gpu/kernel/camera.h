/* camera.h — the camera ray of buffer pixel (bi, bj) (ics_plan_ray): its origin and direction
 * from the camera record of device_layout.h (CAM_*, read through ICS_CAM(f)), the view W x H
 * and its padding (pad_l, pad_t). Orthographic: parallel rays along f from the image plane;
 * perspective: from the eye, f + (2 s - 1) tan(fov/2) aspect r + (1 - 2 t) tan(fov/2) u,
 * unnormalised. Every operation in the host's order and `precise` (no contraction), so the device's
 * layered depth image matches the host's bit for bit. Shared kernel source (lang.h): the plan
 * (cpu), slab.cl, slab.comp and ldi.comp compile this one text. */
#ifndef ICS_KERNEL_CAMERA_H
#define ICS_KERNEL_CAMERA_H
#include "kernel/device_layout.h"
#include "kernel/lang.h"

ICS_FN void ics_k_plan_ray(ICS_VIEW_PARAM int bi, int bj, int W, int H, int pad_l, int pad_t,
                           ICS_OUT double o[3], ICS_OUT double d[3]) {
  ICS_PRECISE double s = (ICS_TO_DOUBLE(bi - pad_l) + 0.5) / ICS_TO_DOUBLE(W);
  ICS_PRECISE double t = (ICS_TO_DOUBLE(bj - pad_t) + 0.5) / ICS_TO_DOUBLE(H);
  if (ICS_CAM(CAM_PROJ) == 0.0) {
    double h = ICS_CAM(CAM_H), w = ICS_CAM(CAM_W);
    for (int i = 0; i < 3; i++) {
      ICS_PRECISE double a = (s - 0.5) * w * ICS_CAM(CAM_R + i),
                         b = (0.5 - t) * h * ICS_CAM(CAM_U + i);
      ICS_PRECISE double v = ICS_CAM(CAM_EYE + i) + a + b;
      o[i] = v;
      d[i] = ICS_CAM(CAM_F + i);
    }
  } else {
    double th = ICS_CAM(CAM_TH), asp = ICS_CAM(CAM_ASP);
    for (int i = 0; i < 3; i++) {
      ICS_PRECISE double a = (2.0 * s - 1.0) * th * asp * ICS_CAM(CAM_R + i);
      ICS_PRECISE double b = (1.0 - 2.0 * t) * th * ICS_CAM(CAM_U + i);
      ICS_PRECISE double v = ICS_CAM(CAM_F + i) + a + b;
      o[i] = ICS_CAM(CAM_EYE + i);
      d[i] = v;
    }
  }
}

#endif
