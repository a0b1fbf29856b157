/* meshcheck.h -- an independent mesh checker for the tests: its own OBJ, PLY
 * and STL readers, and the invariants of a closed, outward 2-manifold that
 * passes exactly through its input contours.  It shares no code with
 * surface/ (the mesh under test). */
#ifndef MESHCHECK_H
#define MESHCHECK_H

#include <stddef.h>

typedef struct {
  int nv, nt;
  double *v;            /* 3 nv coordinates */
  int *t;               /* 3 nt vertex indices, 0-based */
} mc_mesh;

/* Read OBJ (v, f; f a/b/c forms and negative indices; triangles only), PLY
 * (ASCII 1.0; x, y, z among the vertex properties; a face list) or STL
 * (binary, or ASCII; float vertices welded where their coordinates are
 * equal), by the file's extension.  0, or -1 with "PATH:LINE: why" in err. */
int mc_read(const char *path, mc_mesh *m, char *err, size_t errlen);

/* A mesh from arrays (copied), for hand-made meshes. */
void mc_make(mc_mesh *m, const double *v, int nv, const int *t, int nt);
void mc_free(mc_mesh *m);

typedef struct {
  int boundary;         /* directed edges whose reverse is not in the mesh */
  int overused;         /* directed edges used by more than one triangle */
  int pinched;          /* vertices whose triangles do not form one closed fan */
  int degenerate;       /* triangles with a repeated vertex or (nearly) zero area */
  int duplicate;        /* triangles with the same three vertices as another */
  int unused;           /* vertices in no triangle */
  int samepoint;        /* vertices at exactly the coordinates of another */
  int edges;            /* undirected edges */
  int manifold;         /* all the counts above are 0: a closed, consistently
                           oriented 2-manifold without degenerate triangles */
  int ncomp;            /* connected components (through shared vertices) */
  int *chi;             /* ncomp Euler characteristics V - E + F */
  double *cvol;         /* ncomp signed volumes */
  int *wind;            /* ncomp: the winding number of the other components
                           around a vertex of this one (1 inside a solid) */
  int outward;          /* every component faces out of the solid: volume > 0
                           with wind 0 (an outer shell) or volume < 0 with
                           wind 1 (a cavity's surface), no winding ambiguous */
  double volume, area;  /* signed volume (divergence theorem), total area */
  char first[256];      /* the first problem found, "" if none */
} mc_report;

/* Check m.  Free the report with mc_report_free.  Scale-free: the geometry
 * is judged on m scaled by the power of two that brings its largest
 * coordinate into [1/2, 1), so a mesh scaled by 2^k gets the same verdicts,
 * its area and volumes exactly 2^2k and 2^3k times as large (inf or 0 beyond
 * a double); mc_check_input's slab volumes likewise. */
void mc_check(const mc_mesh *m, mc_report *r);
void mc_report_free(mc_report *r);

/* A planar input contour: n points (x[i], y[i]) in the plane z. */
typedef struct { int n; double z; const double *x, *y; } mc_poly;

typedef struct {
  int segments, missing;   /* input segments, and those that are not a mesh edge */
  int channel;             /* segments whose reverse is a segment of their contour
                              too (a keyhole's channel walked out and back): not
                              required to be edges, not in missing */
  int points, absent;      /* input points, and those that are not a mesh vertex
                              (coordinates compared exactly, bit for bit) */
  int strays;              /* mesh vertices on an input plane that are not input points */
  int crossing;            /* triangles that cross an input plane */
  int nplanes;
  double *planes;          /* the input planes, increasing */
  double *slab;            /* nplanes - 1: the volume of the mesh between planes k
                              and k+1, closed by its sections there */
  double outside;          /* the volume beyond the first and last planes (apex caps) */
} mc_fidelity;

/* How exactly m passes through the contours c[0..nc): every segment an edge,
 * every point a vertex, no other vertex on a plane, no triangle across a
 * plane; and its volume slab by slab (the flux of (x, y, 0) / 2, to which
 * horizontal faces add nothing, so the slabs sum to the mesh's volume
 * exactly when it is closed).  Free with mc_fidelity_free. */
void mc_check_input(const mc_mesh *m, const mc_poly *c, int nc, mc_fidelity *f);
void mc_fidelity_free(mc_fidelity *f);

#endif
