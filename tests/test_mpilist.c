/* test_mpilist.c -- the list of MPI functions (mpi/mpi_funcs.h) against the library and the
 * documentation: every function of the list is defined exactly once (this program takes the
 * address of each, and of its PMPI_ name, so the link fails otherwise); a PMPI_ name calls the
 * function; calling an unimplemented function stops the run naming the rank and the function;
 * and the list in doc/mpi-support.md is the one the list makes.
 *
 *   test_mpilist                     the checks (doc/mpi-support.md read from the source tree)
 *   test_mpilist --write FILE        rewrite FILE's generated list from mpi_funcs.h */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mpi/funcs.h"
#include "mpi/mpi.h"
#include "util/atomicfile.h"
#include "tests/check.h"
#include "sim/sim.h"

/* Every function and its PMPI_ name, by address: a missing definition, or
 * a stub beside an implementation, fails the link. */
typedef void (*anyfn)(void);
static const struct {
  const char *name;
  anyfn fn, pfn;
} linked[] = {
#define TSMPI_FN(impl, chapter, ret, name, params, args) {#name, (anyfn)name, (anyfn)P##name},
#include "mpi/mpi_funcs.h"
#undef TSMPI_FN
};

static const char BEGIN[] = "<!-- BEGIN list: generated from mpi/mpi_funcs.h by "
                            "build/chk/tests/test_mpilist --write doc/mpi-support.md -->\n";
static const char END[] = "<!-- END list -->\n";

static const struct {
  const char *id, *title;
} chapters[] = {
  {"ENV", "Environment, errors, profiling"}, {"P2P", "Point-to-point"}, {"DTYPE", "Datatypes"},
  {"COLL", "Collectives and reduction operations"}, {"COMM", "Groups, communicators, attributes"},
  {"TOPO", "Process topologies"}, {"INFO", "Info objects"}, {"SPAWN", "Process creation and management"},
  {"RMA", "One-sided communication"}, {"EXT", "External interfaces, threads"}, {"IO", "I/O"},
  {"TOOL", "Tool information interface (MPI_T)"}, {"LANG", "Language interoperability"},
  {"REMOVED", "Removed by MPI 3.0, kept as MPICH keeps them"},
  {"MPI4", "MPI-4 additions"},
};
enum { NCHAPTERS = sizeof chapters / sizeof chapters[0] };

/* The generated part of doc/mpi-support.md, into a malloc'd string. */
static char *render(void) {
  size_t cap = 1 << 16, n = 0;
  char *s = malloc(cap);
  if (!s) abort();
#define OUT(...)                                                     \
  do {                                                               \
    int k_ = snprintf(s + n, cap - n, __VA_ARGS__);                  \
    if (k_ < 0 || (size_t)k_ >= cap - n) abort();                    \
    n += (size_t)k_;                                                 \
  } while (0)
  int all = 0, impl = 0, mpi4 = 0;
  for (int i = 0; i < funcs_n; i++)
    all++, impl += funcs_table[i].implemented, mpi4 += !strcmp(funcs_table[i].chapter, "MPI4");
  OUT("%s", BEGIN);
  OUT("%d functions: the %d of MPI 3.1, %d that MPI 3.0 removed and %d of MPI-4; %d implemented, %d declared "
      "only.\n",
      all, all - 10 - mpi4, 10, mpi4, impl, all - impl);
  for (int c = 0; c < NCHAPTERS; c++) {
    int ci = 0, cn = 0;
    for (int i = 0; i < funcs_n; i++)
      if (!strcmp(funcs_table[i].chapter, chapters[c].id)) cn++, ci += funcs_table[i].implemented;
    OUT("\n### %s: %d of %d implemented\n", chapters[c].title, ci, cn);
    for (int want = 1; want >= 0; want--) {
      int k = 0;
      for (int i = 0; i < funcs_n; i++) {
        if (strcmp(funcs_table[i].chapter, chapters[c].id) || funcs_table[i].implemented != want) continue;
        OUT("%s`%s`", k ? ", " : want ? "\nImplemented: " : "\nDeclared only (a call stops the run): ",
            funcs_table[i].name);
        k++;
      }
      if (k) OUT(".\n");
    }
  }
  OUT("%s", END);
  return s;
#undef OUT
}

static char *slurp(const char *path, size_t *len) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  size_t cap = 1 << 16, n = 0;
  char *s = malloc(cap + 1);
  size_t k;
  while (s && (k = fread(s + n, 1, cap - n, f)) > 0) {
    n += k;
    if (n == cap) {
      char *t = realloc(s, 2 * cap + 1);
      if (!t) free(s);
      s = t;
      cap *= 2;
    }
  }
  fclose(f);
  if (!s) abort();
  s[n] = '\0';
  *len = n;
  return s;
}

/* Replace the generated part of path with the list's (atomically). */
static int write_doc(const char *path) {
  size_t len;
  char *doc = slurp(path, &len), *gen = render();
  char *b = doc ? strstr(doc, BEGIN) : NULL, *e = b ? strstr(b, END) : NULL;
  if (!b || !e) {
    fprintf(stderr, "test_mpilist: %s: no generated list (a line \"%.*s\" and an END line)\n", path,
            (int)strlen(BEGIN) - 1, BEGIN);
    free(doc);
    free(gen);
    return 1;
  }
  char err[256];
  atomicfile af;
  int rc = atomicfile_open(&af, path, "wb", err, sizeof err);
  if (rc == 0) {
    fwrite(doc, 1, (size_t)(b - doc), af.f);
    fputs(gen, af.f);
    fputs(e + strlen(END), af.f);
    rc = atomicfile_close(&af, 1, err, sizeof err);
  }
  if (rc) fprintf(stderr, "test_mpilist: %s\n", err);
  free(doc);
  free(gen);
  return rc ? 1 : 0;
}

/* A rank that calls an unimplemented function stops the run. */
static void calls_comm_spawn(mp *self, void *ud) {
  (void)self;
  MPI_Comm c;
  *(int *)ud = 1;
  MPI_Comm_spawn("x", MPI_ARGV_NULL, 1, MPI_INFO_NULL, 0, MPI_COMM_WORLD, &c, MPI_ERRCODES_IGNORE);
  *(int *)ud = 2;   /* never: the call does not return */
}
static void waits(mp *self, void *ud) {
  (void)ud;
  mp_recv(self, MP_ANY, 5, NULL, 0, NULL);
}

int main(int argc, char **argv) {
  if (argc == 3 && !strcmp(argv[1], "--write")) return write_doc(argv[2]);
  if (argc != 1) {
    fprintf(stderr, "usage: test_mpilist [--write FILE]\n");
    return 2;
  }

  /* The list: 417 distinct functions (then MPI-4's), each linked, with its
   * PMPI_ name. */
  int mpi3 = 0;
  for (int i = 0; i < funcs_n; i++) mpi3 += strcmp(funcs_table[i].chapter, "MPI4") != 0;
  CHECK(mpi3 == 417 && (int)(sizeof linked / sizeof linked[0]) == funcs_n,
        "%d functions of MPI 3.1 in the list (want 407 and 10 removed)", mpi3);
  int dup = 0, nulls = 0;
  for (int i = 0; i < funcs_n; i++) {
    nulls += !linked[i].fn || !linked[i].pfn || linked[i].fn == linked[i].pfn;
    for (int j = 0; j < i; j++) dup += !strcmp(funcs_table[i].name, funcs_table[j].name);
  }
  CHECK(dup == 0 && nulls == 0, "%d names twice, %d functions without their own address", dup, nulls);

  /* A PMPI_ name is the function. */
  int size = 0;
  CHECK(PMPI_Type_size(MPI_DOUBLE_INT, &size) == MPI_SUCCESS && size == 12, "PMPI_Type_size(MPI_DOUBLE_INT): %d",
        size);
  CHECK(MPI_Aint_diff(PMPI_Aint_add(100, 28), 28) == 100, "PMPI_Aint_add/MPI_Aint_diff");

  /* An unimplemented function on the simulator: the run stops, naming
   * the rank and the function, with exit code 1. */
  sim_config cfg;
  sim_config_init(&cfg);
  cfg.procs = 2;
  cfg.warn = NULL;
  char err[512];
  sim *s = sim_new(&cfg, 2, err, sizeof err);
  int reached = 0;
  mp_proc procs[2] = {{waits, NULL}, {calls_comm_spawn, &reached}};
  int rc = s ? sim_run(s, procs, err, sizeof err) : -2;
  CHECK(rc == -1 && strstr(err, "rank 1 called MPI_Comm_spawn, which tilesim does not implement") && reached == 1 &&
            sim_stats_get(s)->aborted && sim_stats_get(s)->abort_code == 1,
        "calling MPI_Comm_spawn: sim_run %d, \"%s\", reached %d", rc, err, reached);
  if (s) sim_free(s);

  /* doc/mpi-support.md's list is the list's. */
  size_t len;
  char *doc = slurp("doc/mpi-support.md", &len), *gen = render();
  char *b = doc ? strstr(doc, BEGIN) : NULL, *e = b ? strstr(b, END) : NULL;
  int same = b && e && (size_t)(e + strlen(END) - b) == strlen(gen) && !memcmp(b, gen, strlen(gen));
  CHECK(same, "doc/mpi-support.md: %s (run build/chk/tests/test_mpilist --write doc/mpi-support.md)",
        !doc ? "cannot be read" : !b || !e ? "has no generated list" : "its list is not mpi/mpi_funcs.h's");
  free(doc);
  free(gen);
  return check_done("test_mpilist");
}
