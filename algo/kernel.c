/* kernel.c -- the anti-diagonal kernel, in three variants (weights from the
 * per-diagonal tables, area on the fly, span on the fly).
 *
 * Each variant runs over blocks of 64 nodes: a loop the compiler vectorises
 * computes the costs and one flag byte per node, then the flags are packed
 * into one word (section 7.3: the incoming edge, one bit per node).  On x86-64
 * each variant is also compiled for AVX2 and picked when the CPU has it; no
 * fused multiply-add is used, so both give bit-identical results. */
#include "kernel.h"

#include <string.h>

#if defined(__x86_64__) && defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__) &&        \
    (defined(__clang__) ? __clang_major__ >= 14 : __GNUC__ >= 8)
#define CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CLONES
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

CLONES
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

CLONES
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

/* Row r of node (k-c, c) is stored at index 2m+1-r = base + c. */
CLONES
static void diag_area(const weights *w, int k, int a, int b, const double *restrict prev,
                      double *restrict cur, uint64_t *restrict bits) {
  int base = 2 * w->m + 1 - k;
  const double *restrict rx = w->rx + base, *restrict ry = w->ry + base;
  const double *restrict rex = w->rex + base, *restrict rey = w->rey + base;
  const double *restrict ree = w->ree + base;
  const double *restrict cx = w->cx + 1, *restrict cy = w->cy + 1;
  const double *restrict cfx = w->cfx + 1, *restrict cfy = w->cfy + 1;
  const double *restrict cff = w->cff + 1;
  double sc = w->sc;
  uint8_t f[64];
  for (int c0 = a; c0 <= b; c0 += 64) {
    int len = b - c0 + 1 < 64 ? b - c0 + 1 : 64;
    for (int i = 0; i < len; i++) {
      int c = c0 + i;
      /* V(r-1, c): edge R_{r-1} R_r (row r-1 is at index base+c+1), apex C_c.
       * H(r, c-1): edge C_{c-1} C_c, apex R_r. */
      double v = weights_tri(ree[c + 1], rex[c + 1], rey[c + 1], rx[c + 1], ry[c + 1], cx[c],
                             cy[c], sc);
      double h = weights_tri(cff[c - 1], cfx[c - 1], cfy[c - 1], cx[c - 1], cy[c - 1], rx[c],
                             ry[c], sc);
      double up = prev[c] + v, left = prev[c - 1] + h;
      f[i] = up <= left;
      cur[c] = up <= left ? up : left;
    }
    *bits++ = pack(f, len);
  }
}

CLONES
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
  double sc = w->sc, h2 = w->h2;
  tv += c0;
  if (w->kind == COST_SPAN) {
    /* |R_{r'} C_c|: the in-edge weight of node (r', c). */
    for (int i = 0; i < len; i++) tv[i] = weights_len(rx[i], ry[i], cx[i], cy[i], h2, sc);
    return;
  }
  th += c0;
  for (int i = 0; i < len; i++) {
    tv[i] = weights_tri(ree[i], rex[i], rey[i], rx[i], ry[i], cx[i], cy[i], sc);
    /* H(r', c-1): edge C_{c-1} C_c (column index c-1, stored at c), apex R_{r'}. */
    th[i] = weights_tri(cff[i], cfx[i], cfy[i], cx[i - 1], cy[i - 1], rx[i], ry[i], sc);
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

void kernel_diag(const weights *w, int k, int a, int b, const double *prev, double *cur,
                 uint64_t *bits) {
  if (w->tv)
    (w->kind == COST_AREA ? diag_table : diag_span_table)(w, k, a, b, prev, cur, bits);
  else
    (w->kind == COST_AREA ? diag_area : diag_span)(w, k, a, b, prev, cur, bits);
}
