/* propagate.h — one slab step of a light buffer on the CPU (docs/renderer.md "One step") over
 * the taps and layout of core/slab_taps.h: the portable loops, with the vector loops of
 * propagate_vec.h where the processor has their instruction set (simd_path.h). */
#ifndef ICS_RENDER_PROPAGATE_H
#define ICS_RENDER_PROPAGATE_H

#include <stddef.h>
#include <stdint.h>

#include "simd_path.h"
#include "slab_taps.h"

/* Refreshes the apron of rows [y0, y1) (left and right) of every plane; then the A rows above
 * row 0 (edges & ICS_APRON_TOP: after row 0 and its sides are final) and those below row h - 1
 * (edges & ICS_APRON_BOTTOM). */
#define ICS_APRON_TOP 1
#define ICS_APRON_BOTTOM 2
void ics_prop_apron(const ics_buf_layout *L, float *buf, int nch, int y0, int y1, int edges);

/* Pixels [x0, x1) x [y0, y1) of the first nch planes of dst from src, nothing else written;
 * scratch holds ICS_PROP_SCRATCH(L->w) words (the entries of ICS_PROP_ROW_BLOCK rows, w + 2
 * words each, or the choices of a row's runs of 16: up to (w + 31) / 16 of them, 2 for w = 1).
 * simd: the loops to take where they apply (ics_simd_choose; the portable ones elsewhere). A
 * pixel's value does not depend on the span it is computed in. */
#define ICS_PROP_ROW_BLOCK 8
#define ICS_PROP_SCRATCH(w) (ICS_PROP_ROW_BLOCK * ((size_t)(w) + 2))
void ics_prop_span(const ics_prop_taps *pt, const float *src, float *dst, const ics_buf_layout *L,
                   int nch, int y0, int y1, int x0, int x1, uint32_t *scratch, ics_simd_path simd);
/* Whole rows [y0, y1): ics_prop_span over [0, L->w). */
void ics_prop_rows(const ics_prop_taps *pt, const float *src, float *dst, const ics_buf_layout *L,
                   int nch, int y0, int y1, uint32_t *scratch, ics_simd_path simd);

/* Pieces shared with the vectorised loops: one pixel with clamped reads from tap set e, and the
 * entries of pixels [x0, x1) of row y (ent[x] for pixel y w + x of the w x h buffer). */
void ics_prop_pixel(const ics_prop_taps *pt, int e, const float *src, float *dst,
                    const ics_buf_layout *L, int nch, int x, int y);
void ics_prop_entries_row(const ics_prop_taps *pt, int w, int y, int x0, int x1, uint32_t *ent);
/* One pixel of a perspective step (pt->classes), clamped reads. */
void ics_prop_pixel_classes(const ics_prop_taps *pt, const float *src, float *dst,
                            const ics_buf_layout *L, int nch, int x, int y);
/* The choice of the run holding pixel (x, y) of a w-wide buffer (pt->run = 16): the choice
 * (ics_slab_choice) of the counter y (w + 32) + 16 floor((x + 16 - phase) / 16). */
uint32_t ics_prop_run_choice(const ics_prop_taps *pt, int w, int x, int y);

#endif
