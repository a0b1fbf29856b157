/* rtwriter.h -- a small DICOM RTSTRUCT writer for the tests: the reader's
 * independent counterpart (its own byte layout, written from PS3.5 and PS3.10,
 * sharing no code with input/dicom.c).
 *
 * Implicit or explicit VR little endian; sequences and items of defined or
 * undefined length; with the 128-byte preamble and meta group, with the meta
 * group alone, or the bare data set; optionally extra elements a reader must
 * skip (private tags, UN of undefined length holding an implicit VR sequence,
 * a nested ReferencedFrameOfReferenceSequence, odd lengths, long text). */
#ifndef RTWRITER_H
#define RTWRITER_H

#include <stddef.h>

typedef struct {
  int explicit_vr;     /* else implicit VR */
  int undefined;       /* sequences and items of undefined length */
  int layout;          /* 0: preamble + meta; 1: meta without preamble; 2: bare data set */
  int extras;          /* elements to skip, see above */
  const char *ts;      /* transfer syntax UID written in the meta group (NULL: the one used) */
  const char *modality;/* NULL: RTSTRUCT */
  int deep;            /* > 0: an unknown sequence nested this deep (undefined lengths) */
} rtw_opts;

typedef struct {
  const char *geom;    /* ContourGeometricType; NULL: CLOSED_PLANAR */
  int n;               /* points */
  const double *xyz;   /* 3n */
  const char *data;    /* ContourData text instead of xyz (NULL: xyz as %.17g) */
  int npoints;         /* NumberOfContourPoints written: -1 for n, -2 to leave it out */
} rtw_contour;

typedef struct {
  int number;
  const char *name;
  const char *type;    /* RTROIInterpretedType, NULL: none */
  int nc;
  const rtw_contour *c;
  int ref;             /* ReferencedROINumber of its ROIContourSequence item (0: number) */
  int no_contours;     /* an ROIContourSequence item without ContourSequence */
} rtw_roi;

/* The file's bytes (malloc'd, *len set). */
unsigned char *rtw_write(const rtw_opts *o, const rtw_roi *roi, int nroi, size_t *len);

/* The len bytes of b written to the file dir/name (a test's fixture): 0, or
 * 1 after a line on stderr naming the file. */
int rtw_save(const char *dir, const char *name, const unsigned char *b, size_t len);

#endif
