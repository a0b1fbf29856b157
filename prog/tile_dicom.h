/* tile_dicom.h -- ./tile on a DICOM RT structure set: --list, --roi, --contours.
 *
 *   tile FILE.dcm [--list]
 *   tile FILE.dcm --roi NAME|NUMBER [--roi ...] [-o OUT.stl] [options as for a stack]
 *   tile FILE.dcm --roi all -o DIR/ [--format stl|obj|ply]
 *   tile FILE.dcm --roi NAME|NUMBER|all --contours OUT.contours|DIR/
 *
 * Each ROI is tiled exactly as its .contours stack would be (input/rtstruct.h);
 * tile.c does the tiling through the callback in tile_dicom_env. */
#ifndef TILE_DICOM_H
#define TILE_DICOM_H

#include <stdio.h>

#include "input/contour.h"
#include "surface/mesh.h"

enum { TILE_DICOM_MAX_ROI = 256 };   /* --roi options, at most */

typedef struct {
  int list;                               /* --list */
  int nroi;                               /* --roi, in order */
  const char *roi[TILE_DICOM_MAX_ROI];
  const char *contours;                   /* --contours FILE or DIR/ */
  const char *format;                     /* --format, for -o DIR/ */
} tile_dicom_opts;

/* Messages about a stack, rewritten before they are printed (for an ROI:
 * to name the DICOM file, byte, ROI and contour item); malloc'd. */
typedef struct {
  char *(*rewrite)(void *ud, const char *msg);
  void *ud;
} tile_dicom_map;

typedef struct {
  /* Tile s (named `name` in messages: the file and ROI; its lines are those
   * of the ROI's stack as --contours writes it; each refusal and note passes
   * through map when map is not NULL): the report on stdout (its header
   * first when header != 0; the header's lines prefixed by hprefix, the
   * others by prefix) and the mesh in *me (the caller frees it).  0, or -1
   * when the run failed (said on stderr). */
  int (*tile)(void *ud, const contour_stack *s, const char *name, const tile_dicom_map *map,
              const char *hprefix, const char *prefix, int header, mesh *me);
  void *ud;
  /* Bad usage: print "tile: " fmt(arg), the usage line; returns 2. */
  int (*usage)(const char *fmt, const char *arg);
  const char *out;     /* -o, or NULL */
  int quiet;           /* -q */
  int trace;           /* --trace given: one ROI only */
  int pairs;           /* check stacks with contour_stack_pairs, as tile.c does */
  int no_keyholes;     /* --no-keyholes: refuse keyhole contours (contour.h) */
  double thickness;    /* --thickness: an ROI of one slice is tiled as a slab; 0 refuses it */
  int read_flags;      /* CONTOUR_SKIP_BAD, CONTOUR_UNION, CONTOUR_VERBOSE: as for a stack */
} tile_dicom_env;

/* A refusal may name every bad contour (contour.h): this much room. */
enum { TILE_ERR_MAX = 1 << 16 };

/* Each line of text on f as "tile: LINE". */
void tile_say_lines(FILE *f, const char *text);

/* 1 if path names a directory for -o/--contours: ends in '/' or is one. */
int tile_dicom_is_dir(const char *path);

/* The DICOM options: returns how many arguments it took (1 or 2), 0 if a
 * is not one of them, -1 if its value is missing or bad (message in err). */
int tile_dicom_option(tile_dicom_opts *o, const char *a, const char *v, char *err, size_t errlen);
int tile_dicom_given(const tile_dicom_opts *o);   /* any of them given */

/* The exit status of --roi all when some ROIs were refused and the others
 * tiled (and written). */
enum { TILE_DICOM_SOME_REFUSED = 3 };

/* ./tile on the DICOM file `in`: returns the exit status (0, 1 bad input or
 * nothing tiled, 2 bad usage, TILE_DICOM_SOME_REFUSED). */
int tile_dicom_main(const tile_dicom_opts *o, const char *in, const tile_dicom_env *env);

#endif
