/* contour.h -- contour stacks: the builder that checks and repairs them,
 * whoever reads them, and the .contours files.
 *
 * Format (doc/tilesim-contours.5): a line "C <n> <z>" opens a contour of n
 * points in the plane z; the next n lines are its points "x y".  Lines
 * starting with '#' are comments; blank lines are skipped.  The closing point
 * is not repeated.
 *
 * Slices.  Contours whose z agree to within a tenth of the slice spacing form
 * one slice, whatever their order in the file (contour_parse groups them and
 * snaps their z to one value); a slice may hold any number of contours.
 * ./tile makes one surface of the whole stack (surface/stack.h); the programs
 * that tile each contour with the next in file order (bench --input, bench
 * --tiler, plot surface) ask contour_stack_pairs for one contour per slice. */
#ifndef CONTOUR_H
#define CONTOUR_H

#include <stddef.h>
#include <stdio.h>

#include "geom/geom.h"
#include "util/strbuf.h"

typedef struct {
  double z;       /* the contour's plane */
  int n;          /* points, after repair (>= 3, not all collinear) */
  vec2 *pt;       /* counter-clockwise seen from +z; closing point not repeated */
  int line;       /* its place: the line of its "C" header in the file (a
                     keyhole's loop: of its first point; an ROI's contour:
                     the line its .contours text gives it) */
  int slice;      /* its slice, 0 .. nslices-1 in increasing z */
  int cw;         /* 1 if the file gave it clockwise (it was reversed) */
} contour;

typedef struct {
  int n;          /* contours, in file order (>= 2; >= 1 with CONTOUR_ONE_SLICE) */
  contour *c;
  int nslices;    /* slices (>= 2; >= 1 with CONTOUR_ONE_SLICE); contours of one slice
                     share their z exactly */
} contour_stack;

enum { CONTOUR_MAX_LINE = 4096 };        /* longer lines are rejected */
enum { CONTOUR_MAX_POINTS = 10000000 };  /* per contour */

/* Read the stack in `path` ("-" is standard input).  Repairs (a repeated
 * closing point, consecutive duplicate points, keyholes and spurs (below),
 * clockwise contours when every slice has one contour, z values snapped to
 * their slice) are reported as lines "PREFIX: FILE:LINE: ..." on `notes`
 * (NULL: silent), only when the stack is accepted; repairs of one kind in
 * one contour are counted on one line ("dropped 212 duplicates of the point
 * before (the first at line L: X Y)"), each on its own with CONTOUR_VERBOSE.
 * Returns 0, or -1 with "FILE:LINE: what is wrong (value)" in err; nothing
 * is allocated on failure.  The caller frees with contour_stack_free.
 *
 * Bad contours.  A contour that cannot be tiled -- fewer than 3 distinct
 * points, all collinear, crossing or touching itself and no keyhole -- does
 * not stop the reading: every one is found.  Refused, err holds one line per
 * bad contour ("FILE:LINE: why", in file order; as many as errlen holds)
 * and then one summary line ("FILE: 8 of 26 contours cannot be tiled (P of
 * Q points), each named above; --skip-bad drops them and tiles the rest");
 * a single bad contour is one line.  With CONTOUR_SKIP_BAD each is dropped
 * with a note naming it and why, one note counts them, and the rest are read
 * as the stack.  Errors in the file's text (a garbled line, a number that is
 * not one) still end the reading at once, in one line. */
int contour_read(const char *path, contour_stack *out, FILE *notes,
                 const char *prefix, char *err, size_t errlen);

/* The same from memory: `name` is used in messages. */
int contour_parse(const char *text, size_t len, const char *name,
                  contour_stack *out, FILE *notes, const char *prefix,
                  char *err, size_t errlen);

/* Keyholes and spurs.  A contour that crosses, touches or runs back over
 * itself is bad ("the contour crosses itself: the segment from line A to
 * line B crosses|touches|overlaps the segment from line C to line D (X Y)")
 * unless it is a keyhole contour or has zero-width spurs (geom/keyhole.h:
 * loops joined by channels walked out and back, spikes walked out and back
 * along themselves, exactly): then it becomes its loops, each a contour of
 * the slice whose `line` is the line of its first point in the file, and a
 * note "keyhole: the contour split into K loops at (X Y), a channel of
 * length L dropped" or "dropped a zero-width spur ... of length L at (X Y)"
 * names its header line.  The *_flags readers take:
 *   CONTOUR_NO_KEYHOLES  such contours are bad too (not repaired);
 *   CONTOUR_SKIP_BAD     bad contours are dropped, with notes (above);
 *   CONTOUR_VERBOSE      every repair on a note of its own (above);
 *   CONTOUR_UNION        the notes on overlapping contours of a slice, which
 *                        are always merged into their union
 *                        (input/slicemerge.h), are --union's: without it
 *                        one note a slice whose pieces were merged;
 *   CONTOUR_DROP_DEGENERATE  a contour of fewer than 3 distinct points or
 *                        all collinear (no area: Pinnacle writes single
 *                        points and two-point contours among real ones) is
 *                        dropped, not bad: one note counts them ("dropped N
 *                        degenerate contours of M ..."), each with
 *                        CONTOUR_VERBOSE, its own repair notes dropped with it;
 *   CONTOUR_ONE_SLICE    a stack of one slice (one contour or more) is
 *                        accepted: for ./tile, which makes it a slab of a
 *                        given thickness (surface/stack.h) or refuses it
 *                        itself, naming the option; without it it is refused;
 *   CONTOUR_PAIRS        the stack is checked by contour_stack_pairs too,
 *                        before any note is said.
 * The others take none. */
enum {
  CONTOUR_NO_KEYHOLES = 1,
  CONTOUR_SKIP_BAD = 2,
  CONTOUR_VERBOSE = 4,
  CONTOUR_UNION = 8,
  CONTOUR_ONE_SLICE = 16,
  CONTOUR_DROP_DEGENERATE = 32,
  CONTOUR_PAIRS = 64
};
int contour_read_flags(const char *path, int flags, contour_stack *out, FILE *notes,
                       const char *prefix, char *err, size_t errlen);
int contour_parse_flags(const char *text, size_t len, const char *name, int flags,
                        contour_stack *out, FILE *notes, const char *prefix,
                        char *err, size_t errlen);

/* Places in messages.  Every message about a stack names its contours and
 * points by the `line` the reader gave each; a stack's places say how a line
 * is written: for a .contours file "NAME:LINE" at the head of a message and
 * "line N" within it (contour_places_file); the DICOM reader names the
 * file, the byte, the ROI and the contour item instead (input/rtstruct.h). */
typedef struct {
  /* The head of a message about `line` (0: about the stack as a whole);
   * the message goes on with ": what". */
  void (*head)(void *ud, strbuf *b, int line);
  /* `line` named within a message whose head is about line `head` (at most
   * CONTOUR_PLACE_MAX - 1 bytes). */
  void (*ref)(void *ud, char *buf, size_t cap, int line, int head);
  void *ud;
} contour_places;

enum { CONTOUR_PLACE_MAX = 64 };

/* The places of the file `name` (kept, not copied). */
contour_places contour_places_file(const char *name);

/* `line` as pl names it in a message about `head`: in p, returned. */
typedef struct {
  char s[CONTOUR_PLACE_MAX];
} contour_place;
const char *contour_place_at(const contour_places *pl, int line, int head, contour_place *p);

/* The builder the readers fill: a contour at a time, its points in order,
 * each with its place; the repairs, checks, slices and notes are those of
 * contour_read above, whoever reads.  contour_build_open takes the flags of
 * contour_read_flags; pl is kept, not copied; prefix NULL is "tilesim". */
typedef struct contour_build contour_build;
contour_build *contour_build_open(const contour_places *pl, int flags, const char *prefix);
/* A contour in the plane z, named by `line`; then its points, then its end
 * (repaired and checked there: a bad contour is kept to be named at the
 * close, as contour_read says).  At most CONTOUR_MAX_POINTS points. */
void contour_build_begin(contour_build *b, double z, int line);
void contour_build_point(contour_build *b, vec2 p, int line);
void contour_build_end(contour_build *b);
/* The stack: 0, with the notes said on `notes` (NULL: silent); or -1 with
 * the refusal in err, as contour_read says.  Frees b. */
int contour_build_close(contour_build *b, contour_stack *out, FILE *notes, char *err, size_t errlen);
/* Frees b, with what it holds (a reader that failed on its own). */
void contour_build_free(contour_build *b);

/* Write a stack in the same format (%.17g: reading it back is exact).
 * Returns 0 or -1 on a write error. */
int contour_write(FILE *f, const contour_stack *s);

/* For the programs that tile each contour with the next in file order: 0
 * if every slice has one contour and z runs monotone through the file; else
 * -1 and "NAME:LINE: what (value)" in err. */
int contour_stack_pairs(const contour_stack *s, const char *name, char *err, size_t errlen);
/* The same, naming places by pl. */
int contour_stack_pairs_at(const contour_stack *s, const contour_places *pl, char *err, size_t errlen);

void contour_stack_free(contour_stack *s);

#endif
