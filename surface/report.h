/* report.h -- the CSV report of a tiled stack (./tile's standard output).
 *
 *   band,z0,z1,depth,lower,upper,junction,m,n,bridges,cost,area,volume,nodes,spans,euler,genus
 *   [,procs,sim_time,msg_boundary,msg_backtrack,msg_bounds,msg_control,bytes,backend]
 *
 * One row per band (band = 0, 1, ...): the slices' z, the contours' depth,
 * which contours of the lower and upper slice (their places in canonical
 * order, joined by '+'), the junction type (contours below - above), the
 * points of the two contours (m below, n above, bridge vertices included:
 * the band has m + n tiles; a 1-1 band's tiler sees their corners only,
 * surface/follow.h), bridges, the optimum, the band's area and slab volume,
 * the tiler's node evaluations, the spans its optimum used twice (a pinched
 * band, surface/unpinch.h: the band is then the cheapest path without, and
 * cost its cost); with --procs the parallel run's columns, and after them
 * the caller's (report_par: the network's on a topology).
 * Then with caps one row per cap (band = cap; z1 the apex's z; volume what
 * the cap adds beyond its flat region), one row `joins` (junction: the
 * joining rule; m: joins made without overlap; n: contour ends left without
 * a partner though the neighbouring slice has candidates; bridges: joins
 * dropped for want of a bridge; stack_joins), one row `mesh` (zmin, zmax,
 * closed|open, vertices, triangles, bridges, cost, area, volume, nodes and
 * the Euler characteristic), and one row `component` per connected
 * component (closed|pinched|open, vertices, triangles, area, volume, Euler
 * characteristic, genus when closed).  Volumes are given only where the
 * surface encloses one: on every row when the mesh is closed (then the
 * bands' and caps' volumes sum to the mesh's), on a closed component's row;
 * an open mesh's (--no-caps) volume fields are empty. */
#ifndef REPORT_H
#define REPORT_H

#include <stdio.h>

#include "surface/stack.h"

/* The columns of a run by a tiler (stack_tiler: ./tile --procs). */
typedef struct {
  int procs;            /* the procs column */
  const char *backend;  /* the backend column: "sim", "threads" or "mpi" */
  const char *more;     /* the names of further columns, each after a comma
                           (",hops_per_msg,..."), or "" */
  void (*fields)(void *ud, FILE *f, int pair);   /* a band's further fields,
                           each after a comma, for its run `pair`
                           (stack_row.pair); other rows get them empty */
  void *ud;
} report_par;

/* The header line, after `prefix` (for columns a caller puts first); par as
 * for report_rows. */
void report_header(FILE *f, const char *prefix, const report_par *par);

/* Every row, each after `prefix`; par: the run's columns (NULL: none,
 * without --procs). */
void report_rows(FILE *f, const char *prefix, const stack_surface *ss, const report_par *par);

#endif
