/* coll_util.c -- the collectives' point-to-point on packed bytes, and small helpers (coll.h). */
#include <stdio.h>
#include <stdlib.h>

#include "mpi/coll.h"
#include "mpi/op.h"
#include "mpi/core.h"

/* A message longer than the receive: the ranks disagree on the counts. */
static int truncated(const coll_cg *g, int src) {
  if (src < 0)
    return err_comm_raise(g->comm, MPI_ERR_TRUNCATE, g->fn,
                          "a message is longer than expected (do all ranks pass the same counts?)");
  return err_comm_raise(g->comm, MPI_ERR_TRUNCATE, g->fn,
                        "a message from rank %d is longer than expected (do all ranks pass the same counts?)", src);
}

static int too_big(const coll_cg *g, size_t n) {
  return err_comm_raise(g->comm, MPI_ERR_COUNT, g->fn, "a message of %zu bytes (more than INT_MAX)", n);
}

int coll_cg_send(const coll_cg *g, const void *buf, size_t n, int dst) {
  if (n > 0x7fffffff) return too_big(g, n);
  return coll_p2p_send(buf, (int)n, MPI_BYTE, dst, g->tag, g->comm);
}

int coll_cg_recv(const coll_cg *g, void *buf, size_t n, int src, size_t *got) {
  MPI_Status st;
  if (n > 0x7fffffff) return too_big(g, n);
  int rc = coll_p2p_recv(buf, (int)n, MPI_BYTE, src, g->tag, g->comm, &st);
  if (rc == MPI_ERR_TRUNCATE) return truncated(g, src);
  if (rc) return err_comm_raise(g->comm, rc, g->fn, "a receive from rank %d failed", src);
  if (got) *got = (size_t)st.tsmpi_count;
  return MPI_SUCCESS;
}

int coll_cg_sendrecv(const coll_cg *g, const void *sbuf, size_t sn, int dst, void *rbuf, size_t rn, int src,
                     size_t *got) {
  MPI_Status st;
  if (sn > 0x7fffffff) return too_big(g, sn);
  if (rn > 0x7fffffff) return too_big(g, rn);
  int rc = coll_p2p_sendrecv(sbuf, (int)sn, MPI_BYTE, dst, g->tag, rbuf, (int)rn, MPI_BYTE, src, g->tag, g->comm,
                             &st);
  if (rc == MPI_ERR_TRUNCATE) return truncated(g, src);
  if (rc) return err_comm_raise(g->comm, rc, g->fn, "a receive from rank %d failed", src);
  if (got) *got = (size_t)st.tsmpi_count;
  return MPI_SUCCESS;
}

int coll_cg_isend(const coll_cg *g, const void *buf, size_t n, int dst, MPI_Request *req) {
  if (n > 0x7fffffff) return too_big(g, n);
  return coll_p2p_isend(buf, (int)n, MPI_BYTE, dst, g->tag, g->comm, req);
}

int coll_cg_irecv(const coll_cg *g, void *buf, size_t n, int src, MPI_Request *req) {
  if (n > 0x7fffffff) return too_big(g, n);
  return coll_p2p_irecv(buf, (int)n, MPI_BYTE, src, g->tag, g->comm, req);
}

int coll_cg_waitall(const coll_cg *g, int n, MPI_Request *reqs) {
  return coll_cg_failed(g, coll_p2p_waitall(n, reqs, MPI_STATUSES_IGNORE), -1);
}

int coll_cg_failed(const coll_cg *g, int err, int src) {
  if (err == MPI_ERR_TRUNCATE) return truncated(g, src);
  return err ? err_comm_raise(g->comm, err, g->fn, "a request failed") : err;
}

/* The rank's scratch memory in use, freed by the rank's end when a stopped
 * run ends it inside a collective (mp_exit: the collective never returns
 * to free it). */
typedef struct {
  void **p;
  size_t n, cap;
} scratch;

static void scratch_release(void *ud) {
  scratch *s = ud;
  for (size_t i = 0; i < s->n; i++) free(s->p[i]);
  free(s->p);
  free(s);
}

static void oom(const char *fn, size_t n) {
  fprintf(stderr, "tilesim: %s: out of memory (%zu bytes)\n", fn, n);
  abort();
}

void *coll_cg_alloc(const coll_cg *g, size_t n) {
  scratch *s = st_part(ST_PART_COLL);
  if (!s) {
    if (!(s = calloc(1, sizeof *s))) oom(g->fn, sizeof *s);
    st_part_set(ST_PART_COLL, s, scratch_release);
  }
  if (s->n == s->cap) {
    size_t cap = s->cap ? 2 * s->cap : 16;
    void **q = realloc(s->p, cap * sizeof *q);
    if (!q) oom(g->fn, cap * sizeof *q);
    s->p = q;
    s->cap = cap;
  }
  void *p = malloc(n ? n : 1);
  if (!p) oom(g->fn, n);
  s->p[s->n++] = p;
  return p;
}

void coll_cg_free(void *p) {
  scratch *s = st_part(ST_PART_COLL);
  if (!p) return;
  for (size_t i = s ? s->n : 0; i-- > 0;)
    if (s->p[i] == p) {
      s->p[i] = s->p[--s->n];
      break;
    }
  free(p);
}

int coll_pof2(int n) {
  int p = 1;
  while (p <= n / 2) p <<= 1;
  return p;
}

int coll_is_pof2(int n) { return n > 0 && (n & (n - 1)) == 0; }

void coll_red_apply(const coll_red *r, const void *left, void *right, int count) {
  if (count > 0) op_reduce_packed(r->op, r->dt, left, right, count);
}
