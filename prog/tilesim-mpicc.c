/* tilesim-mpicc.c -- compile and link an MPI C program for tilesim-mpirun.
 *
 *   tilesim-mpicc [--count-blocks] [--showme] [CC OPTIONS] FILES... [-o PROG]
 *
 * Like mpicc: the arguments go to the C compiler ($TILESIM_CC, else $CC,
 * else cc) with tilesim's mpi.h on the include path and its runtime header
 * (tilesim_mpi.h, which gives each rank its own libc state and the
 * simulated clocks) included first in every file, position-independent.
 * With -c, -S, -E or -M it only compiles.  Otherwise it links a shared
 * object (what tilesim-mpirun loads once per rank), its own names bound to
 * its own definitions (-Bsymbolic); the MPI functions stay undefined until
 * tilesim-mpirun provides them.  After linking it lists the MPI functions
 * the program references that tilesim does not implement (a warning: the
 * run stops if it calls one).  --count-blocks compiles with
 * -fsanitize-coverage=trace-pc, for tilesim-mpirun --compute blocks.
 * --showme prints the compiler's command instead of running it.
 * The exit status is the compiler's; 2 for bad usage. */
#define _GNU_SOURCE
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "elfsyms.h"
#include "funcs.h"
#include "xmem.h"

static const char prog[] = "tilesim-mpicc";

/* The folder that holds mpi.h and tilesim_mpi.h: $TILESIM_MPI_INCLUDE, or
 * next to this program as installed (PREFIX/bin -> PREFIX/include/tilesim/mpi;
 * build/bin -> build/include/tilesim/mpi) or in the source tree's root
 * (./tilesim-mpicc -> build/include/tilesim/mpi). */
static char *include_dir(void) {
  const char *env = getenv("TILESIM_MPI_INCLUDE");
  if (env && *env) return xstrdup(env);
  char self[PATH_MAX];
  ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
  if (k <= 0) return NULL;
  self[k] = 0;
  char *slash = strrchr(self, '/');
  if (!slash) return NULL;
  *slash = 0;
  static const char *const rel[] = {"/../include/tilesim/mpi", "/build/include/tilesim/mpi"};
  for (size_t i = 0; i < sizeof rel / sizeof *rel; i++) {
    char dir[PATH_MAX + 64], probe[PATH_MAX + 80];
    snprintf(dir, sizeof dir, "%s%s", self, rel[i]);
    snprintf(probe, sizeof probe, "%s/mpi.h", dir);
    struct stat sb;
    if (stat(probe, &sb) == 0) return xstrdup(dir);
  }
  return NULL;
}

/* An argument vector that grows. */
typedef struct {
  char **v;
  int n, cap;
} vec;

static void push(vec *a, const char *s) {
  if (a->n + 2 > a->cap) a->v = xreallocarray(a->v, (size_t)(a->cap = a->cap ? 2 * a->cap : 32), sizeof *a->v);
  a->v[a->n++] = xstrdup(s);
  a->v[a->n] = NULL;
}

/* The unimplemented MPI functions a linked program references. */
typedef struct {
  char list[2048];
  size_t len;
  int count;
} missing;

static void reference(void *ud, const char *name, int defined) {
  missing *m = ud;
  if (defined || strncmp(name, "MPI_", 4) != 0) return;
  for (int i = 0; i < tsmpi_nfuncs; i++)
    if (strcmp(tsmpi_funcs[i].name, name) == 0) {
      if (tsmpi_funcs[i].implemented) return;
      break;
    }
  if (m->len + strlen(name) + 3 < sizeof m->list)
    m->len += (size_t)snprintf(m->list + m->len, sizeof m->list - m->len, "%s%s", m->count ? ", " : "", name);
  m->count++;
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: %s [--count-blocks] [--showme] [CC OPTIONS] FILES... [-o PROG]\n"
          "\n"
          "Compile and link an MPI C program for tilesim-mpirun, as mpicc does for an MPI\n"
          "library: the arguments go to the C compiler ($TILESIM_CC, else $CC, else cc) with\n"
          "tilesim's mpi.h and its runtime header; -c, -S, -E or -M only compile; otherwise\n"
          "the program is linked as a shared object that tilesim-mpirun loads once per\n"
          "rank, and the MPI functions it references that tilesim does not implement are\n"
          "listed.\n"
          "\n"
          "  --count-blocks     count the program's basic blocks (tilesim-mpirun --compute\n"
          "                     blocks charges them)\n"
          "  --showme           print the compiler's command instead of running it\n"
          "  -h, --help         this text\n",
          prog);
}

/* Run the compiler: its exit status (128 + a signal that ended it). */
static int compile(const vec *cmd, const char *cc) {
  fflush(stdout);
  pid_t pid = fork();
  if (pid < 0) {
    fprintf(stderr, "%s: cannot start %s: %s\n", prog, cc, strerror(errno));
    return 1;
  }
  if (pid == 0) {
    execvp(cmd->v[0], cmd->v);
    fprintf(stderr, "%s: cannot run %s: %s\n", prog, cc, strerror(errno));
    _exit(127);
  }
  int ws;
  while (waitpid(pid, &ws, 0) < 0)
    if (errno != EINTR) return 1;
  return WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
}

int main(int argc, char **argv) {
  int compile_only = 0, count_blocks = 0, showme = 0, any_input = 0;
  const char *out = "a.out";
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "--help") == 0 || (strcmp(a, "-h") == 0 && argc == 2)) {
      usage(stdout);
      return 0;
    }
    if (strcmp(a, "-c") == 0 || strcmp(a, "-S") == 0 || strcmp(a, "-E") == 0 || strcmp(a, "-M") == 0 ||
        strcmp(a, "-MM") == 0)
      compile_only = 1;
    else if (strcmp(a, "-o") == 0 && i + 1 < argc) out = argv[++i];
    else if (a[0] != '-') any_input = 1;
  }
  char *inc = include_dir();
  if (!inc) {
    fprintf(stderr, "%s: cannot find tilesim's mpi.h next to this program (set TILESIM_MPI_INCLUDE)\n", prog);
    return 2;
  }
  const char *cc = getenv("TILESIM_CC");
  if (!cc || !*cc) cc = getenv("CC");
  if (!cc || !*cc) cc = "cc";
  vec cmd = {NULL, 0, 0};
  push(&cmd, cc);
  char buf[PATH_MAX + 64];
  snprintf(buf, sizeof buf, "-I%s", inc);
  push(&cmd, buf);
  snprintf(buf, sizeof buf, "%s/tilesim_mpi.h", inc);
  push(&cmd, "-include");
  push(&cmd, buf);
  push(&cmd, "-fPIC");
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--count-blocks") == 0) count_blocks = 1;
    else if (strcmp(argv[i], "--showme") == 0) showme = 1;
    else push(&cmd, argv[i]);
  }
  if (count_blocks) push(&cmd, "-fsanitize-coverage=trace-pc");
  if (!compile_only) {
    push(&cmd, "-shared");
    push(&cmd, "-Wl,-Bsymbolic");
  }
  int status = 0;
  if (!any_input && !showme) {
    fprintf(stderr, "%s: no input files\n", prog);
    usage(stderr);
    status = 2;
  } else if (showme) {
    for (int i = 0; i < cmd.n; i++) printf("%s%s", i ? " " : "", cmd.v[i]);
    putchar('\n');
  } else {
    status = compile(&cmd, cc);
  }
  if (status == 0 && !compile_only && !showme) {
    missing m = {"", 0, 0};
    char err[512];
    if (elfsyms_read(out, reference, &m, err, sizeof err) != 0)
      fprintf(stderr, "%s: warning: %s\n", prog, err);
    else if (m.count)
      fprintf(stderr, "%s: warning: %s references %s, which tilesim does not implement: a run stops if it calls %s\n",
              prog, out, m.list, m.count == 1 ? "it" : "one");
  }
  for (int i = 0; i < cmd.n; i++) free(cmd.v[i]);
  free(cmd.v);
  free(inc);
  return status;
}
