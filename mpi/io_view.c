/* io_view.c -- file views: the filetype's runs of data, and the stream's bytes to the file's
 * (io_view.h). */
#include "mpi/io_view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/dtype.h"

void io_view_default(io_view *v) {
  static MPI_Aint zero = 0, one = 1;
  static MPI_Offset none = 0;
  memset(v, 0, sizeof *v);
  v->etype = v->ftype = MPI_BYTE;
  v->esize = v->fext = 1;
  v->fsize = 1;
  v->nrun = 1;
  v->off = &zero;
  v->len = &one;
  v->before = &none;
  snprintf(v->datarep, sizeof v->datarep, "native");
}

void io_view_free(io_view *v) {
  if (v->heap) {
    free(v->off);
    free(v->len);
    free(v->before);
  }
  dtype_release(v->etype);
  dtype_release(v->ftype);
  v->off = v->len = NULL;
  v->before = NULL;
  v->nrun = 0;
  v->heap = 0;
}

typedef struct {
  MPI_Aint *off, *len;
  size_t n;
  int bad;          /* a negative, decreasing or overlapping run */
} runs;

static void one_run(void *ud, MPI_Aint disp, MPI_Aint len) {
  runs *r = ud;
  if (disp < 0 || (r->n && disp < r->off[r->n - 1] + r->len[r->n - 1])) r->bad = 1;
  r->off[r->n] = disp;
  r->len[r->n++] = len;
}

int io_view_set(io_view *v, MPI_Offset disp, MPI_Datatype etype, MPI_Datatype ftype, const char *datarep,
                char *why, size_t len) {
  char w[96];
  if (disp < 0) {
    snprintf(why, len, "displacement %lld < 0", (long long)disp);
    return MPI_ERR_ARG;
  }
  if (dtype_check(etype, w, sizeof w) != MPI_SUCCESS) {
    snprintf(why, len, "invalid etype: %s", w);
    return MPI_ERR_TYPE;
  }
  if (dtype_check(ftype, w, sizeof w) != MPI_SUCCESS) {
    snprintf(why, len, "invalid filetype: %s", w);
    return MPI_ERR_TYPE;
  }
  if (strcmp(datarep, "native") && strcmp(datarep, "internal")) {
    snprintf(why, len, "data representation \"%.40s\": tilesim has \"native\" and \"internal\" (the same)", datarep);
    return MPI_ERR_UNSUPPORTED_DATAREP;
  }
  MPI_Aint esize = (MPI_Aint)dtype_size(etype);
  MPI_Offset fsize = (MPI_Offset)dtype_size(ftype);
  if (esize == 0 || fsize == 0 || fsize % esize) {
    snprintf(why, len, "%s", esize == 0 ? "the etype has no data" : fsize == 0 ? "the filetype has no data"
                                                                     : "the filetype is not whole etypes");
    return MPI_ERR_ARG;
  }
  size_t n = dtype_segments(ftype, NULL, NULL);
  runs r = {malloc(n * sizeof *r.off), malloc(n * sizeof *r.len), 0, 0};
  MPI_Offset *before = malloc(n * sizeof *before);
  if (!r.off || !r.len || !before) {
    free(r.off), free(r.len), free(before);
    snprintf(why, len, "out of memory for %zu runs", n);
    return MPI_ERR_NO_MEM;
  }
  dtype_segments(ftype, one_run, &r);
  if (r.bad) {
    free(r.off), free(r.len), free(before);
    snprintf(why, len, "the filetype's displacements must be >= 0 and increase (MPI 3.1 section 13.3)");
    return MPI_ERR_ARG;
  }
  for (size_t k = 0; k < n; k++) before[k] = k ? before[k - 1] + r.len[k - 1] : 0;
  dtype_hold(etype);
  dtype_hold(ftype);
  io_view_free(v);
  v->disp = disp;
  v->etype = etype;
  v->ftype = ftype;
  v->esize = esize;
  v->fext = dtype_extent(ftype);
  v->fsize = fsize;
  v->nrun = n;
  v->off = r.off;
  v->len = r.len;
  v->before = before;
  v->heap = 1;
  snprintf(v->datarep, sizeof v->datarep, "%s", datarep);
  return MPI_SUCCESS;
}

/* The run of the tile's data holding the tile's data byte b (0 <= b <
 * fsize): the last k with before[k] <= b. */
static size_t run_of(const io_view *v, MPI_Offset b) {
  size_t lo = 0, hi = v->nrun;
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (v->before[mid] <= b) lo = mid;
    else hi = mid;
  }
  return lo;
}

MPI_Offset io_view_byte(const io_view *v, MPI_Offset pos) {
  MPI_Offset tile = pos / v->fsize, b = pos % v->fsize;
  size_t k = run_of(v, b);
  return v->disp + tile * v->fext + v->off[k] + (b - v->before[k]);
}

int io_view_map(const io_view *v, MPI_Offset pos, MPI_Offset bytes,
                int (*f)(void *ud, MPI_Offset off, MPI_Offset n, MPI_Offset at), void *ud) {
  MPI_Offset at = 0, poff = 0, pn = 0, pat = 0;   /* the piece being merged */
  MPI_Offset tile = pos / v->fsize, b = pos % v->fsize;
  size_t k = run_of(v, b);
  while (at < bytes) {
    MPI_Offset in = b - v->before[k], n = v->len[k] - in;
    if (n > bytes - at) n = bytes - at;
    MPI_Offset off = v->disp + tile * v->fext + v->off[k] + in;
    if (pn && poff + pn == off) {
      pn += n;
    } else {
      int rc = pn ? f(ud, poff, pn, pat) : 0;
      if (rc) return rc;
      poff = off, pn = n, pat = at;
    }
    at += n;
    b += n;
    if (++k == v->nrun || b >= v->fsize) {
      k = 0;
      b = 0;
      tile++;
    }
  }
  return pn ? f(ud, poff, pn, pat) : 0;
}

MPI_Offset io_view_stream(const io_view *v, MPI_Offset off) {
  if (off <= v->disp) return 0;
  MPI_Offset rel = off - v->disp, tile = v->fext > 0 ? rel / v->fext : 0, in = rel - tile * v->fext, s = 0;
  for (size_t k = 0; k < v->nrun; k++) {
    if (v->off[k] >= in) break;
    s += v->off[k] + v->len[k] <= in ? v->len[k] : in - v->off[k];
  }
  return tile * v->fsize + s;
}
