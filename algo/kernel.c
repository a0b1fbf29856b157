/* kernel.c -- the anti-diagonal kernel, in three variants (weights from the
 * per-diagonal tables, area on the fly, span on the fly).
 *
 * The portable version runs over blocks of 64 nodes: a loop the compiler
 * vectorises computes the costs and one flag byte per node, then the flags
 * are packed into one word (section 7.3: the incoming edge, one bit per
 * node).  On x86-64 with AVX2, hand-written versions take four nodes at a
 * time and put the comparison mask straight into the word.  Every version
 * does the same IEEE operations in the same order (no fused multiply-add),
 * so all give bit-identical costs and bits. */
#include "algo/kernel.h"

#include <string.h>

/* No clones under a sanitizer: their ifunc resolvers run before its runtime
 * is set up (a ThreadSanitizer build died at start-up in table_chunk's). */
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define KERNEL_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define KERNEL_SANITIZED 1
#endif
#endif
#if defined(__x86_64__) && defined(__GLIBC__) && !defined(KERNEL_SANITIZED) &&        \
    (defined(__clang__) ? __clang_major__ >= 14 : __GNUC__ >= 8)
#define CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CLONES
#endif

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define HAVE_AVX2_KERNEL 1
#include <immintrin.h>
#define AVX2 __attribute__((target("avx2")))
#endif

/* Pack n <= 64 flag bytes (0 or 1) into a word, flag i to bit i. */
static inline uint64_t pack(const uint8_t *f, int n) {
  uint64_t w = 0;
  int i = 0;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  for (; i + 8 <= n; i += 8) {
    uint64_t x;
    memcpy(&x, f + i, 8);
    w |= ((x * 0x0102040810204080ULL) >> 56) << i;   /* byte j -> bit j */
  }
#endif
  for (; i < n; i++) w |= (uint64_t)f[i] << i;
  return w;
}

static void diag_table(const weights *w, int k, int a, int b, const double *restrict prev,
                       double *restrict cur, uint64_t *restrict bits) {
  size_t stride = (size_t)w->n + 1;
  const double *restrict tv = w->tv + (size_t)((k - 1) % w->m) * stride;
  const double *restrict th = w->th + (size_t)(k % w->m) * stride;
  uint8_t f[64];
  for (int c0 = a; c0 <= b; c0 += 64) {
    int len = b - c0 + 1 < 64 ? b - c0 + 1 : 64;
    for (int i = 0; i < len; i++) {
      int c = c0 + i;
      double up = prev[c] + tv[c], left = prev[c - 1] + th[c];
      f[i] = up <= left;
      cur[c] = up <= left ? up : left;
    }
    *bits++ = pack(f, len);
  }
}

static void diag_span_table(const weights *w, int k, int a, int b,
                            const double *restrict prev, double *restrict cur,
                            uint64_t *restrict bits) {
  const double *restrict ts = w->tv + (size_t)(k % w->m) * ((size_t)w->n + 1);
  uint8_t f[64];
  for (int c0 = a; c0 <= b; c0 += 64) {
    int len = b - c0 + 1 < 64 ? b - c0 + 1 : 64;
    for (int i = 0; i < len; i++) {
      int c = c0 + i;
      double up = prev[c], left = prev[c - 1];
      f[i] = up <= left;
      cur[c] = (up <= left ? up : left) + ts[c];
    }
    *bits++ = pack(f, len);
  }
}

/* Row r of node (k-c, c) is stored at index 2m+1-r = base + c.  shadowed:
 * a constant in each caller (diag_area, diag_shadow), so that the paper's
 * weights keep their vectorised loop. */
static inline void diag_area_of(const weights *w, int k, int a, int b, const double *restrict prev,
                                double *restrict cur, uint64_t *restrict bits, int shadowed) {
  int base = 2 * w->m + 1 - k;
  const double *restrict rx = w->rx + base, *restrict ry = w->ry + base;
  const double *restrict rex = w->rex + base, *restrict rey = w->rey + base;
  const double *restrict ree = w->ree + base;
  const double *restrict cx = w->cx + 1, *restrict cy = w->cy + 1;
  const double *restrict cfx = w->cfx + 1, *restrict cfy = w->cfy + 1;
  const double *restrict cff = w->cff + 1;
  double sc = w->sc, shadow = shadowed ? w->shadow : 0;
  uint8_t f[64];
  for (int c0 = a; c0 <= b; c0 += 64) {
    int len = b - c0 + 1 < 64 ? b - c0 + 1 : 64;
    for (int i = 0; i < len; i++) {
      int c = c0 + i;
      /* V(r-1, c): edge R_{r-1} R_r (row r-1 is at index base+c+1), apex C_c.
       * H(r, c-1): edge C_{c-1} C_c, apex R_r. */
      double v = weights_tri(ree[c + 1], rex[c + 1], rey[c + 1], rx[c + 1], ry[c + 1], cx[c],
                             cy[c], sc, shadow);
      double h = weights_tri(cff[c - 1], cfx[c - 1], cfy[c - 1], cx[c - 1], cy[c - 1], rx[c],
                             ry[c], sc, shadow);
      double up = prev[c] + v, left = prev[c - 1] + h;
      f[i] = up <= left;
      cur[c] = up <= left ? up : left;
    }
    *bits++ = pack(f, len);
  }
}

static void diag_area(const weights *w, int k, int a, int b, const double *restrict prev, double *restrict cur,
                      uint64_t *restrict bits) {
  diag_area_of(w, k, a, b, prev, cur, bits, 0);
}

static void diag_shadow(const weights *w, int k, int a, int b, const double *restrict prev, double *restrict cur,
                        uint64_t *restrict bits) {
  diag_area_of(w, k, a, b, prev, cur, bits, 1);
}

static void diag_span(const weights *w, int k, int a, int b, const double *restrict prev,
                      double *restrict cur, uint64_t *restrict bits) {
  int base = 2 * w->m + 1 - k;
  const double *restrict rx = w->rx + base, *restrict ry = w->ry + base;
  const double *restrict cx = w->cx + 1, *restrict cy = w->cy + 1;
  double sc = w->sc, h2 = w->h2;
  uint8_t f[64];
  for (int c0 = a; c0 <= b; c0 += 64) {
    int len = b - c0 + 1 < 64 ? b - c0 + 1 : 64;
    for (int i = 0; i < len; i++) {
      int c = c0 + i;
      double s = weights_len(rx[c], ry[c], cx[c], cy[c], h2, sc);
      double up = prev[c], left = prev[c - 1];
      f[i] = up <= left;
      cur[c] = (up <= left ? up : left) + s;
    }
    *bits++ = pack(f, len);
  }
}

/* Table row s: column c pairs with row r = (s - c) mod m; area: V(r, c) and
 * H(r, c-1); span: |R_r C_c|, the weight of both in-edges of node (r, c)
 * (weights.h says which diagonals each row serves).  Within a run of c where
 * r does not wrap, the reversed row arrays are read forwards. */
CLONES
static void table_chunk(const weights *w, int r, int c0, int len, double *restrict tv,
                        double *restrict th) {
  /* rows r, r-1, ..., at reversed index 2m+1-r+i */
  int base = 2 * w->m + 1 - r;
  const double *restrict rx = w->rx + base, *restrict ry = w->ry + base;
  const double *restrict rex = w->rex + base, *restrict rey = w->rey + base;
  const double *restrict ree = w->ree + base;
  const double *restrict cx = w->cx + 1 + c0, *restrict cy = w->cy + 1 + c0;
  const double *restrict cfx = w->cfx + c0, *restrict cfy = w->cfy + c0;
  const double *restrict cff = w->cff + c0;
  double sc = w->sc, h2 = w->h2, shadow = w->shadow;
  tv += c0;
  if (w->kind == COST_SPAN) {
    /* |R_{r'} C_c|: the in-edge weight of node (r', c). */
    for (int i = 0; i < len; i++) tv[i] = weights_len(rx[i], ry[i], cx[i], cy[i], h2, sc);
    return;
  }
  th += c0;
  if (shadow == 0) {   /* (a loop of its own, vectorised as before there were shadows) */
    for (int i = 0; i < len; i++) {
      tv[i] = weights_tri(ree[i], rex[i], rey[i], rx[i], ry[i], cx[i], cy[i], sc, 0);
      /* H(r', c-1): edge C_{c-1} C_c (column index c-1, stored at c), apex R_{r'}. */
      th[i] = weights_tri(cff[i], cfx[i], cfy[i], cx[i - 1], cy[i - 1], rx[i], ry[i], sc, 0);
    }
    return;
  }
  for (int i = 0; i < len; i++) {
    tv[i] = weights_tri(ree[i], rex[i], rey[i], rx[i], ry[i], cx[i], cy[i], sc, shadow);
    th[i] = weights_tri(cff[i], cfx[i], cfy[i], cx[i - 1], cy[i - 1], rx[i], ry[i], sc, shadow);
  }
}

void kernel_table_row(const weights *w, int s, double *tv, double *th) {
  int m = w->m, n = w->n;
  for (int c = 0; c <= n;) {
    int r = ((s - c) % m + m) % m;
    int len = r + 1 < n + 1 - c ? r + 1 : n + 1 - c;
    table_chunk(w, r, c, len, tv, th);
    c += len;
  }
  if (th && w->kind == COST_AREA) th[0] = 0;   /* column 0 has no horizontal in-edge */
}

#ifdef HAVE_AVX2_KERNEL
/* Four nodes at a time; the scalar tail does exactly the portable version's
 * arithmetic.  `word`/`nb` collect the bits of the current 64-node block. */
#define PUT_BITS(mask, count)                                                  \
  do {                                                                         \
    word |= (uint64_t)(mask) << nb;                                            \
    nb += (count);                                                             \
    if (nb == 64) *bits++ = word, word = 0, nb = 0;                            \
  } while (0)

AVX2 static void diag_table_avx2(const weights *w, int k, int a, int b, const double *prev,
                                 double *cur, uint64_t *bits) {
  size_t stride = (size_t)w->n + 1;
  const double *tv = w->tv + (size_t)((k - 1) % w->m) * stride;
  const double *th = w->th + (size_t)(k % w->m) * stride;
  uint64_t word = 0;
  int nb = 0, c = a;
  for (; c + 3 <= b; c += 4) {
    __m256d up = _mm256_add_pd(_mm256_loadu_pd(prev + c), _mm256_loadu_pd(tv + c));
    __m256d left = _mm256_add_pd(_mm256_loadu_pd(prev + c - 1), _mm256_loadu_pd(th + c));
    __m256d le = _mm256_cmp_pd(up, left, _CMP_LE_OQ);
    _mm256_storeu_pd(cur + c, _mm256_blendv_pd(left, up, le));
    PUT_BITS(_mm256_movemask_pd(le), 4);
  }
  for (; c <= b; c++) {
    double up = prev[c] + tv[c], left = prev[c - 1] + th[c];
    cur[c] = up <= left ? up : left;
    PUT_BITS(up <= left, 1);
  }
  if (nb) *bits = word;
}

AVX2 static void diag_span_table_avx2(const weights *w, int k, int a, int b,
                                      const double *prev, double *cur, uint64_t *bits) {
  const double *ts = w->tv + (size_t)(k % w->m) * ((size_t)w->n + 1);
  uint64_t word = 0;
  int nb = 0, c = a;
  for (; c + 3 <= b; c += 4) {
    __m256d up = _mm256_loadu_pd(prev + c), left = _mm256_loadu_pd(prev + c - 1);
    __m256d le = _mm256_cmp_pd(up, left, _CMP_LE_OQ);
    _mm256_storeu_pd(cur + c, _mm256_add_pd(_mm256_blendv_pd(left, up, le), _mm256_loadu_pd(ts + c)));
    PUT_BITS(_mm256_movemask_pd(le), 4);
  }
  for (; c <= b; c++) {
    double up = prev[c], left = prev[c - 1];
    cur[c] = (up <= left ? up : left) + ts[c];
    PUT_BITS(up <= left, 1);
  }
  if (nb) *bits = word;
}

/* weights_round((sqrt(ee + cz*cz) + shadow cz) * sc) with
 * cz = ex (py - ay) - ey (px - ax), four at a time, operation for operation
 * as weights_tri; without the shadow's two operations where `shadowed` is 0
 * (a constant in each caller: the paper's kernel keeps its work). */
AVX2 static inline __m256d tri4(__m256d ee, __m256d ex, __m256d ey, __m256d ax, __m256d ay,
                                __m256d px, __m256d py, __m256d sc, __m256d sh, int shadowed) {
  const __m256d big = _mm256_set1_pd(0x1p52);
  __m256d dx = _mm256_sub_pd(px, ax), dy = _mm256_sub_pd(py, ay);
  __m256d cz = _mm256_sub_pd(_mm256_mul_pd(ex, dy), _mm256_mul_pd(ey, dx));
  __m256d r = _mm256_sqrt_pd(_mm256_add_pd(ee, _mm256_mul_pd(cz, cz)));
  if (shadowed) r = _mm256_add_pd(r, _mm256_mul_pd(sh, cz));
  __m256d q = _mm256_mul_pd(r, sc);
  return _mm256_sub_pd(_mm256_add_pd(q, big), big);
}

#define L4(p) _mm256_loadu_pd(p)

AVX2 static inline void diag_area_avx2_of(const weights *w, int k, int a, int b, const double *prev,
                                          double *cur, uint64_t *bits, int shadowed) {
  int base = 2 * w->m + 1 - k;
  const double *rx = w->rx + base, *ry = w->ry + base, *rex = w->rex + base;
  const double *rey = w->rey + base, *ree = w->ree + base;
  const double *cx = w->cx + 1, *cy = w->cy + 1, *cfx = w->cfx + 1, *cfy = w->cfy + 1;
  const double *cff = w->cff + 1;
  double sc = w->sc, shadow = shadowed ? w->shadow : 0;
  __m256d sc4 = _mm256_set1_pd(sc), sh4 = _mm256_set1_pd(shadow);
  uint64_t word = 0;
  int nb = 0, c = a;
  for (; c + 3 <= b; c += 4) {
    __m256d v = tri4(L4(ree + c + 1), L4(rex + c + 1), L4(rey + c + 1), L4(rx + c + 1),
                     L4(ry + c + 1), L4(cx + c), L4(cy + c), sc4, sh4, shadowed);
    __m256d h = tri4(L4(cff + c - 1), L4(cfx + c - 1), L4(cfy + c - 1), L4(cx + c - 1),
                     L4(cy + c - 1), L4(rx + c), L4(ry + c), sc4, sh4, shadowed);
    __m256d up = _mm256_add_pd(L4(prev + c), v), left = _mm256_add_pd(L4(prev + c - 1), h);
    __m256d le = _mm256_cmp_pd(up, left, _CMP_LE_OQ);
    _mm256_storeu_pd(cur + c, _mm256_blendv_pd(left, up, le));
    PUT_BITS(_mm256_movemask_pd(le), 4);
  }
  for (; c <= b; c++) {
    double v = weights_tri(ree[c + 1], rex[c + 1], rey[c + 1], rx[c + 1], ry[c + 1], cx[c],
                           cy[c], sc, shadow);
    double h = weights_tri(cff[c - 1], cfx[c - 1], cfy[c - 1], cx[c - 1], cy[c - 1], rx[c],
                           ry[c], sc, shadow);
    double up = prev[c] + v, left = prev[c - 1] + h;
    cur[c] = up <= left ? up : left;
    PUT_BITS(up <= left, 1);
  }
  if (nb) *bits = word;
}

AVX2 static void diag_area_avx2(const weights *w, int k, int a, int b, const double *prev, double *cur,
                                uint64_t *bits) {
  diag_area_avx2_of(w, k, a, b, prev, cur, bits, 0);
}

AVX2 static void diag_shadow_avx2(const weights *w, int k, int a, int b, const double *prev, double *cur,
                                  uint64_t *bits) {
  diag_area_avx2_of(w, k, a, b, prev, cur, bits, 1);
}

AVX2 static void diag_span_avx2(const weights *w, int k, int a, int b, const double *prev,
                                double *cur, uint64_t *bits) {
  int base = 2 * w->m + 1 - k;
  const double *rx = w->rx + base, *ry = w->ry + base;
  const double *cx = w->cx + 1, *cy = w->cy + 1;
  double sc = w->sc, h2 = w->h2;
  const __m256d big = _mm256_set1_pd(0x1p52), sc4 = _mm256_set1_pd(sc), h24 = _mm256_set1_pd(h2);
  uint64_t word = 0;
  int nb = 0, c = a;
  for (; c + 3 <= b; c += 4) {
    __m256d dx = _mm256_sub_pd(L4(cx + c), L4(rx + c)), dy = _mm256_sub_pd(L4(cy + c), L4(ry + c));
    __m256d d2 = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), h24);
    __m256d q = _mm256_mul_pd(_mm256_sqrt_pd(d2), sc4);
    __m256d s4 = _mm256_sub_pd(_mm256_add_pd(q, big), big);
    __m256d up = L4(prev + c), left = L4(prev + c - 1);
    __m256d le = _mm256_cmp_pd(up, left, _CMP_LE_OQ);
    _mm256_storeu_pd(cur + c, _mm256_add_pd(_mm256_blendv_pd(left, up, le), s4));
    PUT_BITS(_mm256_movemask_pd(le), 4);
  }
  for (; c <= b; c++) {
    double s1 = weights_len(rx[c], ry[c], cx[c], cy[c], h2, sc);
    double up = prev[c], left = prev[c - 1];
    cur[c] = (up <= left ? up : left) + s1;
    PUT_BITS(up <= left, 1);
  }
  if (nb) *bits = word;
}
#endif

typedef void diag_fn(const weights *, int, int, int, const double *, double *, uint64_t *);

/* -1: not yet decided; 0: portable; 1: AVX2. */
static int simd = -1;

int kernel_simd(int want) {
#ifdef HAVE_AVX2_KERNEL
  if (simd < 0) simd = __builtin_cpu_supports("avx2") ? 1 : 0;
  if (want >= 0) simd = want && __builtin_cpu_supports("avx2");
  return simd;
#else
  (void)want;
  return simd = 0;
#endif
}

void kernel_diag(const weights *w, int k, int a, int b, const double *prev, double *cur,
                 uint64_t *bits) {
  diag_fn *f;
  if (simd < 0) kernel_simd(-1);
#ifdef HAVE_AVX2_KERNEL
  if (simd)
    f = w->tv ? (w->kind == COST_AREA ? diag_table_avx2 : diag_span_table_avx2)
              : (w->kind == COST_AREA ? (w->shadow == 0 ? diag_area_avx2 : diag_shadow_avx2) : diag_span_avx2);
  else
#endif
    f = w->tv ? (w->kind == COST_AREA ? diag_table : diag_span_table)
              : (w->kind == COST_AREA ? (w->shadow == 0 ? diag_area : diag_shadow) : diag_span);
  f(w, k, a, b, prev, cur, bits);
}
