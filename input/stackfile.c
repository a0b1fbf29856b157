/* stackfile.c -- a contour stack from a .contours file or a DICOM ROI
 * (stackfile.h). */
#include "input/stackfile.h"

#include <stdlib.h>
#include <string.h>

#include "input/dicom.h"
#include "input/rtstruct.h"
#include "util/strbuf.h"
#include "util/xmem.h"

struct stackfile {
  contour_stack s;
  rtstruct rs;       /* the structure set, when an ROI was read */
  int roi;           /* its index, or -1 for a .contours file */
  char *name, *title;
};

int stackfile_is_dicom(const char *path) { return dicom_sniff_file(path); }

int stackfile_open(const char *path, const char *roi, int flags, FILE *notes, const char *prefix, stackfile **out,
                   char *err, size_t errlen) {
  stackfile *f = xcalloc(1, sizeof *f);
  strbuf name = {0}, title = {0};
  *out = NULL;
  f->roi = -1;
  if (!roi) {
    if (contour_read_flags(path, flags, &f->s, notes, prefix, err, errlen) != 0) {
      free(f);
      return -1;
    }
    f->name = xstrdup(strcmp(path, "-") == 0 ? "<stdin>" : path);
    f->title = xstrdup(f->name);
    *out = f;
    return 0;
  }
  if (rtstruct_read(path, &f->rs, err, errlen) != 0) {
    free(f);
    return -1;
  }
  int k = rtstruct_find(&f->rs, roi, err, errlen);
  if (k < 0 || rtstruct_roi_stack(&f->rs, k, flags, &f->s, notes, prefix, err, errlen) != 0) {
    rtstruct_free(&f->rs);
    free(f);
    return -1;
  }
  const rtstruct_roi *r = &f->rs.roi[k];
  f->roi = k;
  strbuf_add(&title, "%s: ROI %d '%s'", f->rs.name, r->number, r->name);
  strbuf_add(&name, "%s as a stack", title.buf);
  f->name = name.buf, f->title = title.buf;
  *out = f;
  return 0;
}

contour_stack *stackfile_stack(stackfile *f) { return &f->s; }

const char *stackfile_name(const stackfile *f) { return f->name; }

const char *stackfile_title(const stackfile *f) { return f->title; }

char *stackfile_say(const stackfile *f, const char *msg) {
  return f->roi >= 0 ? rtstruct_rewrite(&f->rs, f->roi, f->name, msg) : xstrdup(msg);
}

void stackfile_close(stackfile *f) {
  if (!f) return;
  contour_stack_free(&f->s);
  if (f->roi >= 0) rtstruct_free(&f->rs);
  free(f->name);
  free(f->title);
  free(f);
}
