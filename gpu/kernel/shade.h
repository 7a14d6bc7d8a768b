/* shade.h — the per-pixel shading steps of the cl and gl backends, written once (the cpu backend's
 * gpu/backends/cpu/backend_cpu.c is the reference they follow; docs/renderer.md "Shading and
 * compositing"):
 *   ics_k_frag_*          a fragment code's object, surface bias and slab (ldi.c packs them);
 *   ics_k_volume_sig      a volume's extinction and colour at a piece's sample point(s);
 *   ics_k_volume_piece    one volume piece: its colour composited into the pixel and the light
 *                         buffers attenuated by the volumes' transmittance along each light;
 *   ics_k_surface_occlusion  a surface fragment's occlusion of each light within its window.
 * The including program defines, over its own storage (lang.h "view"): ICS_OBJ(ob, f) (the
 * object records, device_layout.h), ICS_TT(i) (the transfer rows), ICS_PERM(i), ICS_GRID(i),
 * ICS_CAM(f), ICS_VOLOBJ(i) (the object of volume bit i), ICS_LPATH(l) (light l's path per unit
 * depth), ICS_LMU(i) (the lights' means, two per light), ICS_WINDOW(l) (this slab's windows),
 * ICS_DST(l, c, q) (light l's channel c at buffer index q), ICS_ARG(name) (nlights, nch, k, W,
 * H, pad_l, pad_t, preintegrate) and ICS_JITTER(k, p) (ics_rng_uniform_at(seed, "jitt" << 32 | k,
 * p)). Shared kernel source (lang.h) for slab.cl and slab.comp. */
#ifndef ICS_KERNEL_SHADE_H
#define ICS_KERNEL_SHADE_H
/* transfer.h's accessors over the object records and the transfer rows */
#define ICS_NTRANSFER(ob) ICS_TO_INT(ICS_OBJ(ob, O_NTRANSFER))
#define ICS_TRANSFER(ob, i) ICS_TT(5 * ICS_TO_INT(ICS_OBJ(ob, O_TRANSFER)) + (i))
#define ICS_COLOR(ob, c) ICS_OBJ(ob, O_COLOR + (c))

#include "kernel/camera.h"
#include "kernel/composite.h"
#include "kernel/detail_value.h"
#include "kernel/device_layout.h"
#include "kernel/lang.h"
#include "kernel/occlusion.h"
#include "kernel/transfer.h"

#define ICS_K_MAXV 8 /* overlapping volumes whose extinctions are kept (private memory) */

ICS_FN int ics_k_frag_obj(ICS_UINT code) { return ICS_TO_INT(code & 0xfffu); }
ICS_FN int ics_k_frag_bias(ICS_UINT code) { return ICS_TO_INT((code >> 12) & 0xfu); }
ICS_FN int ics_k_frag_slab(ICS_UINT code) { return ICS_TO_INT(code >> 16); }

/* the extinction of volume object ob at the piece's sample point(s) (pt; pt2 its far end when
 * pre-integrating), its colour into c */
ICS_FN double ics_k_volume_sig(ICS_VIEW_PARAM int ob, ICS_CONST_IN double pt[3],
                               ICS_CONST_IN double pt2[3], ICS_OUT double c[3]) {
  double scale = 1.0;
  for (int i = 0; i < 3; i++) c[i] = ICS_OBJ(ob, O_COLOR + i);
  if (ICS_OBJ(ob, O_DETAIL) != 0.0) {
    double v = ics_k_detail_value(ICS_VIEW_ARG ob, pt);
    if (ICS_ARG(preintegrate) != 0)
      scale = ics_k_preintegrate(ICS_VIEW_ARG ob, v, ics_k_detail_value(ICS_VIEW_ARG ob, pt2), c);
    else
      scale = ics_k_transfer(ICS_VIEW_ARG ob, v, c);
  }
  return ICS_OBJ(ob, O_EXTINCTION) * scale;
}

/* One volume piece of depth extent dz from za at buffer pixel (bi, bj) (p its index in the grid,
 * q in the light buffers), inside the volumes of `mask`: its colour, lit by L, composited under
 * C (RGBA) when the pixel is in view, and each light's buffer attenuated. The extinctions of up
 * to ICS_K_MAXV overlapping volumes are kept for the transmittance; with more, each is evaluated
 * again per light (the same values: the sample point depends on the pixel and slab only). */
ICS_FN void ics_k_volume_piece(ICS_VIEW_PARAM int p, int q, int bi, int bj, ICS_MASK mask,
                               double za, double dz, ICS_CONST_IN double L[3], ICS_INOUT float C[4],
                               int inview) {
  double sig[ICS_K_MAXV], o[3], d[3], pt[3], pt2[3], cc[3], sum = 0.0;
  for (int i = 0; i < 3; i++) pt[i] = 0.0, pt2[i] = 0.0, cc[i] = 0.0;
  int nv = 0, have_ray = 0, keep = ics_mask_count(mask) <= ICS_K_MAXV ? 1 : 0;
  for (ICS_MASK m = mask; ics_mask_any(m);
       m = ics_mask_drop(m)) /* the sample point, if some volume has detail */
    if (ICS_OBJ(ICS_VOLOBJ(ics_mask_lowest(m)), O_DETAIL) != 0.0) {
      ics_k_plan_ray(ICS_VIEW_ARG bi, bj, ICS_ARG(W), ICS_ARG(H), ICS_ARG(pad_l), ICS_ARG(pad_t), o,
                     d);
      if (ICS_ARG(preintegrate) != 0) {
        for (int i = 0; i < 3; i++) pt[i] = o[i] + za * d[i], pt2[i] = o[i] + (za + dz) * d[i];
      } else {
        double zs = za + ICS_JITTER(ICS_ARG(k), p) * dz;
        for (int i = 0; i < 3; i++) pt[i] = o[i] + zs * d[i];
      }
      have_ray = 1;
      break;
    }
  for (ICS_MASK m = mask; ics_mask_any(m); m = ics_mask_drop(m)) {
    double c[3], sg = ics_k_volume_sig(ICS_VIEW_ARG ICS_VOLOBJ(ics_mask_lowest(m)), pt, pt2, c);
    if (keep != 0) sig[nv] = sg;
    nv++;
    sum += sg;
    for (int i = 0; i < 3; i++) cc[i] += sg * c[i];
  }
  if (!(sum > 0)) return;
  if (inview != 0 && C[3] < 1.0) {
    double dl = 1.0;
    if (ICS_CAM(CAM_PROJ) != 0.0) {
      if (have_ray == 0)
        ics_k_plan_ray(ICS_VIEW_ARG bi, bj, ICS_ARG(W), ICS_ARG(H), ICS_ARG(pad_l), ICS_ARG(pad_t),
                       o, d);
      dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    double rgb[3];
    for (int i = 0; i < 3; i++) rgb[i] = cc[i] / sum;
    ics_k_composite(ics_k_piece_alpha(sum, dz, dl), rgb, L, C);
  }
  for (int l = 0; l < ICS_ARG(nlights); l++) {
    double pass[3];
    for (int c = 0; c < 3; c++) pass[c] = 1.0;
    int i = 0;
    for (ICS_MASK m = mask; ics_mask_any(m); m = ics_mask_drop(m)) {
      int ob = ICS_VOLOBJ(ics_mask_lowest(m));
      double c[3], sg = keep != 0 ? sig[i] : ics_k_volume_sig(ICS_VIEW_ARG ob, pt, pt2, c);
      i++;
      for (int ch = 0; ch < ICS_ARG(nch); ch++)
        pass[ch] *= ics_k_piece_pass(sg, dz, ICS_LPATH(l), ICS_OBJ(ob, O_TRANSPORT + ch));
    }
    for (int ch = 0; ch < ICS_ARG(nch); ch++) ICS_DST(l, ch, q) *= ICS_TO_FLOAT(pass[ch]);
  }
}

/* Surface object ob's occlusion at buffer index q, `after` slabs after its first, within each
 * light's window (span x this slab's window, in slabs; occlusion.h), the light's parcels
 * crossing it along the depth gradient (gr, gu) against the light's mean direction. */
ICS_FN void ics_k_surface_occlusion(ICS_VIEW_PARAM int ob, double gr, double gu, int span, int q,
                                    int after) {
  double a = ICS_OBJ(ob, O_OPACITY);
  if (!(a > 0)) return;
  for (int l = 0; l < ICS_ARG(nlights); l++) {
    double win = floor(ICS_TO_DOUBLE(span) * ICS_WINDOW(l));
    if (ICS_TO_DOUBLE(after) > win) continue;
    double rho = -(gr * ICS_LMU(2 * l) + gu * ICS_LMU(2 * l + 1));
    double meets = ics_k_meets(win, ICS_FABS(1 - rho));
    for (int c = 0; c < ICS_ARG(nch); c++)
      ICS_DST(l, c, q) *= ics_k_slab_pass(a, ICS_OBJ(ob, O_TRANSPORT + c), meets);
  }
}

#endif
