/* report.c -- ./tile's CSV, row by row (report.h). */
#include "surface/report.h"

static const char par_cols[] = ",procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend";
static const char par_empty[] = ",,,,,,,,";

void report_header(FILE *f, const char *prefix, const report_par *par) {
  fprintf(f, "%sband,z0,z1,depth,lower,upper,junction,m,n,bridges,cost,area,volume,nodes,spans,euler,genus%s%s\n",
          prefix, par ? par_cols : "", par ? par->more : "");
}

/* The run's columns of a row without a run: empty. */
static void no_run(FILE *f, const report_par *par) {
  if (!par) return;
  fputs(par_empty, f);
  for (const char *c = par->more; *c; c++)
    if (*c == ',') fputc(',', f);
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

void report_rows(FILE *f, const char *prefix, const stack_surface *ss, const report_par *par) {
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
    if (par && x->pair >= 0) {
      const par_counts *pc = &pp[x->pair].counts;
      unsigned long long bytes = 0;
      for (int k = 0; k < PAR_KINDS; k++) bytes += pc->bytes[k];
      fprintf(f, ",%d,%.9f,%llu,%llu,%llu,%llu,%llu,%s", par->procs, pp[x->pair].time,
              (unsigned long long)pc->msgs[PAR_BOUNDARY], (unsigned long long)pc->msgs[PAR_BACKTRACK],
              (unsigned long long)pc->msgs[PAR_BOUNDS], (unsigned long long)pc->msgs[PAR_CONTROL], bytes,
              par->backend);
      if (par->fields) par->fields(par->ud, f, x->pair);
    } else {
      no_run(f, par);
    }
    fputc('\n', f);
  }
  const mesh *me = stack_mesh(ss);
  stack_totals(ss, &cost, &area, &volume);
  const stack_joins *js = stack_join_counts(ss);
  fprintf(f, "%sjoins,,,,,,%s,%d,%d,%d,,,,,,,", prefix, js->rule, js->apart, js->unjoined, js->dropped);
  no_run(f, par);
  fputc('\n', f);
  fprintf(f, "%smesh,%.17g,%.17g,,,,%s,%d,%d,%d,%.17g,%.17g", prefix, zmin, zmax,
          manifold ? "closed" : closed ? "pinched" : "open", me->nv, me->nt, bridges, cost, area);
  volume_field(f, closed, volume);
  fprintf(f, ",%llu,%d,%d,", nodes, spans, euler);
  no_run(f, par);
  fputc('\n', f);
  for (int i = 0; i < nc; i++) {
    fprintf(f, "%scomponent,%.17g,%.17g,,,,%s,%d,%d,,,%.17g", prefix, c[i].zmin, c[i].zmax,
            c[i].manifold ? "closed" : c[i].closed ? "pinched" : "open", c[i].nv, c[i].nt, c[i].area);
    volume_field(f, c[i].closed, c[i].volume);
    fprintf(f, ",,,%d,", c[i].euler);
    if (c[i].manifold) fprintf(f, "%d", c[i].genus);
    no_run(f, par);
    fputc('\n', f);
  }
}
