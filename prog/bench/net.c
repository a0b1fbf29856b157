/* net.c -- ./bench's --topology and --place lists and the network's CSV columns (net.h). */
#include "prog/bench/net.h"

#include <string.h>

const char bench_net_header[] =
    "topology,place,hop_latency,switching,hops_per_msg,hop_bytes,max_link_msgs,max_link_bytes,"
    "link_wait";

/* Split s at commas into at most BENCH_NET_MAX items, each handed to take. */
static int each(const char *s, const char *what, int (*take)(const char *item, void *ud, int i,
                                                             char *err, size_t errlen),
                void *ud, int *n, char *err, size_t errlen) {
  *n = 0;
  const char *p = s;
  for (;;) {
    const char *comma = strchr(p, ',');
    size_t len = comma ? (size_t)(comma - p) : strlen(p);
    char item[PLACE_PATH_MAX + 16];
    if (len == 0 || len >= sizeof item) {
      snprintf(err, errlen, "%s takes a comma-separated list (%s)", what, s);
      return -1;
    }
    if (*n == BENCH_NET_MAX) {
      snprintf(err, errlen, "%s takes at most %d items (%s)", what, BENCH_NET_MAX, s);
      return -1;
    }
    memcpy(item, p, len);
    item[len] = 0;
    if (take(item, ud, (*n)++, err, errlen) != 0) return -1;
    if (!comma) return 0;
    p = comma + 1;
  }
}

static int take_topo(const char *item, void *ud, int i, char *err, size_t errlen) {
  return topo_parse(item, &((bench_topos *)ud)->v[i], err, errlen);
}

static int take_place(const char *item, void *ud, int i, char *err, size_t errlen) {
  return place_parse(item, &((bench_places *)ud)->v[i], err, errlen);
}

int bench_topos_parse(const char *s, bench_topos *out, char *err, size_t errlen) {
  return each(s, "--topology", take_topo, out, &out->n, err, errlen);
}

int bench_places_parse(const char *s, bench_places *out, char *err, size_t errlen) {
  return each(s, "--place", take_place, out, &out->n, err, errlen);
}

void bench_net_fields(FILE *f, const bench_machine *rc, const net_stats *ns) {
  char tn[64], pn[PLACE_PATH_MAX + 16];
  const sim_config *c = &rc->mc.sim;
  place_spec_str(&rc->mc.place, pn, sizeof pn);
  if (rc->mc.backend != MACHINE_SIM) {
    fputs(",,,,,,,,", f);
    return;
  }
  if (c->topo.kind == TOPO_NONE) {
    fprintf(f, ",%s,,,,,,,", pn);
    return;
  }
  topo_spec_str(&c->topo, tn, sizeof tn);
  net_stats z = {0};
  if (!ns) ns = &z;
  fprintf(f, "%s,%s,%.9g,%s,%.6f,%lld,%lld,%lld,%.9f", tn, pn, c->hop_latency,
          c->store_forward ? "store-and-forward" : "cut-through",
          ns->messages ? (double)ns->hops / (double)ns->messages : 0.0, ns->hop_bytes,
          ns->max_link_msgs, ns->max_link_bytes, ns->link_wait);
}
