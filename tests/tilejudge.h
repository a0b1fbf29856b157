/* tilejudge.h -- ./tile's output judged by the tests' independent mesh
 * checker (meshcheck.h): the mesh against the stack it was tiled from and
 * the solid it samples (solids.h), and the CSV report against the mesh.
 * Each finding is a check (check.h) named by the caller's name. */
#ifndef TILEJUDGE_H
#define TILEJUDGE_H

#include "tests/meshcheck.h"
#include "tests/solids.h"

/* Check the mesh in path against the stack and the solid s (s < 0: topology
 * and fidelity only); exact != 0: its coordinates must be the input's. */
void tilejudge_mesh(const char *name, const char *path, const sl_stack *st, int s, int exact, mc_report *r,
                    mc_fidelity *f);

/* The report (doc/tile.1, OUTPUT: a row per band, then with --caps a row
 * `cap` per cap, a row `mesh` and a row `component` per component) against
 * the mesh as the checker sees it: the bands' and caps' volumes sum to the
 * `mesh` row's volume, which is the mesh's own; the bands between two
 * planes, and the caps whose apex lies between them, sum to the mesh's slab
 * there (caps beyond the end planes: to the mesh beyond them); a flat cap
 * adds nothing; the `mesh` and `component` rows give the checker's
 * components, Euler characteristics and volumes. */
void tilejudge_report(const char *name, const char *csv, const mc_report *r, const mc_fidelity *f);

#endif
