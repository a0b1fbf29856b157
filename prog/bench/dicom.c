/* dicom.c -- ./bench --dicom: how fast a DICOM RT structure set is
 * read, and its ROIs made into stacks.
 *
 *   bench --dicom [FILE...] [--repeat R]
 *
 * One CSV row per file (default tests/data/rtstruct/dicompyler_rtss.dcm, 1.9
 * MB, 10 ROIs).  The file is read into memory once; read_ms is the best of R
 * runs of rtstruct_parse on it (the DICOM tree, every ROI's contours parsed
 * from their decimal strings, planes, sorting), stacks_ms the best of R runs
 * of rtstruct_roi_stack on every ROI that has contours (the contour
 * builder: repairs, checks, slices).  checksum is the sum of every coordinate read: it
 * shows a fast wrong answer. */
#include "prog/bench/bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/args.h"
#include "prog/bench/data.h"
#include "util/progname.h"
#include "util/readfile.h"
#include "input/rtstruct.h"
#include "util/wallclock.h"
#include "util/xmem.h"

static int one(const char *path, int repeat) {
  size_t len;
  char err[1024];
  unsigned char *buf = (unsigned char *)readfile(path, &len, err, sizeof err);
  if (!buf) {
    progname_eprintf("bench: %s\n", err);
    return 1;
  }
  double best = 1e300, best_stacks = 1e300, sum = 0;
  int rois = 0, contours = 0, stacks = 0;
  long points = 0;
  for (int r = 0; r < repeat; r++) {
    rtstruct s;
    double t0 = wallclock();
    if (rtstruct_parse(buf, len, path, &s, err, sizeof err) != 0) {
      progname_eprintf("bench: %s\n", err);
      free(buf);
      return 1;
    }
    double t1 = wallclock();
    if (t1 - t0 < best) best = t1 - t0;
    stacks = 0;
    for (int i = 0; i < s.nroi; i++) {
      contour_stack st;
      if (rtstruct_roi_stack(&s, i, 0, &st, NULL, progname_as("bench"), err, sizeof err) == 0) {
        stacks++;
        contour_stack_free(&st);
      }
    }
    double t2 = wallclock();
    if (t2 - t1 < best_stacks) best_stacks = t2 - t1;
    if (r == 0) {
      rois = s.nroi;
      for (int i = 0; i < s.nroi; i++) {
        const rtstruct_roi *roi = &s.roi[i];
        contours += roi->nc;
        points += roi->points;
        for (int k = 0; !roi->error && k < roi->nc; k++)
          for (int j = 0; j < 3 * roi->c[k].n; j++) sum += roi->c[k].p[j];
      }
    }
    rtstruct_free(&s);
  }
  printf("%s,%zu,%d,%d,%ld,%d,%d,%.3f,%.1f,%.3f,%.17g\n", path, len, rois, contours, points, stacks,
         repeat, best * 1e3, len / best / 1e6, best_stacks * 1e3, sum);
  free(buf);
  return 0;
}

static const char dicom_usage[] = "usage: bench --dicom [FILE...] [--repeat R]   (bench --help: every mode)\n";

int bench_dicom(int argc, char **argv) {
  int repeat = 20, nfiles = 0;
  const char **files = xcalloc((size_t)argc + 1, sizeof *files);
  char err[300], shown[200];
  for (int i = 2; i < argc; i++) {
    const char *why = NULL;
    if (strcmp(argv[i], "--repeat") == 0) {
      long v;
      if (i + 1 >= argc) why = "an option needs a value (--repeat)";
      else if (args_long(argv[i], argv[i + 1], 1, 100000, &v, err, sizeof err) != 0) why = err;
      else repeat = (int)v, i++;
    } else if (argv[i][0] == '-' || !argv[i][0]) {
      args_show(argv[i], shown, sizeof shown);
      snprintf(err, sizeof err, "%s (%s)", argv[i][0] ? "unknown option" : "a file name is not empty", shown);
      why = err;
    } else {
      files[nfiles++] = argv[i];
    }
    if (why) {
      progname_eprintf("bench: %s\n%s", why, dicom_usage);
      free(files);
      return 2;
    }
  }
  static char found[3000];
  if (nfiles == 0) {   /* installed, or the source tree */
    if (bench_data_find("tests/data/rtstruct/dicompyler_rtss.dcm", NULL, found, sizeof found) != 0) {
      progname_eprintf("bench: %s\n", found);
      free(files);
      return 1;
    }
    files[nfiles++] = found;
  }
  printf("file,bytes,rois,contours,points,stacks,runs,read_ms,read_mb_per_s,stacks_ms,checksum\n");
  int rc = 0;
  for (int i = 0; i < nfiles && rc == 0; i++) rc = one(files[i], repeat);
  free(files);
  return rc;
}
