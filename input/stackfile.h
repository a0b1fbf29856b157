/* stackfile.h -- a contour stack from a file: a .contours file, or one ROI
 * of a DICOM RT structure set; and how messages about it name its places.
 *
 * What ./tile, plot surface and bench --stack read as "a stack".  An ROI's
 * stack is made as rtstruct_roi_stack makes it (input/rtstruct.h), a file's
 * as contour_read_flags reads it (input/contour.h), with the same flags. */
#ifndef STACKFILE_H
#define STACKFILE_H

#include <stddef.h>
#include <stdio.h>

#include "input/contour.h"

typedef struct stackfile stackfile;

/* The stack of the .contours file `path` ("-": standard input) when roi is
 * NULL, else of the ROI named or numbered `roi` in the RT structure set
 * `path`.  flags: contour_read_flags's (CONTOUR_PAIRS too).  Notes on
 * `notes` (NULL: silent) only when the stack is accepted.  0 and *out (free
 * with stackfile_close), or -1 with the refusal in err (one line, or one a
 * bad contour and a summary, as contour.h says) and *out NULL. */
int stackfile_open(const char *path, const char *roi, int flags, FILE *notes, const char *prefix, stackfile **out,
                   char *err, size_t errlen);

/* Is path a DICOM file (by its content)?  Then it wants an ROI. */
int stackfile_is_dicom(const char *path);

/* The stack (the handle's: stackfile_close frees it). */
contour_stack *stackfile_stack(stackfile *f);

/* What messages about the stack call it: the file ("<stdin>" for "-"),
 * or "FILE: ROI N 'NAME' as a stack". */
const char *stackfile_name(const stackfile *f);

/* The stack's title: the file, or "FILE: ROI N 'NAME'". */
const char *stackfile_title(const stackfile *f);

/* A message about the stack that names it stackfile_name and its places
 * by their lines ("NAME:LINE: ...", "line N": surface/'s), as the reader
 * names places: as it is for a file, rewritten for an ROI (the DICOM file,
 * the byte, the ROI, the contour item; rtstruct_rewrite).  malloc'd. */
char *stackfile_say(const stackfile *f, const char *msg);

void stackfile_close(stackfile *f);

#endif
