/* test_render_propagate.c — the CPU slab step (gpu/backends/cpu/propagate*.c) against the core engine
 * (ics_conv2d_step, double sums per pixel, clamp-to-edge): one tap set with fractional offsets
 * (discretised into a stencil), 2, 4 and 8 tap sets (per-pixel rotations, 2 the default: blended
 * vector loads) and 384 (a per-pixel table: gathers), where each pixel's set is the one its RNG word
 * chooses and the reference applies that set to that pixel alone; in the apron layout (unclamped
 * reads) and without an apron (the clamped path). The portable loops and every vector path the
 * processor has (simd_path.h) are compared. Agreement to 4 float ulps of the values (the engine
 * sums in double and rounds once); since the set of each pixel of every third row is checked,
 * the vector paths' Philox gives exactly ics_slab_pixel_choice's choices. Also rows 1..17 pixels wide
 * on every path, and the fused paths against each other bit for bit. It needs only the propagation sources and the core
 * library, so tests/cross/neon.sh also builds it for AArch64 and runs it under qemu-user. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "propagate.h"
#include "propagate_simd.h"
#include "slab_choice.h"
#include "testutil.h"

enum { W = 77, H = 45 };

static void fill(float *a) {
  for (int i = 0; i < W * H; i++) a[i] = (float)test_rng_unit();
}

/* a plain W x H image into the layout (apron refreshed) and back */
static float *pack(const float *plain, int nch, const ics_buf_layout *L) {
  float *b = calloc((size_t)nch * L->plane, sizeof *b);
  for (int c = 0; c < nch; c++)
    for (int y = 0; y < H; y++)
      memcpy(b + (size_t)c * L->plane + ics_buf_index(L, 0, y), plain + ((size_t)c * H + y) * W,
             sizeof(float) * W);
  ics_prop_apron(L, b, nch, 0, H, 0);
  ics_prop_apron(L, b, nch, 0, 0, ICS_APRON_TOP | ICS_APRON_BOTTOM);
  return b;
}

typedef ics_simd_path path_t;
#define PORTABLE ICS_SIMD_SCALAR

/* the rows through ics_prop_rows on the given path (the portable loops where it does not apply) */
static void step(const ics_prop_taps *pt, const float *src, float *dst, const ics_buf_layout *L,
                int nch, path_t path) {
  uint32_t scratch[ICS_PROP_SCRATCH(W)];
  ics_prop_rows(pt, src, dst, L, nch, 0, H, scratch, path);
}

static const char *path_name(path_t p, const ics_buf_layout *L) {
  return p != PORTABLE ? ics_simd_name(p) : L->apron ? "portable" : "clamped";
}

static void test_stencil(path_t path, int apron) {
  float *plain = malloc(sizeof(float) * W * H), *ref = malloc(sizeof(float) * W * H);
  fill(plain);
  ics_buf_layout L;
  ics_buf_layout_init(&L, W, H, apron);
  float *src = pack(plain, 1, &L), *dst = calloc(L.plane, sizeof *dst);
  ics_tap2d taps[4] = {{0.3, -1.2, 0.4}, {-2.6, 0.7, 0.25}, {1, 2, 0.25}, {4.5, -3.25, 0.1}};
  ics_prop_taps pt = {0};
  CHECK(ics_prop_prepare(&pt, taps, 1, 4, 4, 1, 0, 0, &L) == 0 && pt.stencil, "prepare stencil");
  step(&pt, src, dst, &L, 1, path);
  ics_conv2d_step(plain, ref, W, H, taps, 4, NULL);
  double worst = 0;
  for (int y = 0; y < H; y++)
    for (int x = 0; x < W; x++)
      worst = fmax(worst, fabs(dst[ics_buf_index(&L, x, y)] - ref[y * W + x]) / 0x1p-24);
  CHECK(worst <= 4, "%s stencil vs engine: %.2f ulps of 1", path_name(path, &L), worst);
  printf("stencil (%s, apron %d) vs ics_conv2d_step: max %.2f float ulps of 1\n",
         path_name(path, &L), apron, worst);
  ics_prop_release(&pt);
  free(plain), free(ref), free(src), free(dst);
}

/* M tap sets of 2 taps (an antipodal pair around a mean); each pixel uses the set its RNG word
 * picks, and the reference applies that set to that pixel alone */
static void test_sets_run(int M, path_t path, int apron, int run);
static void test_sets(int M, path_t path, int apron) { test_sets_run(M, path, apron, 1); }

static void test_sets_run(int M, path_t path, int apron, int run) {
  float *plain = malloc(sizeof(float) * 3 * W * H);
  fill(plain), fill(plain + W * H), fill(plain + 2 * W * H);
  ics_buf_layout L;
  ics_buf_layout_init(&L, W, H, apron);
  float *src = pack(plain, 3, &L), *dst = calloc(3 * L.plane, sizeof *dst);
  ics_tap2d *t = malloc(sizeof *t * 2 * M);
  for (int e = 0; e < M; e++) {
    double a = 2 * ICS_PI * e / M;
    t[2 * e] = (ics_tap2d){-0.37 + 1.7 * cos(a), 0.21 + 0.9 * sin(a), 0.5};
    t[2 * e + 1] = (ics_tap2d){-0.37 - 1.7 * cos(a), 0.21 - 0.9 * sin(a), 0.5};
  }
  ics_prop_taps pt = {0};
  CHECK(ics_prop_prepare(&pt, t, M, 2, 2, 1, 0, 0, &L) == 0 && !pt.stencil, "prepare sets");
  pt.seed = 12345, pt.light = 1, pt.slab = 7, pt.run = run, pt.phase = run > 1 ? 5 : 0;
  step(&pt, src, dst, &L, 3, path);
  /* the engine's step with each set, over the whole image, made when a pixel first needs it */
  float **ref = calloc((size_t)M * 3, sizeof *ref);
  double worst = 0;
  for (int y = 0; y < H; y += 3)
    for (int x = 0; x < W; x++) {
      int e = run > 1 ? (int)ics_prop_run_choice(&pt, W, x, y)
                      : (int)ics_slab_pixel_choice(12345, 1, 7, (uint32_t)(y * W + x), (uint32_t)M);
      for (int c = 0; c < 3; c++) {
        float **r = &ref[(size_t)e * 3 + c];
        if (!*r) {
          *r = malloc(sizeof(float) * W * H);
          ics_conv2d_step(plain + (size_t)c * W * H, *r, W, H, t + 2 * e, 2, NULL);
        }
        worst = fmax(worst, fabs(dst[(size_t)c * L.plane + ics_buf_index(&L, x, y)] - (*r)[y * W + x]) /
                                0x1p-24);
      }
    }
  for (int i = 0; i < 3 * M; i++) free(ref[i]);
  free(ref);
  CHECK(worst <= 4, "%s, %d sets, runs of %d, per pixel vs engine: %.2f ulps of 1",
        path_name(path, &L), M, run, worst);
  printf("%d tap sets (%s, apron %d, runs of %d, 3 channels) vs ics_conv2d_step per pixel: max "
         "%.2f float ulps\n", M, path_name(path, &L), apron, run, worst);
  ics_prop_release(&pt);
  free(plain), free(src), free(dst), free(t);
}

/* buffers narrower than a run or a vector (1 .. 17 pixels, runs of 16 at phases 0 and 5, and
 * per-pixel choice), each path against the portable loops, with scratch of exactly
 * ICS_PROP_SCRATCH(w) words on the heap (the runs' choices of a 1-pixel row are 2: ASan sees an
 * overflow) */
static void test_narrow(path_t path) {
  double worst = 0;
  for (int w = 1; w <= 17; w++)
    for (int variant = 0; variant < 3; variant++) {
      ics_buf_layout L;
      ics_buf_layout_init(&L, w, 3, 8);
      float *src = calloc(L.plane, sizeof *src), *a = calloc(L.plane, sizeof *a),
            *b = calloc(L.plane, sizeof *b);
      for (size_t i = 0; i < L.plane; i++) src[i] = (float)test_rng_unit();
      ics_tap2d t[8];
      for (int e = 0; e < 4; e++)
        t[2 * e] = (ics_tap2d){0.3 + 0.4 * e, -0.2, 0.5}, t[2 * e + 1] = (ics_tap2d){-0.5, 0.7 - 0.3 * e, 0.5};
      ics_prop_taps pt = {0};
      CHECK(ics_prop_prepare(&pt, t, 4, 2, 2, 1, 0, 0, &L) == 0, "prepare narrow");
      pt.seed = 99, pt.light = 0, pt.slab = 3, pt.run = variant ? 16 : 1, pt.phase = variant == 2 ? 5 : 0;
      uint32_t *scratch = malloc(sizeof *scratch * ICS_PROP_SCRATCH(w));
      ics_prop_rows(&pt, src, a, &L, 1, 0, 3, scratch, PORTABLE);
      ics_prop_rows(&pt, src, b, &L, 1, 0, 3, scratch, path);
      for (int y = 0; y < 3; y++)
        for (int x = 0; x < w; x++) {
          size_t i = ics_buf_index(&L, x, y);
          worst = fmax(worst, fabs(a[i] - b[i]) / 0x1p-24);
        }
      free(scratch), free(src), free(a), free(b);
      ics_prop_release(&pt);
    }
  CHECK(worst <= 4, "%s, buffers 1..17 wide: %.2f ulps of 1 from the portable loops",
        ics_simd_name(path), worst);
  printf("buffers 1..17 pixels wide (%s, runs of 1 and 16): max %.2f float ulps from portable\n",
         ics_simd_name(path), worst);
}

/* the paths with fused multiply-adds (avx2, avx512, neon) give the same bits for every row
 * width 1..40 (whole vectors, a row end overlapping the last vector, rows narrower than a
 * vector) and every loop: stencil, 4 and 8 blended sets, the 384-entry table, runs of 16 */
static void test_fused_equal(void) {
  int have[ICS_SIMD_PATHS_], nf = 0, bad = 0, cases = 0;
  for (int p = 0; p < ICS_SIMD_PATHS_; p++) {
    have[p] = (p == ICS_SIMD_AVX2 || p == ICS_SIMD_AVX512 || p == ICS_SIMD_NEON) &&
              ics_simd_has((path_t)p);
    nf += have[p];
  }
  if (nf < 2) {
    printf("fused paths bit for bit: skipped (%d of them here)\n", nf);
    return;
  }
  ics_tap2d t[2 * ICS_SLAB_TABLE_M];
  for (int e = 0; e < ICS_SLAB_TABLE_M; e++) {
    double a = 2 * ICS_PI * e / ICS_SLAB_TABLE_M;
    t[2 * e] = (ics_tap2d){0.31 + 1.3 * cos(a), -0.17 + 0.8 * sin(a), 0.5};
    t[2 * e + 1] = (ics_tap2d){0.31 - 1.3 * cos(a), -0.17 - 0.8 * sin(a), 0.5};
  }
  const int sets[] = {1, 4, 8, ICS_SLAB_TABLE_M, 4, 2};
  for (int w = 1; w <= 40; w++)
    for (int v = 0; v < 6; v++) {
      ics_buf_layout L;
      ics_buf_layout_init(&L, w, 2, 8);
      float *src = calloc(L.plane, sizeof *src), *ref = NULL;
      for (size_t i = 0; i < L.plane; i++) src[i] = (float)test_rng_unit();
      ics_prop_taps pt = {0};
      CHECK(ics_prop_prepare(&pt, t, sets[v], 2, 2, 1, 0, 0, &L) == 0, "prepare");
      pt.seed = 3, pt.slab = 11, pt.run = v == 4 ? 16 : 1, pt.phase = w % 16;
      uint32_t *scratch = malloc(sizeof *scratch * ICS_PROP_SCRATCH(w));
      for (int p = 0; p < ICS_SIMD_PATHS_; p++) {
        if (!have[p]) continue;
        float *d = calloc(L.plane, sizeof *d);
        ics_prop_rows(&pt, src, d, &L, 1, 0, 2, scratch, (path_t)p);
        if (!ref) {
          ref = d;
          continue;
        }
        for (int y = 0; y < 2; y++)
          for (int x = 0; x < w; x++) bad += d[ics_buf_index(&L, x, y)] != ref[ics_buf_index(&L, x, y)];
        cases++;
        free(d);
      }
      free(ref), free(src), free(scratch);
      ics_prop_release(&pt);
    }
  CHECK(bad == 0, "the fused paths differ in %d pixels", bad);
  printf("fused paths bit for bit: %d comparisons of rows 1..40 wide, %d pixels differ\n", cases, bad);
}

/* a span [x0, x1) x [y0, y1) gives bit for bit the whole rows' values there and writes nothing
 * else (the cpu backend steps tiles and runs of tiles): every path, every loop (stencil, 4 and 8
 * blended sets, the 384-entry table, runs of 16 at two phases), from every start of a 70-pixel
 * row spans of every width 1..8 and then of growing steps (9, 11, ...: vectors, their overlapping
 * ends, runs cut by the span), over one row and over rows that split into blocks of
 * ICS_PROP_ROW_BLOCK ending in a block of every size 1..8 (21 rows: 8 + 8 + 5; 17 from row 3:
 * 8 + 8 + 1; 9 from row 5: 8 + 1; then 2, 3, 4, 6, 7 and 8 rows) */
static void test_spans(path_t path) {
  ics_tap2d t[2 * ICS_SLAB_TABLE_M];
  for (int e = 0; e < ICS_SLAB_TABLE_M; e++) {
    double a = 2 * ICS_PI * e / ICS_SLAB_TABLE_M;
    t[2 * e] = (ics_tap2d){0.31 + 1.3 * cos(a), -0.17 + 0.8 * sin(a), 0.5};
    t[2 * e + 1] = (ics_tap2d){0.31 - 1.3 * cos(a), -0.17 - 0.8 * sin(a), 0.5};
  }
  const int sets[] = {1, 4, 8, ICS_SLAB_TABLE_M, 4, 4, 2};
  const int w = 70, h = 21, rows[][2] = {{1, 2},  {0, 21}, {3, 20}, {5, 14}, {10, 12},
                                          {2, 5},  {4, 8},  {1, 7},  {0, 7},  {13, 21}};
  int bad = 0, outside = 0, spans = 0;
  for (int v = 0; v < 7; v++) {
    ics_buf_layout L;
    ics_buf_layout_init(&L, w, h, 8);
    float *src = calloc(L.plane, sizeof *src), *full = calloc(L.plane, sizeof *full),
          *d = calloc(L.plane, sizeof *d);
    for (size_t i = 0; i < L.plane; i++) src[i] = (float)test_rng_unit();
    ics_prop_taps pt = {0};
    CHECK(ics_prop_prepare(&pt, t, sets[v], 2, 2, 1, 0, 0, &L) == 0, "prepare spans");
    pt.seed = 5, pt.slab = 2, pt.run = v == 4 || v == 5 ? 16 : 1, pt.phase = v == 5 ? 11 : 0;
    uint32_t *scratch = malloc(sizeof *scratch * ICS_PROP_SCRATCH(w));
    ics_prop_rows(&pt, src, full, &L, 1, 0, h, scratch, path);
    for (int x0 = 0; x0 < w; x0++)
      for (int x1 = x0 + 1; x1 <= w; x1 += 1 + (x1 - x0) / 8) {
        for (int r = 0; r < (int)(sizeof rows / sizeof rows[0]); r++) {
          int y0 = rows[r][0], y1 = rows[r][1];
          for (size_t i = 0; i < L.plane; i++) d[i] = -1;
          ics_prop_span(&pt, src, d, &L, 1, y0, y1, x0, x1, scratch, path);
          for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
              size_t i = ics_buf_index(&L, x, y);
              int in = y >= y0 && y < y1 && x >= x0 && x < x1;
              if (in) bad += d[i] != full[i];
              else outside += d[i] != -1;
            }
          spans++;
        }
      }
    free(scratch), free(src), free(full), free(d);
    ics_prop_release(&pt);
  }
  CHECK(bad == 0 && outside == 0, "%s, spans: %d pixels differ from whole rows, %d written outside",
        ics_simd_name(path), bad, outside);
  printf("spans (%s): %d spans of 70-pixel rows (1 to 21 rows), %d pixels differ from whole rows, "
         "%d written outside\n", ics_simd_name(path), spans, bad, outside);
}

static void test_entries(void) {
  /* the portable loops' row entries equal ics_slab_entry, and their choices among 2, 4 and 8
   * ics_slab_pixel_choice (the vector paths' choices are checked pixel by pixel in test_sets) */
  ics_prop_taps pt = {0};
  pt.seed = 0xfeedface12345678ull, pt.light = 3, pt.slab = 99, pt.entries = ICS_SLAB_TABLE_M;
  uint32_t ent[W];
  int bad = 0;
  for (int y = 0; y < 9; y++) {
    ics_prop_entries_row(&pt, W, y, 0, W, ent);
    for (int x = 0; x < W; x++)
      bad += ent[x] != ics_slab_entry(pt.seed, 3, 99, (uint32_t)(y * W + x)) || ent[x] >= ICS_SLAB_TABLE_M;
  }
  CHECK(bad == 0, "portable row entries differ from ics_slab_entry in %d pixels", bad);
  for (int k = 2; k <= 8; k *= 2) {
    pt.entries = k, bad = 0;
    for (int y = 0; y < 9; y++) {
      ics_prop_entries_row(&pt, W, y, 0, W, ent);
      for (int x = 0; x < W; x++)
        bad += ent[x] != ics_slab_pixel_choice(pt.seed, 3, 99, (uint32_t)(y * W + x), (uint32_t)k) ||
               ent[x] >= (uint32_t)k;
    }
    CHECK(bad == 0, "portable row choices (%d) differ from ics_slab_pixel_choice in %d pixels", k, bad);
  }
  /* the packing, written out: 4 candidates take 2 bits, 16 to a word; pixel 1024 g + 64 c +
   * 16 w + i is bits 31 - 2c .. 30 - 2c of word w of block 16 g + i */
  bad = 0;
  for (uint32_t px = 0; px < 5000; px += 7) {
    uint32_t g = px / 1024, c = px % 1024 / 64, w = px % 64 / 16, i = px % 16, words[4];
    ics_slab_entry_block(pt.seed, 3, 99, 16 * g + i, words);
    bad += ics_slab_pixel_choice(pt.seed, 3, 99, px, 4) != (words[w] >> (30 - 2 * c) & 3);
  }
  CHECK(bad == 0, "packed choices (4) differ from the words' bits in %d pixels", bad);
  /* packed choices are uniform and independent of their neighbours in a row and in the word:
   * chi-square of the pairs (p, p + d) over 4 x 4 bins (15 degrees of freedom: mean 15, sd 5.5) */
  for (int d = 1; d <= 64; d *= 64) {
    long pairs[16] = {0};
    const int NP = 160000;
    for (int p = 0; p < NP; p++)
      pairs[4 * ics_slab_pixel_choice(9, 1, 2, (uint32_t)p, 4) +
            ics_slab_pixel_choice(9, 1, 2, (uint32_t)(p + d), 4)]++;
    double chi2 = 0, e16 = NP / 16.0;
    for (int b = 0; b < 16; b++) chi2 += (pairs[b] - e16) * (pairs[b] - e16) / e16;
    CHECK(fabs(chi2 - 15) < 5 * 5.5, "choices (4) at distance %d not independent: chi^2 = %.1f", d, chi2);
  }
  /* the entries are uniform over the table: chi-square over 384 bins, 384 000 draws */
  static long cnt[ICS_SLAB_TABLE_M];
  const int N = 384000;
  for (int i = 0; i < N; i++) cnt[ics_slab_entry(7, 0, 0, (uint32_t)i)]++;
  double chi = 0, expct = (double)N / ICS_SLAB_TABLE_M;
  for (int i = 0; i < ICS_SLAB_TABLE_M; i++) chi += (cnt[i] - expct) * (cnt[i] - expct) / expct;
  /* 383 degrees of freedom: mean 383, sd 27.7; 5 sd */
  CHECK(fabs(chi - 383) < 5 * 27.7, "entries not uniform: chi^2 = %.1f (383 +- 27.7)", chi);
}

/* Perspective steps (the classes of ics_prop_prepare_perspective): every path against the
 * portable pixel (4 float ulps of 1: the paths with fused multiply-adds round differently), the
 * fused paths against each other bit for bit, and spans against whole rows bit for bit, at
 * magnifications above and below 1 (a few and many classes to a vector), with an apron of 8 and
 * of 1 (lanes reading beyond it take the clamped pixel; the ASan build checks that no read leaves
 * the buffer) */
static void test_classes(void) {
  const ics_tap2d t[2] = {{0.9, -0.4, 0.5}, {-0.9, 0.4, 0.5}};
  /* magnification and principal point: the last makes floor(D) drop inside the first vector
   * (s < 1, D crossing 0 between x = 1 and 2), where the classes' reads reach farthest left */
  const double mags[4][3] = {{1.004, 29.3, 17.8}, {0.993, 29.3, 17.8}, {1.06, 29.3, 17.8},
                             {0.95, 1.02, 1.02}};
  int bad_fused = 0, bad_span = 0, outside = 0;
  double worst = 0;
  for (int a = 0; a < 2; a++)
    for (int v = 0; v < 4; v++) {
      ics_buf_layout L;
      ics_buf_layout_init(&L, W, H, a ? 1 : 8);
      float *src = calloc(3 * L.plane, sizeof *src), *out[ICS_SIMD_PATHS_] = {0};
      for (size_t i = 0; i < 3 * L.plane; i++) src[i] = (float)test_rng_unit();
      for (int c = 0; c < 3; c++) ics_prop_apron(&L, src + c * L.plane, 1, 0, H, ICS_APRON_TOP | ICS_APRON_BOTTOM);
      ics_prop_taps pt = {0};
      CHECK(ics_prop_prepare_perspective(&pt, t, 2, mags[v][0], mags[v][1], mags[v][2], &L) == 0,
            "prepare classes");
      uint32_t scratch[ICS_PROP_SCRATCH(W)];
      for (int p = 0; p < ICS_SIMD_PATHS_; p++) {
        if (p != PORTABLE && !ics_simd_has((path_t)p)) continue;
        out[p] = calloc(3 * L.plane, sizeof *out[p]);
        ics_prop_rows(&pt, src, out[p], &L, 3, 0, H, scratch, (path_t)p);
        for (int c = 0; c < 3; c++)
          for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
              size_t i = c * L.plane + ics_buf_index(&L, x, y);
              worst = fmax(worst, fabs(out[p][i] - out[PORTABLE][i]) / 0x1p-24);
            }
        /* spans of row 5 from every start, widths 1 .. 40 */
        float *d = calloc(3 * L.plane, sizeof *d);
        for (int x0 = 0; x0 < W; x0 += 3)
          for (int x1 = x0 + 1; x1 <= W && x1 <= x0 + 40; x1++) {
            for (size_t i = 0; i < 3 * L.plane; i++) d[i] = -1;
            ics_prop_span(&pt, src, d, &L, 3, 5, 6, x0, x1, scratch, (path_t)p);
            for (int c = 0; c < 3; c++)
              for (int y = 0; y < H; y++)
                for (int x = 0; x < W; x++) {
                  size_t i = c * L.plane + ics_buf_index(&L, x, y);
                  if (y == 5 && x >= x0 && x < x1) bad_span += d[i] != out[p][i];
                  else outside += d[i] != -1;
                }
          }
        free(d);
      }
      const path_t fused[] = {ICS_SIMD_AVX2, ICS_SIMD_AVX512, ICS_SIMD_NEON};
      for (int f = 1; f < 3; f++)
        if (out[fused[0]] && out[fused[f]])
          for (size_t i = 0; i < 3 * L.plane; i++) bad_fused += out[fused[0]][i] != out[fused[f]][i];
      for (int p = 0; p < ICS_SIMD_PATHS_; p++) free(out[p]);
      free(src);
      ics_prop_release(&pt);
    }
  CHECK(worst <= 4, "perspective classes: a path differs from the portable pixel by %.2f ulps", worst);
  CHECK(bad_fused == 0, "perspective classes: the fused paths differ in %d values", bad_fused);
  CHECK(bad_span == 0 && outside == 0, "perspective classes: spans differ in %d values, %d written outside",
        bad_span, outside);
  printf("perspective classes: every path within %.2f ulps of the portable pixel; fused paths "
         "differ in %d values; spans differ in %d, %d written outside\n", worst, bad_fused,
         bad_span, outside);
}

int main(void) {
  /* apron 8 covers every read (unclamped loops); apron 0 takes the clamped path */
  for (int apron = 8; apron >= 0; apron -= 8) {
    test_stencil(PORTABLE, apron);
    test_sets(4, PORTABLE, apron);
    test_sets(ICS_SLAB_TABLE_M, PORTABLE, apron);
  }
  test_sets_run(4, PORTABLE, 8, 16);
  test_spans(PORTABLE);
  /* every vector path this processor has, each against the engine as the portable loops are */
  for (int p = ICS_SIMD_SCALAR + 1; p < ICS_SIMD_PATHS_; p++) {
    if (!ics_simd_has((path_t)p)) {
      printf("%s loops: skipped (not built for this architecture, or this processor lacks them)\n",
             ics_simd_name((path_t)p));
      continue;
    }
    test_sets_run(4, (path_t)p, 8, 16);
    test_stencil((path_t)p, 8);
    test_sets(2, (path_t)p, 8);
    test_sets(4, (path_t)p, 8);
    test_sets(8, (path_t)p, 8);
    test_sets(ICS_SLAB_TABLE_M, (path_t)p, 8);
    test_narrow((path_t)p);
    test_spans((path_t)p);
  }
  test_fused_equal();
  test_classes();
  test_entries();
  return test_summary("test_render_propagate");
}
