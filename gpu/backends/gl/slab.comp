#version 450
/* slab.comp — the slab renderer's steps per slab as GLSL 4.50 compute shaders (docs/backend_gl.md),
 * the same arithmetic as the cpu backend (gpu/backends/cpu/propagate.c, gpu/backends/cpu/backend_cpu.c) and the cl
 * backend (gpu/backends/cl/slab.cl). One file, one program per entry point: the host compiles it once per
 * ICS_K_* name, defined on the line after #version (glslangValidator -DICS_K_... checks each), and
 * the steps once more with ICS_CLAMPED (a tap reaches past the apron: every read clamps), and
 * each of those with ICS_TAPS_STORAGE (more taps than a uniform block holds).
 *
 *   ICS_K_PROP_STENCIL / _TABLE / _CLASSES  one light buffer's slab step with the host's
 *        prepared taps: integer taps, a table of bilinear tap sets (each pixel takes the set the
 *        counter RNG picks: Philox-4x32-10 as ics_slab_choice), or perspective classes;
 *   ICS_K_ENTRIES_PIXEL / _RUN   those tap-set choices, per pixel or per run of 16;
 *   ICS_K_SHADE_SELECT, _COUNT, ICS_K_SHADE   the buffer pixels with work at this slab, listed,
 *        then per listed pixel: the occlusions due at this slab, the colours of the surfaces and
 *        volume pieces in this slab lit by the light arriving here; the clamp of signed kernels;
 *   ICS_K_APRON_SIDES / _ENDS    the apron of replicated edge pixels, refreshed after a slab.
 *
 * Buffers are SSBOs (the steps read them as buffer textures) with the CPU's layout (propagate.h): light l, channel c at planes l nch + c,
 * pixel (x, y) at origin + y stride + x. Doubles where the CPU computes in double
 * (ARB_gpu_shader_fp64, core since 4.0); exp and pow have no double form in GLSL, so those two
 * run in float (the largest source of the difference to the cpu backend besides the FMAs that
 * `precise` rules out in the steps). No 64-bit integers: the inside masks are uvec2. */
#extension GL_ARB_gpu_shader_fp64 : enable

#define PHILOX_M0 0xD2511F53u
#define PHILOX_M1 0xCD9E8D57u
#define PHILOX_W0 0x9E3779B9u
#define PHILOX_W1 0xBB67AE85u

/* Philox-4x32-10 (libicshadow/src/rng.c) of counter c under key k */
uvec4 philox(uvec4 c, uvec2 k) {
  for (int r = 0; r < 10; r++) {
    uint hi0, lo0, hi1, lo1;
    umulExtended(PHILOX_M0, c.x, hi0, lo0);
    umulExtended(PHILOX_M1, c.z, hi1, lo1);
    c = uvec4(hi1 ^ c.y ^ k.x, lo1, hi0 ^ c.w ^ k.y, lo0);
    k += uvec2(PHILOX_W0, PHILOX_W1);
  }
  return c;
}

/* the buffer layout and the seed (every program sets what it uses) */
uniform int bw, bh, stride, plane, origin, nch;
uniform uint seed_lo, seed_hi;
#define AT(x, y) (origin + (y) * stride + (x))
int clampi(int v, int hi) { return v < 0 ? 0 : v > hi ? hi : v; }

/* ics_slab_choice_bits and ics_slab_word_choice: the bits of a packed choice among k (0: the
 * word scaled), and chunk c of a word */
int choice_bits(uint k) { return k >= 2u && k <= 256u && (k & (k - 1u)) == 0u ? findLSB(k) : 0; }
uint word_choice(uint word, uint k, int b, uint c) {
  if (b != 0) return (word >> uint(32 - b * int(c + 1u))) & (k - 1u);
  uint hi, lo;
  umulExtended(word, k, hi, lo);
  return hi;
}

/* ics_slab_choice: word (id / 16) % 4 of block (id / 64) 16 + id % 16 of the counter (block,
 * slab, light, "slab") scaled to [0, k) */
uint slab_choice(uint light, uint slab, uint id, uint k) {
  uvec4 w = philox(uvec4((id / 64u) * 16u + id % 16u, slab, light, 0x736c6162u),
                   uvec2(seed_lo, seed_hi));
  return word_choice(w[(id / 16u) % 4u], k, 0, 0u);
}

/* ---- the slab step ------------------------------------------------------------------------ */
#if defined(ICS_K_PROP_STENCIL) || defined(ICS_K_PROP_TABLE) || defined(ICS_K_PROP_CLASSES)
layout(local_size_x = 16, local_size_y = 8) in;
/* the taps (ix, iy, off; w, fx, fy) in a uniform block: llvmpipe loads a uniform index once for
 * all invocations, a storage buffer's per invocation. ICS_MAX_TAPS comes from the host (the
 * driver's GL_MAX_UNIFORM_BLOCK_SIZE / 32). */
#ifndef ICS_MAX_TAPS
#define ICS_MAX_TAPS 512
#endif
struct tap { ivec4 i; vec4 f; };
/* the buffers read, as a buffer texture over the same storage: llvmpipe fetches texels 2.3x as
 * fast as shader-storage loads (24 reads per pixel: 25 against 58 ns) */
layout(binding = 0) uniform samplerBuffer src;
layout(std430, binding = 1) writeonly buffer Dst { float dst[]; };
#ifdef ICS_TAPS_STORAGE /* more than a uniform block holds */
layout(std430, binding = 2) readonly buffer Taps { tap taps[]; };
#else
layout(std140, binding = 0) uniform Taps { tap taps[ICS_MAX_TAPS]; };
#endif
layout(std430, binding = 3) readonly buffer Ent { uint ent[]; };
uniform int base, ntaps; /* light l's planes start at base */
uniform int entries, Q;
uniform double s, cx, cy;

float S_at(int c, int i) { return texelFetch(src, base + c * plane + i).r; }

#ifdef ICS_K_PROP_CLASSES
/* the taps of perspective class (kx, ky) at pixel (nx, ny) (propagate.c class_sum) */
float class_sum(int c, int kx, int ky, int nx, int ny) {
  if (kx == Q) kx = 0, nx++;
  if (ky == Q) ky = 0, ny++;
  int b0 = (ky * Q + kx) * ntaps;
  precise float acc = 0;
  for (int m = b0; m < b0 + ntaps; m++)
    acc += taps[m].f.x * S_at(c, AT(clampi(nx + taps[m].i.x, bw - 1), clampi(ny + taps[m].i.y, bh - 1)));
  return acc;
}
#endif

void main() {
  int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= bw || y >= bh) return;
  int p = AT(x, y);
#ifdef ICS_K_PROP_STENCIL
  for (int c = 0; c < nch; c++) {
    precise float acc = 0;
#ifdef ICS_CLAMPED
    for (int j = 0; j < ntaps; j++)
      acc += taps[j].f.x * S_at(c, AT(clampi(x + taps[j].i.x, bw - 1), clampi(y + taps[j].i.y, bh - 1)));
#else
    for (int j = 0; j < ntaps; j++) acc += taps[j].f.x * S_at(c, p + taps[j].i.z);
#endif
    dst[base + c * plane + p] = acc;
  }
#elif defined(ICS_K_PROP_TABLE)
  int e0 = int(ent[y * bw + x]) * ntaps;
  for (int c = 0; c < nch; c++) {
    precise float acc = 0;
    for (int j = e0; j < e0 + ntaps; j++) {
      float a, b, cc, d;
#ifdef ICS_CLAMPED
      int x0 = x + taps[j].i.x, y0 = y + taps[j].i.y;
      int xa = clampi(x0, bw - 1), xb = clampi(x0 + 1, bw - 1);
      int ya = clampi(y0, bh - 1), yb = clampi(y0 + 1, bh - 1);
      a = S_at(c, AT(xa, ya)), b = S_at(c, AT(xb, ya)), cc = S_at(c, AT(xa, yb)), d = S_at(c, AT(xb, yb));
#else
      int r0 = p + taps[j].i.z;
      a = S_at(c, r0), b = S_at(c, r0 + 1), cc = S_at(c, r0 + stride), d = S_at(c, r0 + stride + 1);
#endif
      precise float top = a + taps[j].f.y * (b - a), bot = cc + taps[j].f.y * (d - cc);
      acc += taps[j].f.x * (top + taps[j].f.z * (bot - top));
    }
    dst[base + c * plane + p] = acc;
  }
#else
  /* magnification s about (cx, cy); the four classes around the read offset's fraction */
  double Dx = (s - 1) * (x - cx), Dy = (s - 1) * (y - cy);
  double fX = floor(Dx), tX = (Dx - fX) * Q, kX = floor(tX);
  double fY = floor(Dy), tY = (Dy - fY) * Q, kY = floor(tY);
  int nx = x + int(fX), ny = y + int(fY), k0 = int(kX), k1 = int(kY);
  float r0 = float(tX - kX), r1 = float(tY - kY);
  for (int c = 0; c < nch; c++) {
    float a00 = class_sum(c, k0, k1, nx, ny), a10 = class_sum(c, k0 + 1, k1, nx, ny);
    float a01 = class_sum(c, k0, k1 + 1, nx, ny), a11 = class_sum(c, k0 + 1, k1 + 1, nx, ny);
    precise float top = a00 + r0 * (a10 - a00), bot = a01 + r0 * (a11 - a01);
    precise float v = top + r1 * (bot - top);
    dst[base + c * plane + p] = v;
  }
#endif
}
#endif

/* ---- the tap-set choices of a table step (ics_prop_entries_row, ics_prop_run_choice) ------- */
#if defined(ICS_K_ENTRIES_PIXEL) || defined(ICS_K_ENTRIES_RUN)
layout(std430, binding = 3) writeonly buffer Ent { uint ent[]; };
uniform int entries, npx, phase;
uniform uint light, slab;
#ifdef ICS_K_ENTRIES_PIXEL
/* one invocation per Philox block b: its four words choose pixels 64 n (b / 16) + b % 16 +
 * 64 c + 16 i (word i, chunk c; ics_slab_pixel_choice) */
layout(local_size_x = 64) in;
void main() {
  int bits = choice_bits(uint(entries));
  uint n = uint(ICS_CHOICE_CHUNKS(bits)), b = gl_GlobalInvocationID.x;
  uint first = 64u * n * (b / 16u) + b % 16u;
  if (first >= uint(npx)) return;
  uvec4 w = philox(uvec4(b, slab, light, 0x736c6162u), uvec2(seed_lo, seed_hi));
  for (uint c = 0u; c < n; c++)
    for (int i = 0; i < 4; i++) {
      uint px = first + 64u * c + 16u * uint(i);
      if (px < uint(npx)) ent[px] = word_choice(w[i], uint(entries), bits, c);
    }
}
#else
/* one invocation per run k of row y: the pixels x with (x + 16 - phase) / 16 = k */
layout(local_size_x = 16, local_size_y = 8) in;
void main() {
  int k = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  int xa = max(16 * k - 16 + phase, 0), xb = min(16 * k + phase, bw);
  if (y >= bh || xa >= xb) return;
  uint e = slab_choice(light, slab, uint(y) * uint(bw + 32) + 16u * uint(k), uint(entries));
  for (int x = xa; x < xb; x++) ent[y * bw + x] = e;
}
#endif
#endif

/* ---- the apron of every plane (ics_prop_apron): the sides of each row, then whole rows ----- */
#if defined(ICS_K_APRON_SIDES) || defined(ICS_K_APRON_ENDS)
layout(local_size_x = 64) in;
layout(std430, binding = 1) buffer Dst { float dst[]; };
uniform int A, nplanes;
void main() {
  int c = int(gl_GlobalInvocationID.z);
#ifdef ICS_K_APRON_SIDES
  int a = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (a >= 2 * A || y >= bh) return;
  int row = c * plane + AT(0, y);
  if (a < A) dst[row - 1 - a] = dst[row];
  else dst[row + bw + (a - A)] = dst[row + bw - 1];
#else
  int x = int(gl_GlobalInvocationID.x) - A, r = int(gl_GlobalInvocationID.y);
  if (x >= stride - A || r >= 2 * A) return;
  if (r < A) dst[c * plane + AT(x, -1 - r)] = dst[c * plane + AT(x, 0)];
  else dst[c * plane + AT(x, bh + (r - A))] = dst[c * plane + AT(x, bh - 1)];
#endif
}
#endif

/* ---- shading ------------------------------------------------------------------------------ */
/* Compacted: ICS_K_SHADE_SELECT lists the buffer pixels with work at this slab, in two lists:
 * those in or entering a volume (list 0) and those with only surfaces or occlusion windows
 * (list 1); it clamps the others' signed buffers. ICS_K_SHADE_COUNT turns each list's length
 * into an indirect dispatch, and ICS_K_SHADE shades list 0, compiled with ICS_SURFACES_ONLY
 * list 1. A GPU skips the code that no invocation of a group takes; llvmpipe runs every branch
 * and every loop body at least once under a mask, so the full shading costs about 1 us per
 * invocation there whatever it does (measured: 8.8 ns for an empty program, 76 ns without the
 * volume code, 960 ns with it). */
#if defined(ICS_K_SHADE_SELECT) || defined(ICS_K_SHADE_COUNT) || defined(ICS_K_SHADE)
/* per list i: the indirect dispatch (groups x, y, z) at hdr[5 i], its length at hdr[5 i + 3],
 * the append counter at hdr[5 i + 4]; list i's pixels at work[i npx ...] */
layout(std430, binding = 14) buffer Work { uint hdr[10]; uint work[]; };
uniform int npx;
#endif
#ifdef ICS_K_SHADE_COUNT
layout(local_size_x = 1) in;
void main() {
  for (int i = 0; i < 2; i++) {
    uint n = hdr[5 * i + 4];
    hdr[5 * i] = min((n + 63u) / 64u, 65535u), hdr[5 * i + 1] = 1u, hdr[5 * i + 2] = 1u;
    hdr[5 * i + 3] = n;
    hdr[5 * i + 4] = 0u;
  }
}
#endif
#if defined(ICS_K_SHADE_SELECT) || defined(ICS_K_SHADE)
#ifdef ICS_K_SHADE
layout(local_size_x = 64) in;
#else
layout(local_size_x = 16, local_size_y = 8) in;
#endif
layout(std430, binding = 1) buffer Dst { float dst[]; };
layout(std430, binding = 2) readonly buffer Offsets { uint offset[]; };
layout(std430, binding = 3) readonly buffer Fz { float fz[]; };
layout(std430, binding = 4) readonly buffer Fcode { uint fcode[]; };
layout(std430, binding = 5) readonly buffer Fgrad { vec2 fgrad[]; };
layout(std430, binding = 6) readonly buffer Fspan { uint fspan4[]; }; /* bytes, 4 per word */
layout(std430, binding = 7) buffer Pix { uvec4 pix[]; }; /* cursor, occlusion cursor, inside mask */
layout(std430, binding = 8) readonly buffer Obj { double obj[]; };
layout(std430, binding = 9) readonly buffer SceneD { double sd[]; }; /* transfer rows, camera,
                                                            lights, this slab's windows */
layout(std430, binding = 10) readonly buffer Perm { uint perm4[]; }; /* bytes, 512 per object */
layout(std430, binding = 11) readonly buffer Grids { float grids[]; };
layout(std430, binding = 12) readonly buffer Ints { int ints[]; }; /* vol_obj, then signed_l */
layout(std430, binding = 13) buffer Out { float outv[]; }; /* image RGBA, AOVs, AOV seen flags */

uniform int nlights, k, nvol, W, H, pad_l, pad_t, preintegrate;
uniform int aov_count, aov_vis, aov_z, off_aov, off_seen;
uniform int off_cam, off_lcol, off_lmu, off_lpath, off_window, off_signed;
uniform double zf, zb, window_max;

/* Objects and the camera: the offsets O_*, CAM_* and the strides of gpu/core/device_layout.h
 * (embedded ahead of this file) */
#define OB(i, f) obj[ICS_DEV_OBJ_STRIDE * (i) + (f)]
#define CAM(f) sd[off_cam + (f)]
#define MAXV 8

int frag_obj(uint code) { return int(code & 0xfffu); }
int frag_bias(uint code) { return int(code >> 12 & 0xfu); }
int frag_slab(uint code) { return int(code >> 16); }
uint fspan(uint f) { return fspan4[f >> 2] >> (8u * (f & 3u)) & 255u; }
int perm(int i) { return int(perm4[i >> 2] >> (8 * (i & 3)) & 255u); }
/* the inside mask: lowest set bit, clear it */
int lowest_bit(uvec2 m) { return m.x != 0u ? findLSB(m.x) : 32 + findLSB(m.y); }
uvec2 drop_lowest(uvec2 m) { return m.x != 0u ? uvec2(m.x & (m.x - 1u), m.y) : uvec2(0u, m.y & (m.y - 1u)); }
bool any_bit(uvec2 m) { return (m.x | m.y) != 0u; }

/* ics_rng_uniform_at(seed, "jitt" << 32 | k, p): 53 bits of word p of that stream */
double jitter_at(uint slab_k, uint p) {
  uvec4 w = philox(uvec4(p >> 1, 0u, slab_k, 0x6a697474u), uvec2(seed_lo, seed_hi));
  uvec2 x = (p & 1u) != 0u ? w.zw : w.xy; /* lo, hi */
  return double(x.y) * ldexp(1.0lf, -32) + double(x.x >> 11) * ldexp(1.0lf, -53);
}

/* ics_plan_ray: the camera ray of buffer pixel (bi, bj) */
void plan_ray(int bi, int bj, out dvec3 o, out dvec3 d) {
  double s = (bi - pad_l + 0.5lf) / W, t = (bj - pad_t + 0.5lf) / H;
  dvec3 eye = dvec3(CAM(CAM_EYE), CAM(CAM_EYE + 1), CAM(CAM_EYE + 2));
  dvec3 r = dvec3(CAM(CAM_R), CAM(CAM_R + 1), CAM(CAM_R + 2));
  dvec3 u = dvec3(CAM(CAM_U), CAM(CAM_U + 1), CAM(CAM_U + 2));
  dvec3 f = dvec3(CAM(CAM_F), CAM(CAM_F + 1), CAM(CAM_F + 2));
  if (CAM(CAM_PROJ) == 0) {
    double h = CAM(CAM_H), w = CAM(CAM_W);
    for (int i = 0; i < 3; i++) {
      o[i] = eye[i] + (s - 0.5lf) * w * r[i] + (0.5lf - t) * h * u[i];
      d[i] = f[i];
    }
  } else {
    double th = CAM(CAM_TH), asp = CAM(CAM_ASP);
    for (int i = 0; i < 3; i++) {
      o[i] = eye[i];
      d[i] = f[i] + (2 * s - 1) * th * asp * r[i] + (1 - 2 * t) * th * u[i];
    }
  }
}

/* detail.c: improved noise, fBm, ridged multifractal (permutation of object pb / 512) */
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double lerp_d(double t, double a, double b) { return a + t * (b - a); }
double grad3(int hash, double x, double y, double z) {
  int h = hash & 15;
  double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) != 0 ? -u : u) + ((h & 2) != 0 ? -v : v);
}
double perlin(int pb, double x, double y, double z) {
  double fx = floor(x), fy = floor(y), fz_ = floor(z);
  int X = int(fx - 256 * floor(fx / 256)) & 255, Y = int(fy - 256 * floor(fy / 256)) & 255,
      Z = int(fz_ - 256 * floor(fz_ / 256)) & 255;
  x -= fx, y -= fy, z -= fz_;
  double u = fade(x), v = fade(y), w = fade(z);
  int A_ = perm(pb + X) + Y, AA = perm(pb + A_) + Z, AB = perm(pb + A_ + 1) + Z;
  int B_ = perm(pb + X + 1) + Y, BA = perm(pb + B_) + Z, BB = perm(pb + B_ + 1) + Z;
  return lerp_d(w,
                lerp_d(v, lerp_d(u, grad3(perm(pb + AA), x, y, z), grad3(perm(pb + BA), x - 1, y, z)),
                       lerp_d(u, grad3(perm(pb + AB), x, y - 1, z), grad3(perm(pb + BB), x - 1, y - 1, z))),
                lerp_d(v, lerp_d(u, grad3(perm(pb + AA + 1), x, y, z - 1),
                                 grad3(perm(pb + BA + 1), x - 1, y, z - 1)),
                       lerp_d(u, grad3(perm(pb + AB + 1), x, y - 1, z - 1),
                              grad3(perm(pb + BB + 1), x - 1, y - 1, z - 1))));
}

/* ics_volume_sample: trilinear, cell centres at i + 1/2, clamped at the faces, 0 outside */
double grid_sample(int g0, ivec3 n, dvec3 p) {
  ivec3 i0, i1;
  dvec3 f;
  for (int a = 0; a < 3; a++) {
    if (!(p[a] >= 0.0lf && p[a] <= double(n[a]))) return 0.0lf;
    double g = p[a] - 0.5lf, fl = floor(g);
    f[a] = g - fl;
    int i = int(fl), last = n[a] - 1;
    i0[a] = i < 0 ? 0 : i > last ? last : i;
    i1[a] = i + 1 < 0 ? 0 : i + 1 > last ? last : i + 1;
  }
  int sy = n.x, sz = n.x * n.y;
#define V_(i, j, l) double(grids[g0 + (i) + (j) * sy + (l) * sz])
  double c00 = V_(i0.x, i0.y, i0.z) * (1 - f.x) + V_(i1.x, i0.y, i0.z) * f.x;
  double c10 = V_(i0.x, i1.y, i0.z) * (1 - f.x) + V_(i1.x, i1.y, i0.z) * f.x;
  double c01 = V_(i0.x, i0.y, i1.z) * (1 - f.x) + V_(i1.x, i0.y, i1.z) * f.x;
  double c11 = V_(i0.x, i1.y, i1.z) * (1 - f.x) + V_(i1.x, i1.y, i1.z) * f.x;
#undef V_
  double c0 = c00 * (1 - f.y) + c10 * f.y, c1 = c01 * (1 - f.y) + c11 * f.y;
  return c0 * (1 - f.z) + c1 * f.z;
}

double detail_value(int ob, dvec3 pt) {
  const dvec3 drift = dvec3(0.3713lf, 0.5129lf, 0.7731lf);
  int fn = int(OB(ob, O_DETAIL)), octaves = int(OB(ob, O_OCTAVES));
  if (fn == 4) { /* the grid over the object's box (detail.c) */
    ivec3 n;
    dvec3 q;
    for (int i = 0; i < 3; i++) {
      double lo = OB(ob, O_GRID_LO + i), hi = OB(ob, O_GRID_HI + i);
      n[i] = int(OB(ob, O_GRID_N + i));
      q[i] = hi > lo ? (pt[i] - lo) / (hi - lo) * double(n[i]) : 0;
    }
    return OB(ob, O_BIAS) + OB(ob, O_SCALE) * grid_sample(int(OB(ob, O_GRID)), n, q);
  }
  int pb = 512 * ob;
  double fr = OB(ob, O_FREQ), tm = OB(ob, O_TIME), lac = OB(ob, O_LACUNARITY), gain = OB(ob, O_GAIN);
  double x = fr * pt.x + tm * drift.x, y = fr * pt.y + tm * drift.y, z = fr * pt.z + tm * drift.z;
  double f;
  if (fn == 1) {
    f = perlin(pb, x, y, z);
  } else if (fn == 2) {
    f = 0;
    double amp = 1;
    for (int o = 0; o < octaves; o++) {
      f += amp * perlin(pb, x, y, z);
      amp *= gain;
      x *= lac, y *= lac, z *= lac;
    }
  } else {
    double off = OB(ob, O_OFFSET), signal = off - abs(perlin(pb, x, y, z));
    signal *= signal;
    f = signal;
    double expo = 1;
    for (int o = 1; o < octaves; o++) {
      x *= lac, y *= lac, z *= lac;
      expo /= lac;
      double weight = signal * gain;
      weight = weight < 0 ? 0 : weight > 1 ? 1 : weight;
      signal = off - abs(perlin(pb, x, y, z));
      signal *= signal * weight;
      f += signal * expo;
    }
  }
  return OB(ob, O_BIAS) + OB(ob, O_SCALE) * f;
}

/* ics_material_transfer (rows of v, r, g, b, scale from sd[5 O_TRANSFER]) */
void transfer(int ob, double v, out dvec3 rgb, out double scale) {
  int n = int(OB(ob, O_NTRANSFER));
  if (n == 0) {
    rgb = dvec3(OB(ob, O_COLOR), OB(ob, O_COLOR + 1), OB(ob, O_COLOR + 2));
    scale = v > 0 ? v : 0;
    return;
  }
  int t = 5 * int(OB(ob, O_TRANSFER)), j = 0;
  if (v <= sd[t]) {
    j = -1;
  } else if (v >= sd[t + 5 * (n - 1)]) {
    j = n - 1;
  } else {
    while (j + 1 < n && sd[t + 5 * (j + 1)] <= v) j++;
  }
  if (j < 0 || j == n - 1) {
    int row = t + 5 * (j < 0 ? 0 : n - 1);
    rgb = dvec3(sd[row + 1], sd[row + 2], sd[row + 3]);
    scale = sd[row + 4];
    return;
  }
  int r0 = t + 5 * j, r1 = r0 + 5;
  double a = (v - sd[r0]) / (sd[r1] - sd[r0]);
  for (int c = 0; c < 3; c++) rgb[c] = sd[r0 + 1 + c] + a * (sd[r1 + 1 + c] - sd[r0 + 1 + c]);
  scale = sd[r0 + 4] + a * (sd[r1 + 4] - sd[r0 + 4]);
}

void linear_piece(int ob, double a, double b, inout double S, inout dvec3 CS) {
  dvec3 ca, cm, cb;
  double sa, sm, sb, h = b - a;
  transfer(ob, a, ca, sa);
  transfer(ob, 0.5lf * (a + b), cm, sm);
  transfer(ob, b, cb, sb);
  S += h * (sa + 4 * sm + sb) / 6;
  for (int c = 0; c < 3; c++) CS[c] += h * (ca[c] * sa + 4 * cm[c] * sm + cb[c] * sb) / 6;
}

/* ics_material_preintegrate, walking the breakpoints in order */
void preintegrate_piece(int ob, double vf, double vb, out dvec3 rgb, out double scale) {
  double lo = min(vf, vb), hi = max(vf, vb);
  if (!(hi - lo > 1e-12lf * (1 + abs(hi)))) {
    transfer(ob, 0.5lf * (vf + vb), rgb, scale);
    return;
  }
  int n = int(OB(ob, O_NTRANSFER)), t = 5 * int(OB(ob, O_TRANSFER));
  double S = 0, prev = lo;
  dvec3 CS = dvec3(0);
  if (n == 0) {
    if (lo < 0 && hi > 0) linear_piece(ob, prev, 0.0lf, S, CS), prev = 0;
  } else {
    for (int i = 0; i < n; i++)
      if (sd[t + 5 * i] > lo && sd[t + 5 * i] < hi) linear_piece(ob, prev, sd[t + 5 * i], S, CS), prev = sd[t + 5 * i];
  }
  linear_piece(ob, prev, hi, S, CS);
  scale = S / (hi - lo);
  if (S > 0) {
    rgb = CS / S;
  } else {
    transfer(ob, 0.5lf * (vf + vb), rgb, scale);
    scale = 0;
  }
}

/* the extinction and colour of volume object ob at the piece's sample point(s) */
double volume_sig(int ob, dvec3 pt, dvec3 pt2, out dvec3 c) {
  double scale = 1;
  c = dvec3(OB(ob, O_COLOR), OB(ob, O_COLOR + 1), OB(ob, O_COLOR + 2));
  if (OB(ob, O_DETAIL) != 0) {
    double v = detail_value(ob, pt);
    if (preintegrate != 0) preintegrate_piece(ob, v, detail_value(ob, pt2), c, scale);
    else transfer(ob, v, c, scale);
  }
  return OB(ob, O_EXTINCTION) * scale;
}

#define DST(l, c, q) dst[((l) * nch + (c)) * plane + (q)]

/* backend_cpu.c volume_piece: one volume piece of depth extent dz from za */
void volume_piece(uint p, int q, int bi, int bj, uvec2 mask, double za, double dz, dvec3 L,
                  inout vec4 C, bool inview) {
  double sig[MAXV], sum = 0;
  dvec3 o, d, pt = dvec3(0), pt2 = dvec3(0), cc = dvec3(0);
  int nv = 0;
  bool have_ray = false, keep = bitCount(mask.x) + bitCount(mask.y) <= MAXV;
  for (uvec2 m = mask; any_bit(m); m = drop_lowest(m)) /* the sample point, if some volume has detail */
    if (OB(ints[lowest_bit(m)], O_DETAIL) != 0) {
      plan_ray(bi, bj, o, d);
      if (preintegrate != 0) {
        pt = o + za * d, pt2 = o + (za + dz) * d;
      } else {
        double zs = za + jitter_at(uint(k), p) * dz;
        pt = o + zs * d;
      }
      have_ray = true;
      break;
    }
  for (uvec2 m = mask; any_bit(m); m = drop_lowest(m), nv++) {
    dvec3 c;
    double sg = volume_sig(ints[lowest_bit(m)], pt, pt2, c);
    if (keep) sig[nv] = sg;
    sum += sg;
    cc += sg * c;
  }
  if (!(sum > 0)) return;
  if (inview && C.w < 1) {
    double dl = 1;
    if (CAM(CAM_PROJ) != 0) {
      if (!have_ray) plan_ray(bi, bj, o, d);
      dl = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    }
    double a = 1 - double(exp(float(-sum * dz * dl))), wgt = (1 - C.w) * a;
    C.x += float(wgt * (cc.x / sum) * L.x);
    C.y += float(wgt * (cc.y / sum) * L.y);
    C.z += float(wgt * (cc.z / sum) * L.z);
    C.w += float(wgt);
  }
  for (int l = 0; l < nlights; l++) {
    double pass[3] = double[3](1, 1, 1);
    int i = 0;
    for (uvec2 m = mask; any_bit(m); m = drop_lowest(m), i++) {
      int ob = ints[lowest_bit(m)];
      dvec3 c;
      double sg = keep ? sig[i] : volume_sig(ob, pt, pt2, c);
      for (int ch = 0; ch < nch; ch++)
        pass[ch] *= double(exp(float(-sg * dz * sd[off_lpath + l] * (1 - OB(ob, O_TRANSPORT + ch)))));
    }
    for (int ch = 0; ch < nch; ch++) DST(l, ch, q) *= float(pass[ch]);
  }
}

/* backend_cpu.c surface_occlusion: object ob's occlusion, `after` slabs after its first */
void surface_occlusion(int ob, vec2 g, uint span, int q, int after) {
  double a = OB(ob, O_OPACITY);
  if (!(a > 0)) return;
  double gr = g.x, gu = g.y;
  for (int l = 0; l < nlights; l++) {
    double win = floor(span * sd[off_window + l]);
    if (after > win) continue;
    double rho = -(gr * sd[off_lmu + 2 * l] + gu * sd[off_lmu + 2 * l + 1]), rel = abs(1 - rho), meets = 1;
    if (win > 0) meets = rel > 0 ? min(max((win + 1) / rel, 1.0lf), 8 * (win + 1)) : 8 * (win + 1);
    for (int c = 0; c < nch; c++) {
      double pass = 1 - a * (1 - OB(ob, O_TRANSPORT + c));
      DST(l, c, q) *= meets > 1 ? pow(float(pass), float(1 / meets)) : float(pass);
    }
  }
}

/* the clamp of signed kernels, after the shading */
void clamp_signed(int q) {
  for (int l = 0; l < nlights; l++)
    if (ints[off_signed + l] != 0)
      for (int c = 0; c < nch; c++) {
        float v = DST(l, c, q);
        DST(l, c, q) = v < 0 ? 0 : v > 1 ? 1 : v;
      }
}

#ifdef ICS_K_SHADE_SELECT
void main() {
  int bi = int(gl_GlobalInvocationID.x), bj = int(gl_GlobalInvocationID.y);
  if (bi >= bw || bj >= bh) return;
  uint p = uint(bj * bw + bi);
  uvec4 st = pix[p];
  uint cur = st.x, acur = st.y, end = offset[p + 1u];
  bool has = cur < end && frag_slab(fcode[cur]) == k;
  bool occl = acur < end && frag_slab(fcode[acur]) <= k;
  bool vol = nvol != 0 && any_bit(st.zw);
  for (uint f = cur; nvol != 0 && !vol && f < end && frag_slab(fcode[f]) == k; f++)
    vol = OB(frag_obj(fcode[f]), O_VOLBIT) >= 0;
  int list = vol ? 0 : 1;
  if (vol || has || occl) work[uint(list * npx) + atomicAdd(hdr[5 * list + 4], 1u)] = p;
  else clamp_signed(AT(bi, bj));
}
#else
/* per listed buffer pixel, slab k (backend_cpu.c shade_rows) */
#ifdef ICS_SURFACES_ONLY
#define LIST 1
#else
#define LIST 0
#endif
void shade_pixel(uint p) {
  int bi = int(p % uint(bw)), bj = int(p / uint(bw));
  int q = AT(bi, bj);
  uvec4 st = pix[p];
  uint cur = st.x, acur = st.y, end = offset[p + 1u];
  uvec2 mask = nvol != 0 ? st.zw : uvec2(0u);
  bool has = cur < end && frag_slab(fcode[cur]) == k;
  {
    int ii = bi - pad_l, jj = bj - pad_t;
    bool inview = ii >= 0 && ii < W && jj >= 0 && jj < H;
    int pi = jj * W + ii;
    vec4 C = inview ? vec4(outv[4 * pi], outv[4 * pi + 1], outv[4 * pi + 2], outv[4 * pi + 3])
                    : vec4(0, 0, 0, 1);
    dvec3 L = dvec3(0);
    for (int l = 0; l < nlights; l++)
      for (int c = 0; c < 3; c++) L[c] += sd[off_lcol + 3 * l + c] * DST(l, nch == 3 ? c : 0, q);
    /* the AOVs of the pixel's first surface, if it is in this slab (backend_cpu.c record_aov) */
    if (aov_count != 0 && inview && has && outv[off_seen + pi] == 0)
      for (uint f = cur; f < end && frag_slab(fcode[f]) == k; f++) {
        int ob = frag_obj(fcode[f]);
        if (OB(ob, O_VOLBIT) >= 0 || !(OB(ob, O_OPACITY) > 0)) continue;
        int o = off_aov + pi * aov_count;
        if (aov_vis >= 0)
          for (int l = 0; l < nlights; l++)
            for (int c = 0; c < nch; c++) outv[o + aov_vis + l * nch + c] = DST(l, c, q);
        if (aov_z >= 0) outv[o + aov_z] = fz[f];
        outv[off_seen + pi] = 1;
        break;
      }
    for (uint f = acur; f < end && frag_slab(fcode[f]) <= k; f++) {
      uint code = fcode[f];
      int o = frag_obj(code), first = frag_slab(code) + frag_bias(code);
      if (OB(o, O_VOLBIT) < 0 && first <= k && k <= first + fspan(f) * window_max)
        surface_occlusion(o, fgrad[f], fspan(f), q, k - first);
    }
    while (acur < end && frag_slab(fcode[acur]) + frag_bias(fcode[acur]) + fspan(acur) * window_max <= k)
      acur++;
    if (has || any_bit(mask)) {
      double za = zf;
      for (;;) {
        double zn = has ? double(fz[cur]) : zb;
        if (zn < za) zn = za;
        if (zn > zb) zn = zb;
#ifndef ICS_SURFACES_ONLY
        if (any_bit(mask) && zn > za) volume_piece(p, q, bi, bj, mask, za, zn - za, L, C, inview);
#endif
        if (!has) break;
        int ob = frag_obj(fcode[cur]);
        if (OB(ob, O_VOLBIT) >= 0) {
          int bit = int(OB(ob, O_VOLBIT));
          if (bit < 32) mask.x ^= 1u << bit;
          else mask.y ^= 1u << (bit - 32);
        } else if (inview) {
          double a = OB(ob, O_OPACITY);
          if (a > 0 && C.w < 1) {
            double wgt = (1 - C.w) * a;
            C.x += float(wgt * OB(ob, O_COLOR) * L.x);
            C.y += float(wgt * OB(ob, O_COLOR + 1) * L.y);
            C.z += float(wgt * OB(ob, O_COLOR + 2) * L.z);
            C.w += float(wgt);
          }
        }
        za = zn;
        cur++;
        has = cur < end && frag_slab(fcode[cur]) == k;
      }
    }
    pix[p] = uvec4(cur, acur, nvol != 0 ? mask : st.zw);
    if (inview) outv[4 * pi] = C.x, outv[4 * pi + 1] = C.y, outv[4 * pi + 2] = C.z, outv[4 * pi + 3] = C.w;
  }
  clamp_signed(q);
}

/* the list in a grid-stride loop: ICS_K_SHADE_COUNT caps the groups at 65535 (the smallest
 * GL_MAX_COMPUTE_WORK_GROUP_COUNT) */
void main() {
  for (uint w = gl_GlobalInvocationID.x; w < hdr[5 * LIST + 3]; w += gl_NumWorkGroups.x * 64u)
    shade_pixel(work[uint(LIST * npx) + w]);
}
#endif
#endif
