/* report.c -- ./tile's CSV, row by row (report.h). */
#include "surface/report.h"

static const char par_cols[] = ",procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend";
static const char par_empty[] = ",,,,,,,,";
static const char net_cols[] = ",hops_per_msg,hop_bytes,max_link_msgs,max_link_bytes,link_wait";
static const char net_empty[] = ",,,,,";

/* The simulator on a topology (--topology): each band's network columns. */
static int topology(const run_config *rc) { return rc && rc->mc.sim.topo.kind != TOPO_NONE; }

void report_header(FILE *f, const char *prefix, const run_config *rc) {
  fprintf(f, "%sband,z0,z1,depth,lower,upper,junction,m,n,bridges,cost,area,volume,nodes,spans,euler,genus%s%s\n",
          prefix, rc ? par_cols : "", topology(rc) ? net_cols : "");
}

static void list(FILE *f, const int *x, int n) {
  fputc(',', f);
  for (int i = 0; i < n; i++) fprintf(f, "%s%d", i ? "+" : "", x[i]);
}

/* A volume, or nothing where the surface encloses none (an open one). */
static void volume_field(FILE *f, int closed, double v) {
  if (closed) fprintf(f, ",%.17g", v);
  else fputc(',', f);
}

void report_rows(FILE *f, const char *prefix, const stack_surface *ss, const run_config *rc) {
  const stack_row *r = stack_rows(ss);
  const par_pair *pp = stack_pairs(ss);
  int nb = 0, bridges = 0, spans = 0;
  double cost, area, volume, zmin = 0, zmax = 0;
  unsigned long long nodes = 0;
  const manifold_component *c = stack_components(ss);
  int nc = stack_ncomponents(ss), closed = nc > 0, manifold = nc > 0, euler = 0;
  for (int i = 0; i < nc; i++) {
    if (i == 0 || c[i].zmin < zmin) zmin = c[i].zmin;
    if (i == 0 || c[i].zmax > zmax) zmax = c[i].zmax;
    closed &= c[i].closed;
    manifold &= c[i].manifold;
    euler += c[i].euler;
  }
  for (int i = 0; i < stack_nrows(ss); i++) {
    const stack_row *x = &r[i];
    fputs(prefix, f);
    if (x->kind == STACK_BAND) fprintf(f, "%d", nb++);
    else fputs("cap", f);
    fprintf(f, ",%.17g,%.17g,%d", x->z0, x->z1, x->depth);
    list(f, x->lo, x->nlo);
    list(f, x->hi, x->nhi);
    fprintf(f, ",%d-%d,%d,%d", x->nlo, x->nhi, x->m, x->n);
    if (x->kind == STACK_BAND) {
      fprintf(f, ",%d,%.17g,%.17g", x->bridges, x->cost, x->area);
      volume_field(f, closed, x->volume);
      fprintf(f, ",%llu,%d,,", x->nodes, x->spans);
      bridges += x->bridges;
      spans += x->spans;
      nodes += x->nodes;
    } else {
      fprintf(f, ",,,%.17g", x->area);
      volume_field(f, closed, x->volume);
      fputs(",,,,", f);
    }
    if (rc && x->pair >= 0) {
      const par_counts *pc = &pp[x->pair].counts;
      unsigned long long bytes = 0;
      for (int k = 0; k < PAR_KINDS; k++) bytes += pc->bytes[k];
      fprintf(f, ",%d,%.9f,%llu,%llu,%llu,%llu,%llu,%s", rc->mc.procs, pp[x->pair].time,
              (unsigned long long)pc->msgs[PAR_BOUNDARY], (unsigned long long)pc->msgs[PAR_BACKTRACK],
              (unsigned long long)pc->msgs[PAR_BOUNDS], (unsigned long long)pc->msgs[PAR_CONTROL], bytes,
              machine_backend_name(rc->mc.backend));
    } else if (rc) {
      fputs(par_empty, f);
    }
    if (topology(rc) && x->pair >= 0) {
      const net_stats *ns = &stack_nets(ss)[x->pair];
      fprintf(f, ",%.6f,%lld,%lld,%lld,%.9f", ns->messages ? (double)ns->hops / (double)ns->messages : 0.0,
              ns->hop_bytes, ns->max_link_msgs, ns->max_link_bytes, ns->link_wait);
    } else if (topology(rc)) {
      fputs(net_empty, f);
    }
    fputc('\n', f);
  }
  const mesh *me = stack_mesh(ss);
  stack_totals(ss, &cost, &area, &volume);
  const stack_joins *js = stack_join_counts(ss);
  fprintf(f, "%sjoins,,,,,,%s,%d,%d,%d,,,,,,,%s%s\n", prefix, js->rule, js->apart, js->unjoined, js->dropped,
          rc ? par_empty : "", topology(rc) ? net_empty : "");
  fprintf(f, "%smesh,%.17g,%.17g,,,,%s,%d,%d,%d,%.17g,%.17g", prefix, zmin, zmax,
          manifold ? "closed" : closed ? "pinched" : "open", me->nv, me->nt, bridges, cost, area);
  volume_field(f, closed, volume);
  fprintf(f, ",%llu,%d,%d,%s%s\n", nodes, spans, euler, rc ? par_empty : "", topology(rc) ? net_empty : "");
  for (int i = 0; i < nc; i++) {
    fprintf(f, "%scomponent,%.17g,%.17g,,,,%s,%d,%d,,,%.17g", prefix, c[i].zmin, c[i].zmax,
            c[i].manifold ? "closed" : c[i].closed ? "pinched" : "open", c[i].nv, c[i].nt, c[i].area);
    volume_field(f, c[i].closed, c[i].volume);
    fprintf(f, ",,,%d,", c[i].euler);
    if (c[i].manifold) fprintf(f, "%d", c[i].genus);
    fprintf(f, "%s%s\n", rc ? par_empty : "", topology(rc) ? net_empty : "");
  }
}
