/* link.c -- links as FIFO queues reserved in send order; hops, hop-bytes, the busiest link (link.h). */
#include "sim/link.h"

#include <stdlib.h>

#include "sim/trace.h"
#include "util/xmem.h"

typedef struct {
  double free;              /* when the link is next free */
  long long msgs, bytes;    /* what it carried */
} lnk;

struct links {
  const topo *t;
  double m, r, beta;
  int saf;                  /* store-and-forward */
  int bus;                  /* the one shared link, m included */
  int nlinks;
  lnk *l;                   /* [nlinks] */
  long long *base_msgs;     /* [nlinks] msgs and bytes at the period's start */
  long long *base_bytes;
  unsigned char *named;     /* [nlinks] its trace track is named */
  int *route;               /* [max_hops] */
  net_stats total, base;    /* the run's, and at the period's start */
};

links *links_new(const topo *t, double m, double r, double beta, int store_forward) {
  links *n = xcalloc(1, sizeof *n);
  n->t = t;
  n->m = m, n->r = r, n->beta = beta;
  n->saf = store_forward != 0;
  n->bus = topo_kind_of(t) == TOPO_BUS;
  n->nlinks = topo_nlinks(t);
  size_t nl = n->nlinks ? (size_t)n->nlinks : 1;
  n->l = xcalloc(nl, sizeof *n->l);
  n->base_msgs = xcalloc(nl, sizeof *n->base_msgs);
  n->base_bytes = xcalloc(nl, sizeof *n->base_bytes);
  n->named = xcalloc(nl, 1);
  n->route = xmallocarray((size_t)topo_max_hops(t), sizeof *n->route);
  return n;
}

void links_free(links *n) {
  if (!n) return;
  free(n->l);
  free(n->base_msgs);
  free(n->base_bytes);
  free(n->named);
  free(n->route);
  free(n);
}

const topo *links_topo(const links *n) { return n->t; }

link_stats links_get(const links *n, int l) {
  XASSERT(l >= 0 && l < n->nlinks);
  const lnk *k = &n->l[l];
  double busy = (double)k->bytes * n->beta;
  if (n->bus) busy += (double)k->msgs * (n->m + n->r);
  return (link_stats){k->msgs, k->bytes, busy};
}

/* Link l carries the message from s (after waiting from t): trace it. */
static void trace_hop(links *n, trace *tr, int l, double s, double dur, int rank, int dst,
                      int tag, size_t len, uint64_t id) {
  if (!n->named[l]) {
    char name[48];
    topo_link_name(n->t, l, name, sizeof name);
    trace_link_track(tr, l, name);
    n->named[l] = 1;
  }
  trace_link(tr, l, rank, dst, tag, len, id, s, dur);
}

double links_send(links *n, int s, int d, double t0, size_t len, trace *tr, int rank, int dst,
                  int tag, uint64_t id) {
  double lb = (double)len * n->beta, t, start = 0, wait = 0;
  int h = topo_route(n->t, s, d, n->route);
  if (n->bus) {   /* sim.c's SIM_NET_BUS, with r */
    lnk *k = &n->l[0];
    start = t0 > k->free ? t0 : k->free;
    k->free = start + n->m + n->r + lb;
    k->msgs++;
    k->bytes += (long long)len;
    wait = start - t0;
    if (tr) trace_hop(n, tr, 0, start, k->free - start, rank, dst, tag, len, id);
    t = k->free;
  } else {
    t = t0 + n->m;
    double step = n->saf ? n->r + lb : n->r;
    lnk *all = n->l;                 /* locals: the stores below cannot move them */
    const int *route = n->route;
    long long bytes = (long long)len;
    for (int i = 0; i < h; i++) {
      lnk *k = &all[route[i]];
      start = t > k->free ? t : k->free;
      wait += start - t;
      k->free = start + lb;
      k->msgs++;
      k->bytes += bytes;
      if (tr) trace_hop(n, tr, route[i], start, lb, rank, dst, tag, len, id);
      t = start + step;
    }
    t = start + n->r + lb;   /* the tail off the last link */
  }
  n->total.link_wait += wait;
  n->total.messages++;
  n->total.hops += h;
  n->total.hop_bytes += (long long)h * (long long)len;
  return t;
}

/* The busiest links since base (NULL: since the start). */
static void busiest(const links *n, int since, net_stats *out) {
  out->max_link_msgs = out->max_link_bytes = 0;
  for (int l = 0; l < n->nlinks; l++) {
    long long msgs = n->l[l].msgs - (since ? n->base_msgs[l] : 0);
    long long bytes = n->l[l].bytes - (since ? n->base_bytes[l] : 0);
    if (msgs > out->max_link_msgs) out->max_link_msgs = msgs;
    if (bytes > out->max_link_bytes) out->max_link_bytes = bytes;
  }
}

void links_total(const links *n, net_stats *out) {
  *out = n->total;
  busiest(n, 0, out);
}

void links_period(links *n, net_stats *out) {
  out->messages = n->total.messages - n->base.messages;
  out->hops = n->total.hops - n->base.hops;
  out->hop_bytes = n->total.hop_bytes - n->base.hop_bytes;
  out->link_wait = n->total.link_wait - n->base.link_wait;
  busiest(n, 1, out);
  n->base = n->total;
  for (int l = 0; l < n->nlinks; l++) {
    n->base_msgs[l] = n->l[l].msgs;
    n->base_bytes[l] = n->l[l].bytes;
  }
}
