/* shade.h — the per-pixel shading steps of the cl and gl backends, written once (the cpu backend's
 * gpu/backends/cpu/backend_cpu.c is the reference they follow; docs/renderer.md "Shading and
 * compositing"):
 *   ics_k_frag_*          a fragment code's object, surface bias and slab (ldi.c packs them);
 *   ics_k_volume_sig      a volume's extinction and colour at a piece's sample point(s);
 *   ics_k_volume_piece    one volume piece: its colour composited into the pixel and the light
 *                         buffers attenuated by the volumes' transmittance along each light;
 *   ics_k_surface_occlusion  a surface fragment's occlusion of each light within its window;
 *   ics_k_shade_pixel     all of that for one buffer pixel at one slab, front to back.
 * The including program defines, over its own storage (lang.h "view"): ICS_OBJ(ob, f) (the
 * object records, device_layout.h), ICS_TT(i) (the transfer rows), ICS_PERM(i), ICS_GRID(i),
 * ICS_CAM(f), ICS_VOLOBJ(i) (the object of volume bit i), ICS_LPATH(l) (light l's path per unit
 * depth), ICS_LMU(i) (the lights' means, two per light), ICS_WINDOW(l) (this slab's windows),
 * ICS_DST(l, c, q) (light l's channel c at buffer index q), ICS_ARG(name) (nlights, nch, k, W,
 * H, pad_l, pad_t, preintegrate, zf, zb, window_max, aov_count, aov_vis, aov_z) and
 * ICS_JITTER(k, p) (ics_rng_uniform_at(seed, "jitt" << 32 | k, p)); for ics_k_shade_pixel also
 * the fragments ICS_FZ(f), ICS_FCODE(f), ICS_FGRAD(f) (.x, .y: dz/dr, dz/du), ICS_FSPAN(f), the
 * lights' colour x weight ICS_LCOL(i), and the AOVs ICS_AOV(pi, i), ICS_AOV_SEEN(pi) of view
 * pixel pi. Shared kernel source (lang.h) for slab.cl and slab.comp. */
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

/* Buffer pixel (bi, bj) at slab ICS_ARG(k) (backend_cpu.c shade_rows): the light arriving; the
 * AOVs of its first surface when that lies in this slab (the light before this slab's
 * occlusions, its depth); the occlusions due now; then the volume pieces (not with
 * ICS_SURFACES_ONLY) and surfaces of this slab front to back, composited under C (RGBA of view
 * pixel pi, when inview). p: the pixel's index in the grid, q in the light buffers; its
 * fragments end before `end`; cursor: its next fragment and its next occluding one (updated);
 * mask: the volumes it is inside; returns them after this slab. */
ICS_FN ICS_MASK ics_k_shade_pixel(ICS_VIEW_PARAM int p, int q, int bi, int bj, ICS_UINT end,
                                  ICS_INOUT ICS_UINT cursor[2], ICS_MASK mask, int inview, int pi,
                                  ICS_INOUT float C[4]) {
  int k = ICS_ARG(k), nch = ICS_ARG(nch);
  ICS_UINT cur = cursor[0], acur = cursor[1];
  int has = cur < end && ics_k_frag_slab(ICS_FCODE(cur)) == k ? 1 : 0;
  double L[3];
  for (int c = 0; c < 3; c++) L[c] = 0.0;
  for (int l = 0; l < ICS_ARG(nlights); l++)
    for (int c = 0; c < 3; c++) L[c] += ICS_LCOL(3 * l + c) * ICS_DST(l, nch == 3 ? c : 0, q);
  if (ICS_ARG(aov_count) != 0 && inview != 0 && has != 0 && ICS_AOV_SEEN(pi) == 0)
    for (ICS_UINT f = cur; f < end && ics_k_frag_slab(ICS_FCODE(f)) == k; f++) {
      int ob = ics_k_frag_obj(ICS_FCODE(f));
      if (ICS_OBJ(ob, O_VOLBIT) >= 0.0 || !(ICS_OBJ(ob, O_OPACITY) > 0.0)) continue;
      if (ICS_ARG(aov_vis) >= 0)
        for (int l = 0; l < ICS_ARG(nlights); l++)
          for (int c = 0; c < nch; c++) ICS_AOV(pi, ICS_ARG(aov_vis) + l * nch + c) = ICS_DST(l, c, q);
      if (ICS_ARG(aov_z) >= 0) ICS_AOV(pi, ICS_ARG(aov_z)) = ICS_FZ(f);
      ICS_AOV_SEEN(pi) = 1;
      break;
    }
  for (ICS_UINT f = acur; f < end && ics_k_frag_slab(ICS_FCODE(f)) <= k; f++) {
    ICS_UINT code = ICS_FCODE(f);
    int o = ics_k_frag_obj(code), first = ics_k_frag_slab(code) + ics_k_frag_bias(code);
    if (ICS_OBJ(o, O_VOLBIT) < 0.0 && first <= k &&
        ICS_TO_DOUBLE(k) <= ICS_TO_DOUBLE(first) + ICS_TO_DOUBLE(ICS_FSPAN(f)) * ICS_ARG(window_max))
      ics_k_surface_occlusion(ICS_VIEW_ARG o, ICS_FGRAD(f).x, ICS_FGRAD(f).y, ICS_TO_INT(ICS_FSPAN(f)),
                              q, k - first);
  }
  while (acur < end && ICS_TO_DOUBLE(ics_k_frag_slab(ICS_FCODE(acur)) + ics_k_frag_bias(ICS_FCODE(acur))) +
                               ICS_TO_DOUBLE(ICS_FSPAN(acur)) * ICS_ARG(window_max) <=
                           ICS_TO_DOUBLE(k))
    acur++;
  if (has != 0 || ics_mask_any(mask)) {
    double za = ICS_ARG(zf);
    for (;;) {
      double zn = has != 0 ? ICS_TO_DOUBLE(ICS_FZ(cur)) : ICS_ARG(zb);
      if (zn < za) zn = za;
      if (zn > ICS_ARG(zb)) zn = ICS_ARG(zb);
#ifndef ICS_SURFACES_ONLY
      if (ics_mask_any(mask) && zn > za)
        ics_k_volume_piece(ICS_VIEW_ARG p, q, bi, bj, mask, za, zn - za, L, C, inview);
#endif
      if (has == 0) break;
      int ob = ics_k_frag_obj(ICS_FCODE(cur));
      if (ICS_OBJ(ob, O_VOLBIT) >= 0.0) {
        mask = ics_mask_toggle(mask, ICS_TO_INT(ICS_OBJ(ob, O_VOLBIT)));
      } else if (inview != 0) {
        double a = ICS_OBJ(ob, O_OPACITY), rgb[3];
        for (int c = 0; c < 3; c++) rgb[c] = ICS_OBJ(ob, O_COLOR + c);
        if (a > 0.0 && C[3] < 1.0) ics_k_composite(a, rgb, L, C);
      }
      za = zn;
      cur++;
      has = cur < end && ics_k_frag_slab(ICS_FCODE(cur)) == k ? 1 : 0;
    }
  }
  cursor[0] = cur, cursor[1] = acur;
  return mask;
}

#endif
