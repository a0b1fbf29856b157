/* rtstruct.h -- DICOM RT structure sets: the ROIs and their contour stacks.
 *
 * Reads an RTSTRUCT (dicom.h) into its ROIs: StructureSetROISequence
 * (3006,0020) gives each ROI's number and name, ROIContourSequence (3006,0039)
 * its contours (ContourSequence (3006,0040): ContourGeometricType,
 * NumberOfContourPoints, ContourData as decimal strings), and
 * RTROIObservationsSequence (3006,0080) its interpreted type.  Coordinates are
 * the file's: patient LPS, millimetres.
 *
 * Only CLOSED_PLANAR contours are tiled; POINT, OPEN_PLANAR, OPEN_NONPLANAR
 * and unknown types are counted and skipped.  An ROI's closed contours must
 * lie in parallel planes: axial (z constant in each contour) is used as it is;
 * sagittal (x constant) and coronal (y constant) are turned into z by a cyclic
 * permutation of the axes (exact, and a rotation, so windings keep their
 * meaning), and turned back with rtstruct_to_patient.  Oblique: contours in
 * parallel planes of any other common normal (an export in a tilted frame)
 * are turned into z by the same permutation (the axis nearest the normal
 * into z) and then the smallest rotation that takes z to the normal, and
 * back; the normal is the least-squares fit of all the ROI's points to
 * parallel planes, one per contour, computed in an order that does not
 * depend on the file's (rtstruct_frame below).  Contours more than 0.001 mm
 * off a plane of that normal -- not planar, or planar but not parallel to the
 * others -- are refused, naming the contour.
 *
 * An ROI's stack: its closed contours sorted by their plane (stably), in
 * the stack's frame, given to the contour builder (input/contour.h) that
 * the .contours reader fills too, so a DICOM ROI and its converted stack
 * (rtstruct_roi_text: the numbers as the file wrote them, oblique ones
 * computed, %.17g, the same doubles) give the same tiling, mesh and report.
 * Each contour and point is named by the line that text gives it; the
 * builder's places name the DICOM file, the byte, the ROI and the contour
 * item instead. */
#ifndef RTSTRUCT_H
#define RTSTRUCT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "input/contour.h"

typedef enum { RTSTRUCT_AXIAL, RTSTRUCT_SAGITTAL, RTSTRUCT_CORONAL, RTSTRUCT_OBLIQUE } rtstruct_plane;

/* An ROI's stack frame: a point p of the patient is (u.p, v.p, n.p) in the
 * stack, and a stack point (x, y, h) is x u + y v + h n; u, v, n are
 * orthonormal (to rounding), right-handed.  Exact permutations for the three
 * standard planes. */
typedef struct {
  double u[3], v[3], n[3];
  double angle;      /* oblique: degrees between n and the nearest axis */
} rtstruct_frame;

typedef struct {
  int item;          /* 1-based item of the ROI's ContourSequence */
  size_t offset;     /* byte offset of its ContourData element */
  int n;             /* points */
  double *p;         /* 3n: x y z, as in the file */
  size_t *poff;      /* n: byte offset of each point's first value */
  char *txt;         /* the 3n values as written (blanks trimmed), one after another */
  uint32_t *tok;     /* 3n + 1: where each value starts in txt (the next, where it ends) */
  double h;          /* its plane's height along the ROI's normal (oblique:
                        the lower median of its points' heights) */
} rtstruct_contour;

typedef struct {
  int number;        /* ROINumber */
  char *name;        /* ROIName as written, trailing spaces removed ("" if none) */
  char *type;        /* RTROIInterpretedType ("" if none) */
  size_t offset;     /* byte offset of its StructureSetROISequence item */
  int nc;            /* closed planar contours, sorted by height (stably) */
  rtstruct_contour *c;
  int skipped;       /* contours of other types */
  int slices;        /* distinct heights among the closed contours */
  long points;       /* points of the closed contours */
  double hmin, hmax; /* their heights (0 if none) */
  rtstruct_plane plane;
  rtstruct_frame frame;
  double flat;       /* how far apart along the normal points of one plane may lie (mm):
                        from the precision the file writes (input/rtframe.h) */
  char *error;       /* NULL, or why its contours cannot be used (one line) */
  char *warnings;    /* lines to show when the ROI is used, or NULL */
} rtstruct_roi;

typedef struct {
  char *name;        /* the file, for messages */
  int nroi;          /* in StructureSetROISequence order */
  rtstruct_roi *roi;
  char *warnings;    /* lines about the whole file (unknown ROI references), or NULL */
} rtstruct;

/* Parse an RT structure set from memory (`name` is used in messages).
 * Problems of the file refuse it: returns -1 with one line "NAME: byte N:
 * what (value)" in err, nothing allocated.  Problems of one ROI's contours
 * (bad numbers, counts that disagree, contours not in parallel planes) are
 * kept in that ROI's `error`.  Returns 0; free with rtstruct_free. */
int rtstruct_parse(const unsigned char *buf, size_t len, const char *name, rtstruct *out,
                   char *err, size_t errlen);
/* The same from a file ("-" is standard input); "cannot open/read" errors too. */
int rtstruct_read(const char *path, rtstruct *out, char *err, size_t errlen);
void rtstruct_free(rtstruct *s);

/* The ROI whose name is key, or else whose number is key: its index, or -1
 * with a message (unknown, or a name two ROIs share). */
int rtstruct_find(const rtstruct *s, const char *key, char *err, size_t errlen);

/* 0 if the ROI has closed planar contours and no error; else -1 with its
 * error, or why it has nothing to tile, in err. */
int rtstruct_roi_check(const rtstruct *s, int roi, char *err, size_t errlen);

/* The ROI as .contours text (a comment header, then the contours): malloc'd,
 * the caller frees.  The ROI must have no error. */
char *rtstruct_roi_text(const rtstruct *s, int roi, size_t *len);

/* The ROI's stack, made by the contour builder as contour_read_flags makes
 * a file's, with its flags (keyhole contours split into their loops unless
 * CONTOUR_NO_KEYHOLES; bad contours dropped with CONTOUR_SKIP_BAD,
 * overlapping contours of a slice merged (noted as --union's with
 * CONTOUR_UNION), every note in full with CONTOUR_VERBOSE; and, with
 * CONTOUR_PAIRS, checked by contour_stack_pairs, as ./tile checks a stack
 * that it tiles contour by contour; CONTOUR_ONE_SLICE accepts an ROI of one
 * slice, CONTOUR_DROP_DEGENERATE drops contours without area with a
 * counted note): 0, or -1 with the refusal naming the file, ROI, contour
 * item and byte (one line per bad contour, as contour.h says, as many whole
 * lines as errlen holds, the last line kept).  Notes go to `notes` as
 * contour_read's do, named alike ("contour item K, point J" for a line),
 * and only when the stack is accepted. */
int rtstruct_roi_stack(const rtstruct *s, int roi, int flags, contour_stack *out, FILE *notes,
                       const char *prefix, char *err, size_t errlen);

/* A message about the ROI's stack (from surface/, which names it `name`
 * and its contours by their lines: "NAME:LINE: ..." and "line N" within),
 * rewritten to name places as rtstruct_roi_stack's messages do: the file,
 * the byte, the ROI, the contour item and point.  Several lines are
 * rewritten each.  malloc'd; the caller frees. */
char *rtstruct_rewrite(const rtstruct *s, int roi, const char *name, const char *msg);

/* A point of the ROI's stack frame (x, y, z = height) back to patient x,
 * y, z: exact for the three standard planes, to rounding when oblique. */
void rtstruct_to_patient(const rtstruct_roi *roi, double *x, double *y, double *z);

/* "axial", "sagittal", "coronal" or "oblique". */
const char *rtstruct_plane_name(rtstruct_plane plane);

/* Contour k's height as the file wrote it (oblique: %.17g of h; at most cap
 * - 1 bytes). */
void rtstruct_height_text(const rtstruct_roi *roi, int k, char *buf, size_t cap);

#endif
