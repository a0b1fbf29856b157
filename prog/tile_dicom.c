/* tile_dicom.c -- ./tile on a DICOM RT structure set: list its ROIs, tile
 * them (one, several or all), convert them to .contours stacks.
 *
 * Everything that can be refused is refused before any output: the file, the
 * ROIs asked for, their stacks.  With --roi all, an ROI that cannot be tiled
 * (no closed contours, or a refusal) is skipped with a warning and the others
 * are tiled. */
#include "prog/tile_dicom.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "util/args.h"
#include "util/atomicfile.h"
#include "input/dicom.h"
#include "surface/meshio.h"
#include "input/rtstruct.h"
#include "surface/stack.h"
#include "util/strbuf.h"
#include "util/xmem.h"

int tile_dicom_is_dir(const char *path) {
  struct stat st;
  size_t n = strlen(path);
  return (n > 0 && path[n - 1] == '/') || (stat(path, &st) == 0 && S_ISDIR(st.st_mode));
}

int tile_dicom_option(tile_dicom_opts *o, const char *a, const char *v, char *err, size_t errlen) {
  if (strcmp(a, "--list") == 0) {
    o->list = 1;
    return 1;
  }
  int roi = strcmp(a, "--roi") == 0, con = strcmp(a, "--contours") == 0, fmt = strcmp(a, "--format") == 0;
  if (!roi && !con && !fmt) return 0;
  if (!v) {
    snprintf(err, errlen, "option %s needs a value", a);
    return -1;
  }
  if (roi) {
    if (o->nroi == TILE_DICOM_MAX_ROI) {
      snprintf(err, errlen, "--roi at most %d times (%s)", TILE_DICOM_MAX_ROI, v);
      return -1;
    }
    if (!*v) {
      snprintf(err, errlen, "--roi takes a ROI's name, its number or all ('')");
      return -1;
    }
    o->roi[o->nroi++] = v;
  } else if (con) {
    if (args_name(a, v, "a .contours file name or DIR/", 0, err, errlen) != 0) return -1;
    o->contours = v;
  } else {
    if (args_word(a, v, "stl|obj|ply", err, errlen) < 0) return -1;
    o->format = v;
  }
  return 2;
}

int tile_dicom_given(const tile_dicom_opts *o) {
  return o->list || o->nroi > 0 || o->contours || o->format;
}

/* ---------------------------------------------------------------- output */

/* A CSV field: quoted when it holds a comma, a quote or a line break. */
static void csv_field(FILE *f, const char *s) {
  if (!strpbrk(s, ",\"\r\n")) {
    fputs(s, f);
    return;
  }
  fputc('"', f);
  for (; *s; s++) {
    if (*s == '"') fputc('"', f);
    fputc(*s, f);
  }
  fputc('"', f);
}

static void list(const rtstruct *s) {
  printf("roi_number,name,type,contours,skipped,slices,points,z_min,z_max,plane\n");
  for (int i = 0; i < s->nroi; i++) {
    const rtstruct_roi *r = &s->roi[i];
    printf("%d,", r->number);
    csv_field(stdout, r->name);
    putchar(',');
    csv_field(stdout, r->type);
    printf(",%d,%d,", r->nc, r->skipped);
    if (r->error) printf(",,,,\n");
    else if (r->nc == 0) printf("0,0,,,\n");
    else {
      char lo[48], hi[48];   /* as the file wrote them */
      rtstruct_height_text(r, 0, lo, sizeof lo);
      rtstruct_height_text(r, r->nc - 1, hi, sizeof hi);
      printf("%d,%ld,%s,%s,%s\n", r->slices, r->points, lo, hi, rtstruct_plane_name(r->plane));
    }
  }
}

/* The ROI's name as a file name: letters, digits, '.', '-', '_' kept, the
 * rest '_'; not starting with '.' or '-'; at most 100 bytes; roi_N if it
 * has no letter or digit. */
static void file_name(const rtstruct_roi *r, char *buf, size_t cap) {
  size_t j = 0;
  int any = 0;
  for (const char *p = r->name; *p && j + 1 < cap && j < 100; p++) {
    char c = *p;
    int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
             ((c == '.' || c == '-') && j > 0);
    buf[j++] = ok ? c : '_';
    any |= (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
  }
  buf[j] = 0;
  if (!any) snprintf(buf, cap, "roi_%d", r->number);
}

/* Names compared ignoring case (file systems that ignore it). */
static int cmp_name(const char *a, const char *b) {
  for (;; a++, b++) {
    int x = (unsigned char)*a, y = (unsigned char)*b;
    if (x >= 'A' && x <= 'Z') x += 'a' - 'A';
    if (y >= 'A' && y <= 'Z') y += 'a' - 'A';
    if (x != y || !x) return x - y;
  }
}

typedef struct {
  char name[112];
  int i;
} named;

static int by_name(const void *a, const void *b) {
  const named *p = a, *q = b;
  int c = cmp_name(p->name, q->name);
  return c ? c : p->i - q->i;
}

/* DIR/NAME.EXT for every chosen ROI; a name two ROIs share (ignoring case)
 * gets the ROI number: NAME_N.EXT.  Sorted to find the shared names. */
static char **dir_paths(const rtstruct *s, const int *pick, int n, const char *dir, const char *ext) {
  named *nm = xmallocarray((size_t)n, sizeof *nm);
  char *clash = xcalloc((size_t)n + 1, 1);
  for (int i = 0; i < n; i++) file_name(&s->roi[pick[i]], nm[i].name, sizeof nm[i].name), nm[i].i = i;
  qsort(nm, (size_t)n, sizeof *nm, by_name);
  for (int k = 1; k < n; k++)
    if (cmp_name(nm[k].name, nm[k - 1].name) == 0) clash[nm[k].i] = clash[nm[k - 1].i] = 1;
  char **path = xmallocarray((size_t)n, sizeof *path);
  size_t dl = strlen(dir);
  int slash = dl > 0 && dir[dl - 1] == '/';
  for (int k = 0; k < n; k++) {
    int i = nm[k].i;
    size_t len = dl + strlen(nm[k].name) + 32;
    path[i] = xmalloc(len);
    if (clash[i]) snprintf(path[i], len, "%s%s%s_%d.%s", dir, slash ? "" : "/", nm[k].name, s->roi[pick[i]].number, ext);
    else snprintf(path[i], len, "%s%s%s.%s", dir, slash ? "" : "/", nm[k].name, ext);
  }
  free(clash);
  free(nm);
  return path;
}

static void free_paths(char **p, int n) {
  if (!p) return;
  for (int i = 0; i < n; i++) free(p[i]);
  free(p);
}

static int make_dir(const char *dir) {
  struct stat st;
  if (stat(dir, &st) == 0 && S_ISDIR(st.st_mode)) return 0;
  if (mkdir(dir, 0777) == 0) return 0;
  fprintf(stderr, "tile: %s: cannot create the directory (%s)\n", dir, strerror(errno));
  return -1;
}

/* Can file be written (NULL: nothing to write)?  dir, when not NULL, is the
 * folder it goes in, made later: if it is not there yet, its parent must
 * take it.  1, or 0 after a message. */
static int writable(const char *file, const char *dir) {
  char err[1200], d[1024];
  struct stat st;
  const char *check = file;
  if (dir && stat(dir, &st) != 0) {   /* not made yet: a file of its name beside it */
    snprintf(d, sizeof d, "%s", dir);
    for (size_t n = strlen(d); n > 1 && d[n - 1] == '/'; n--) d[n - 1] = 0;
    check = d;
  }
  if (!check || atomicfile_check(check, err, sizeof err) == 0) return 1;
  fprintf(stderr, "tile: %s\n", err);
  return 0;
}

static int write_text(const char *path, const char *text, size_t len) {
  atomicfile af;
  char err[512];
  if (atomicfile_open(&af, path, "w", err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    return -1;
  }
  fwrite(text, 1, len, af.f);
  if (atomicfile_close(&af, 1, err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    return -1;
  }
  return 0;
}

void tile_say_lines(FILE *f, const char *lines) {
  for (const char *p = lines; f && p && *p;) {
    const char *e = strchr(p, '\n');
    size_t n = e ? (size_t)(e - p) : strlen(p);
    fprintf(f, "tile: %.*s\n", (int)n, p);
    p += n + (e != NULL);
  }
}

static void warn_lines(FILE *f, const char *lines) { tile_say_lines(f, lines); }

/* The surface's messages about an ROI's stack, named as the reader's are. */
typedef struct {
  const rtstruct *s;
  int roi;
  const char *name;
} roi_map;

static char *map_rewrite(void *ud, const char *msg) {
  const roi_map *m = ud;
  return rtstruct_rewrite(m->s, m->roi, m->name, msg);
}

/* ---------------------------------------------------------------- main */

static int by_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

int tile_dicom_main(const tile_dicom_opts *o, const char *in, const tile_dicom_env *env) {
  char err[1024], *rerr = NULL;
  int all = 0;
  for (int i = 0; i < o->nroi; i++) all |= strcmp(o->roi[i], "all") == 0;
  int several = all || o->nroi > 1;
  int out_dir = env->out && tile_dicom_is_dir(env->out);
  int con_dir = o->contours && tile_dicom_is_dir(o->contours);
  /* Usage, before the file is read. */
  if (o->list && (o->nroi || o->contours || env->out))
    return env->usage("%s", "--list lists the ROIs; leave out --roi, --contours and -o");
  if (!o->nroi && (o->contours || env->out))
    return env->usage("%s", "-o and --contours need --roi NAME|NUMBER|all (the ROI to tile)");
  if (env->out && !out_dir && meshio_format_of(env->out) == MESHIO_NONE)
    return env->usage("unknown mesh format, use .obj, .ply or .stl, or DIR/ (%s)", env->out);
  if (several && env->out && !out_dir)
    return env->usage("several ROIs write one mesh each: -o DIR/ (%s)", env->out);
  if (several && o->contours && !con_dir)
    return env->usage("several ROIs write one stack each: --contours DIR/ (%s)", o->contours);
  if (o->format && !out_dir) return env->usage("%s", "--format is for -o DIR/ (the meshes' format)");
  if (several && env->trace) return env->usage("%s", "--trace traces one ROI at a time");

  rtstruct s;
  if (rtstruct_read(in, &s, err, sizeof err) != 0) {
    fprintf(stderr, "tile: %s\n", err);
    return 1;
  }
  /* Warnings and notes are held back until nothing can be refused: a
   * refusal is one line and nothing else. */
  char *held = NULL;
  size_t heldlen = 0;
  FILE *notes = env->quiet ? NULL : open_memstream(&held, &heldlen);
  warn_lines(notes, s.warnings);
  if (!o->nroi) {
    if (notes) fclose(notes), fputs(held, stderr), free(held);
    list(&s);
    if (!o->list)
      fprintf(stderr,
              "tile: %s: an RT structure set of %d ROI%s; add --roi NAME|NUMBER to tile one "
              "(-o OUT.stl for its mesh), --roi all -o DIR/ for all, --contours OUT.contours to "
              "convert one to a stack\n", in, s.nroi, s.nroi == 1 ? "" : "s");
    rtstruct_free(&s);
    return fflush(stdout) == 0 ? 0 : 1;
  }

  /* The ROIs, in the order asked, each once. */
  int *pick = xmallocarray((size_t)s.nroi + 1, sizeof *pick), npick = 0, rcode = 1;
  int *refused = NULL, nrefused = 0, nempty = 0;   /* with all: ROIs refused; with nothing to tile */
  int npaths = 0;   /* mpath and cpath hold this many */
  char *chosen = xcalloc((size_t)s.nroi + 1, 1);
  contour_stack *st = xcalloc((size_t)s.nroi + 1, sizeof *st);
  mesh *me = xcalloc((size_t)s.nroi + 1, sizeof *me);
  char **mpath = NULL, **cpath = NULL;
  int nmesh = 0;
  for (int i = 0; i < o->nroi; i++) {
    if (strcmp(o->roi[i], "all") == 0) {
      for (int k = 0; k < s.nroi; k++)
        if (!chosen[k]) chosen[k] = 1, pick[npick++] = k;
      continue;
    }
    int k = rtstruct_find(&s, o->roi[i], err, sizeof err);
    if (k < 0) {
      fprintf(stderr, "tile: %s\n", err);
      goto done;
    }
    if (!chosen[k]) chosen[k] = 1, pick[npick++] = k;
  }
  /* Their stacks: refused ones end the run, or with all are skipped. */
  int tile = env->out || !o->contours, kept = 0;
  int flags = (env->pairs ? CONTOUR_PAIRS : 0) | (env->no_keyholes ? CONTOUR_NO_KEYHOLES : 0) |
              (env->read_flags & (CONTOUR_SKIP_BAD | CONTOUR_UNION | CONTOUR_VERBOSE | CONTOUR_DROP_DEGENERATE));
  rerr = xmalloc(TILE_ERR_MAX);
  refused = xmallocarray((size_t)s.nroi + 1, sizeof *refused);
  for (int i = 0; i < npick; i++) {
    const rtstruct_roi *r = &s.roi[pick[i]];
    int bad = rtstruct_roi_check(&s, pick[i], rerr, TILE_ERR_MAX);
    int empty = bad && !r->error;   /* no closed planar contours: nothing to tile, not a refusal */
    if (!bad && tile)
      bad = rtstruct_roi_stack(&s, pick[i], flags | CONTOUR_ONE_SLICE, &st[kept], notes, "tile", rerr, TILE_ERR_MAX);
    if (!bad && tile) {   /* one slice: only with --thickness, said as the reader says its refusals */
      char sname[700], e2[1024];
      snprintf(sname, sizeof sname, "%s: ROI %d '%s' as a stack", s.name, r->number, r->name);
      if (stack_check_slices(&st[kept], sname, env->thickness, e2, sizeof e2) != 0) {
        char *m = rtstruct_rewrite(&s, pick[i], sname, e2);
        snprintf(rerr, TILE_ERR_MAX, "%s", m);
        free(m);
        contour_stack_free(&st[kept]);
        bad = 1;
      }
    }
    if (bad) {
      if (!all) {
        tile_say_lines(stderr, rerr);
        goto done;
      }
      /* A refusal is said even under -q; an ROI with nothing to tile is a note. */
      if (notes || !empty) {
        size_t el = strlen(rerr);
        snprintf(rerr + el, TILE_ERR_MAX - el, "; skipped");
        tile_say_lines(notes ? notes : stderr, rerr);
      }
      if (empty) nempty++;
      else refused[nrefused++] = pick[i];
      continue;
    }
    warn_lines(notes, r->warnings);
    pick[kept++] = pick[i];
  }
  npick = kept;
  if (notes) {
    fclose(notes), notes = NULL;
    fputs(held, stderr);
  }
  if (npick == 0) {
    fprintf(stderr, "tile: %s: none of the %d ROIs can be tiled\n", s.name, s.nroi);
    goto done;
  }
  int ntiled = 0;   /* ROIs tiled, in pick[0..ntiled-1] (with all, the refused ones left out) */
  if (out_dir) mpath = dir_paths(&s, pick, npick, env->out, o->format ? o->format : "stl");
  if (con_dir) cpath = dir_paths(&s, pick, npick, o->contours, "contours");
  npaths = npick;
  /* The files can be written (a folder: made or makeable), checked before
   * the tiling: a run never prints its report and then fails to write. */
  if (!writable(out_dir ? (mpath ? mpath[0] : NULL) : env->out, out_dir ? env->out : NULL) ||
      !writable(con_dir ? (cpath ? cpath[0] : NULL) : o->contours, con_dir ? o->contours : NULL))
    goto done;

  /* The tiling, the report on stdout. */
  if (tile) {
    char hpre[32] = "", pre[600] = "";
    if (several) snprintf(hpre, sizeof hpre, "roi_number,name,");
    for (int i = 0; i < npick; i++) {
      const rtstruct_roi *r = &s.roi[pick[i]];
      if (several) {
        char *field = NULL;
        size_t flen = 0;
        FILE *f = open_memstream(&field, &flen);
        csv_field(f, r->name);
        fclose(f);
        snprintf(pre, sizeof pre, "%d,%s,", r->number, field);
        free(field);
      }
      char sname[700];
      snprintf(sname, sizeof sname, "%s: ROI %d '%s' as a stack", s.name, r->number, r->name);
      roi_map rm = {&s, pick[i], sname};
      tile_dicom_map map = {map_rewrite, &rm};
      int k = ntiled;   /* its mesh and stack go to slot k (k <= i) */
      if (k != i) {
        contour_stack t = st[k];
        st[k] = st[i], st[i] = t;
        pick[k] = pick[i];
        if (mpath) {
          char *x = mpath[k];
          mpath[k] = mpath[i], mpath[i] = x;
        }
        if (cpath) {
          char *x = cpath[k];
          cpath[k] = cpath[i], cpath[i] = x;
        }
      }
      int res = env->tile(env->ud, &st[k], sname, &map, hpre, pre, k == 0, &me[k]);
      nmesh = k + 1;
      if (res != 0) {
        if (!all) goto done;
        mesh_free(&me[k]);
        refused[nrefused++] = pick[k];
        nmesh = k;
        continue;
      }
      ntiled++;
      for (int v = 0; v < me[k].nv; v++)
        rtstruct_to_patient(r, &me[k].v[v].x, &me[k].v[v].y, &me[k].v[v].z);
    }
    if (ntiled == 0) {
      fprintf(stderr, "tile: %s: none of the %d ROIs can be tiled\n", s.name, s.nroi);
      goto done;
    }
    if (fflush(stdout) != 0) {
      fprintf(stderr, "tile: cannot write the report (%s)\n", strerror(errno));
      goto done;
    }
  }
  if (tile) npick = ntiled;
  /* The files. */
  if ((out_dir && make_dir(env->out) != 0) || (con_dir && make_dir(o->contours) != 0)) goto done;
  for (int i = 0; i < npick; i++) {
    if (o->contours) {
      size_t len;
      char *text = rtstruct_roi_text(&s, pick[i], &len);
      int bad = write_text(cpath ? cpath[i] : o->contours, text, len);
      free(text);
      if (bad) goto done;
    }
    if (env->out && meshio_write(&me[i], mpath ? mpath[i] : env->out, err, sizeof err) != 0) {
      fprintf(stderr, "tile: %s\n", err);
      goto done;
    }
  }
  rcode = 0;
  if (nrefused) {
    /* One line that counts both, naming the refused (each said above), and
     * an exit status that says some were refused. */
    strbuf b = {0};
    qsort(refused, (size_t)nrefused, sizeof *refused, by_int);
    strbuf_add(&b, "tile: %s: %d of %d ROIs %s, %d refused (", s.name, npick, s.nroi,
               tile ? "tiled" : "converted", nrefused);
    for (int i = 0; i < nrefused; i++)
      strbuf_add(&b, "%sROI %d '%s'", i ? ", " : "", s.roi[refused[i]].number, s.roi[refused[i]].name);
    strbuf_add(&b, ": each said above)");
    if (nempty) strbuf_add(&b, ", %d with nothing to tile", nempty);
    strbuf_add(&b, "\n");
    fputs(b.buf, stderr);
    free(b.buf);
    rcode = TILE_DICOM_SOME_REFUSED;
  }
done:
  if (notes) fclose(notes);
  free(held);
  free(rerr);
  for (int i = 0; i < nmesh; i++) mesh_free(&me[i]);
  for (int i = 0; i < s.nroi; i++) contour_stack_free(&st[i]);
  free_paths(mpath, npaths);
  free_paths(cpath, npaths);
  free(me);
  free(st);
  free(chosen);
  free(pick);
  free(refused);
  rtstruct_free(&s);
  return rcode;
}
