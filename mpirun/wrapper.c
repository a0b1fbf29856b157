/* wrapper.c -- tilesim-mpicc and tilesim-mpicxx (wrapper.h). */
#define _GNU_SOURCE
#include "mpirun/wrapper.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "mpirun/elfprog.h"
#include "mpi/funcs.h"
#include "util/xmem.h"

/* Set in the compiler's environment: a wrapper that finds it was run by the
 * compiler it runs. */
#define DEPTH_VAR "TILESIM_MPICC_RUNNING"

/* How far apart tilesim-mpicc puts a program's code and its data: ranks
 * whose images fit in this gap share mappings (mpirun/loader.c). */
#define GAP "0x4000000"

typedef struct {
  const char *prog;      /* "tilesim-mpicc" */
  const char *ccvar;     /* "TILESIM_CC" */
  const char *ccdef;     /* "cc" */
  const char *lang;      /* "C" */
} flavour;

static const flavour flavours[] = {{"tilesim-mpicc", "TILESIM_CC", "cc", "C"},
                                   {"tilesim-mpicxx", "TILESIM_CXX", "c++", "C++"}};

/* ==== argument vectors ==================================================== */

typedef struct {
  char **v;
  int n, cap;
} vec;

static void push(vec *a, const char *s) {
  if (a->n + 2 > a->cap) a->v = xreallocarray(a->v, (size_t)(a->cap = a->cap ? 2 * a->cap : 32), sizeof *a->v);
  a->v[a->n++] = xstrdup(s);
  a->v[a->n] = NULL;
}

static void push_all(vec *a, const vec *b) {
  for (int i = 0; i < b->n; i++) push(a, b->v[i]);
}

static void drop(vec *a) {
  for (int i = 0; i < a->n; i++) free(a->v[i]);
  free(a->v);
}

/* Words of s, split at blanks (TILESIM_CC="ccache gcc -m64"). */
static void push_words(vec *a, const char *s) {
  char *t = xstrdup(s);
  for (char *w = strtok(t, " \t\n"); w; w = strtok(NULL, " \t\n")) push(a, w);
  free(t);
}

static void print(FILE *f, const vec *a) {
  for (int i = 0; i < a->n; i++) fprintf(f, "%s%s", i ? " " : "", a->v[i]);
  fputc('\n', f);
}

/* ==== where tilesim's files are =========================================== */

/* The folder that holds `probe`: $env, or beside this program as installed
 * (PREFIX/bin -> PREFIX/<inst>), in a build (build/bin, build/chk ->
 * build/<inst>) or in the source tree's root (./tilesim-mpicc ->
 * build/<inst>).  NULL if none. */
static char *find_dir(const char *env, const char *inst, const char *probe) {
  const char *e = getenv(env);
  if (e && *e) return xstrdup(e);
  char self[PATH_MAX];
  ssize_t k = readlink("/proc/self/exe", self, sizeof self - 1);
  if (k <= 0) return NULL;
  self[k] = 0;
  char *slash = strrchr(self, '/');
  if (!slash) return NULL;
  *slash = 0;
  const char *rel[] = {"/..", "/build"};
  for (size_t i = 0; i < sizeof rel / sizeof *rel; i++) {
    char dir[PATH_MAX + 64], file[PATH_MAX + 128];
    snprintf(dir, sizeof dir, "%s%s/%s", self, rel[i], inst);
    snprintf(file, sizeof file, "%s/%s", dir, probe);
    struct stat sb;
    if (stat(file, &sb) == 0) {
      char *real = realpath(dir, NULL);
      return real ? real : xstrdup(dir);
    }
  }
  return NULL;
}

/* The compiler's path as the shell would find it, resolved; NULL if not found. */
static char *which(const char *cmd) {
  if (strchr(cmd, '/')) return realpath(cmd, NULL);
  const char *path = getenv("PATH");
  if (!path) path = "/usr/bin:/bin";
  while (*path) {
    size_t k = strcspn(path, ":");
    char full[PATH_MAX + 256];
    snprintf(full, sizeof full, "%.*s/%s", (int)k, k ? path : ".", cmd);
    if (access(full, X_OK) == 0) return realpath(full, NULL);
    path += k + (path[k] == ':');
  }
  return NULL;
}

/* 1 if cmd is one of tilesim's wrappers (this program or its sibling). */
static int is_wrapper(const char *cmd) {
  char *c = which(cmd), *self = realpath("/proc/self/exe", NULL);
  int same = 0;
  if (c && self) {
    same = strcmp(c, self) == 0;
    const char *b = strrchr(c, '/') ? strrchr(c, '/') + 1 : c;
    same |= strcmp(b, "tilesim-mpicc") == 0 || strcmp(b, "tilesim-mpicxx") == 0;
  }
  free(c);
  free(self);
  return same;
}

/* ==== running the compiler ================================================ */

/* Its exit status (128 + a signal that ended it). */
static int run(const vec *cmd, const flavour *fl) {
  fflush(stdout);
  pid_t pid = fork();
  if (pid < 0) {
    fprintf(stderr, "%s: cannot start %s: %s\n", fl->prog, cmd->v[0], strerror(errno));
    return 1;
  }
  if (pid == 0) {
    setenv(DEPTH_VAR, fl->prog, 1);
    execvp(cmd->v[0], cmd->v);
    fprintf(stderr, "%s: cannot run %s: %s (%s names the %s compiler)\n", fl->prog, cmd->v[0], strerror(errno),
            fl->ccvar, fl->lang);
    _exit(127);
  }
  int ws;
  while (waitpid(pid, &ws, 0) < 0)
    if (errno != EINTR) return 1;
  return WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
}

/* ==== running on its own ================================================== */

/* A memory file the compiler inherits, holding assembly for the section
 * that names the program's interpreter: the linker makes no such section in
 * a shared object, and with it a program run on its own is started by the
 * dynamic linker, whose loading of libtilesim_mpi.so says how to run it.
 * The interpreter is this program's own (the same machine's).  Its
 * descriptor, or -1 where that cannot be (the program then crashes when run
 * on its own, and runs under tilesim-mpirun all the same).  Its symbol,
 * tilesim_interp, keeps the section from --gc-sections (-u). */
static int interp_source(void) {
  elf_prog self;
  char err[300];
  if (elf_read("/proc/self/exe", &self, err, sizeof err) != 0) return -1;
  int fd = self.interp ? memfd_create("tilesim-interp", 0) : -1;
  if (fd >= 0) {
    char text[PATH_MAX + 200];
    int k = snprintf(text, sizeof text,
                     "\t.section .interp,\"a\"\n\t.hidden tilesim_interp\n\t.globl tilesim_interp\n"
                     "tilesim_interp:\n\t.string \"%s\"\n\t.section .note.GNU-stack,\"\",%%progbits\n", self.interp);
    if (k <= 0 || (size_t)k >= sizeof text || write(fd, text, (size_t)k) != k) {
      close(fd);
      fd = -1;
    }
  }
  elf_free(&self);
  return fd;
}

/* ==== the unimplemented functions a program calls ========================= */

static int implemented(const char *name) {
  if (strncmp(name, "PMPI_", 5) == 0) name++;
  for (int i = 0; i < funcs_n; i++)
    if (strcmp(funcs_table[i].name, name) == 0) return funcs_table[i].implemented;
  return 1;   /* a callback or a compute call: tilesim-mpirun has it */
}

/* The linked program at out: it has a main (else it is removed, as a
 * linker removes what it failed to link: 1), and which MPI functions its
 * code calls (a PLT slot names them) that tilesim does not implement, in
 * one warning.  0, or 1. */
static int check_linked(const char *out, const flavour *fl) {
  elf_prog e;
  char err[600];
  if (elf_read(out, &e, err, sizeof err) != 0) {
    fprintf(stderr, "%s: warning: %s\n", fl->prog, err);
    return 0;
  }
  if (!e.has_main) {
    fprintf(stderr, "%s: %s has no main function: an MPI program needs one\n", fl->prog, out);
    elf_free(&e);
    remove(out);
    return 1;
  }
  char list[2048] = "";
  size_t len = 0;
  int count = 0;
  for (size_t k = 1; k < e.nsyms; k++) {
    const elf_sym *s = &e.syms[k];
    if (s->defined || !s->called || (strncmp(s->name, "MPI_", 4) != 0 && strncmp(s->name, "PMPI_", 5) != 0) ||
        implemented(s->name))
      continue;
    if (len + strlen(s->name) + 8 < sizeof list)
      len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", count ? ", " : "", s->name);
    else if (len + 8 < sizeof list && !strstr(list, ", ..."))
      len += (size_t)snprintf(list + len, sizeof list - len, ", ...");
    count++;
  }
  if (count)
    fprintf(stderr, "%s: warning: %s calls %s, which tilesim does not implement: a run stops if it calls %s\n",
            fl->prog, out, list, count == 1 ? "it" : "one");
  elf_free(&e);
  return 0;
}

/* ==== the wrapper ========================================================= */

static void usage(FILE *f, const flavour *fl) {
  fprintf(f,
          "usage: %s [--count-blocks] [-show] [%s OPTIONS] FILES... [-o PROG]\n"
          "\n"
          "Compile and link an MPI %s program for tilesim-mpirun, as mpi%s does for an MPI\n"
          "library: the arguments go to the %s compiler ($%s, else %s) with tilesim's\n"
          "mpi.h; -c, -S, -E, -M or -MM only compile; otherwise the program is linked for\n"
          "tilesim-mpirun, a call of a function tilesim does not have fails the link, and\n"
          "the MPI functions the program calls that tilesim does not implement are listed.\n"
          "\n"
          "  --count-blocks     count the program's basic blocks (tilesim-mpirun --compute\n"
          "                     blocks charges them)\n"
          "  -show, -showme, --showme\n"
          "                     print the compiler's command instead of running it\n"
          "  --showme:compile, --showme:link\n"
          "                     print the flags added to compiling, to linking\n"
          "  -compile_info, -link_info\n"
          "                     print the command that compiles, that links\n"
          "  -h, --help         this text\n",
          fl->prog, fl->lang[1] ? "CXX" : "CC", fl->lang, fl->lang[1] ? "cxx" : "cc", fl->lang, fl->ccvar, fl->ccdef);
}

enum { SHOW_NONE, SHOW_ALL, SHOW_CFLAGS, SHOW_LDFLAGS, SHOW_CINFO, SHOW_LINFO };

/* Options whose value is the next argument (not an input file). */
static int takes_value(const char *a) {
  static const char *const opts[] = {"-o", "-I", "-L", "-D", "-U", "-x", "-MF", "-MT", "-MQ", "-include", "-imacros",
                                     "-isystem", "-idirafter", "-iquote", "-iprefix", "-Xlinker", "-Xpreprocessor",
                                     "-Xassembler", "-l", "-T", "-u", "-e", "-aux-info", "--param", "-z"};
  for (size_t i = 0; i < sizeof opts / sizeof *opts; i++)
    if (strcmp(a, opts[i]) == 0) return 1;
  return 0;
}

int wrapper_main(int argc, char **argv, wrap_lang lang) {
  const flavour *fl = &flavours[lang == WRAP_CXX];
  if (argc == 1) {
    usage(stderr, fl);
    return 2;
  }
  const char *running = getenv(DEPTH_VAR);
  if (running && *running) {
    fprintf(stderr, "%s: run by the compiler that %s runs ($%s=%s): %s must name a %s compiler, not a tilesim "
            "wrapper\n", fl->prog, running, fl->ccvar, getenv(fl->ccvar) ? getenv(fl->ccvar) : "", fl->ccvar, fl->lang);
    return 2;
  }
  int compile_only = 0, shared = 0, count_blocks = 0, show = SHOW_NONE, any_input = 0, is_static = 0;
  const char *out = "a.out";
  vec user = {NULL, 0, 0};
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "--help") == 0 || (strcmp(a, "-h") == 0 && argc == 2)) {
      usage(stdout, fl);
      drop(&user);
      return 0;
    }
    if (strcmp(a, "--count-blocks") == 0) count_blocks = 1;
    else if (strcmp(a, "-show") == 0 || strcmp(a, "-showme") == 0 || strcmp(a, "--showme") == 0) show = SHOW_ALL;
    else if (strcmp(a, "-showme:compile") == 0 || strcmp(a, "--showme:compile") == 0) show = SHOW_CFLAGS;
    else if (strcmp(a, "-showme:link") == 0 || strcmp(a, "--showme:link") == 0) show = SHOW_LDFLAGS;
    else if (strcmp(a, "-compile_info") == 0 || strcmp(a, "-compile-info") == 0) show = SHOW_CINFO;
    else if (strcmp(a, "-link_info") == 0 || strcmp(a, "-link-info") == 0) show = SHOW_LINFO;
    else {
      push(&user, a);
      if (strcmp(a, "-c") == 0 || strcmp(a, "-S") == 0 || strcmp(a, "-E") == 0 || strcmp(a, "-M") == 0 ||
          strcmp(a, "-MM") == 0)
        compile_only = 1;
      else if (strcmp(a, "-shared") == 0) shared = 1;
      else if (strcmp(a, "-static") == 0 || strcmp(a, "-static-pie") == 0) is_static = 1;
      else if (strcmp(a, "-o") == 0 && i + 1 < argc) push(&user, out = argv[++i]);
      else if (takes_value(a) && i + 1 < argc) push(&user, argv[++i]);
      else if (a[0] != '-' || strcmp(a, "-") == 0) any_input = 1;
    }
  }
  if (is_static && !compile_only && !shared && any_input) {
    fprintf(stderr, "%s: -static: tilesim-mpirun loads the program itself, which must be linked dynamically (drop "
            "-static)\n", fl->prog);
    drop(&user);
    return 2;
  }
  const char *ccenv = getenv(fl->ccvar);
  vec cc = {NULL, 0, 0}, cflags = {NULL, 0, 0}, ldflags = {NULL, 0, 0};
  push_words(&cc, ccenv && *ccenv ? ccenv : fl->ccdef);
  if (cc.n == 0) push(&cc, fl->ccdef);
  if (is_wrapper(cc.v[0])) {
    fprintf(stderr, "%s: $%s names %s, a tilesim wrapper: it must name a %s compiler (it would run itself without "
            "end)\n", fl->prog, fl->ccvar, cc.v[0], fl->lang);
    drop(&cc);
    drop(&user);
    return 2;
  }
  char *inc = find_dir("TILESIM_MPI_INCLUDE", "include/tilesim/mpi", "mpi.h");
  char *lib = find_dir("TILESIM_MPI_LIB", "lib/tilesim", ELF_TILESIM_LIB);
  int status = 0;
  if (!inc || !lib) {
    fprintf(stderr, "%s: cannot find tilesim's %s next to this program (set %s)\n", fl->prog,
            !inc ? "mpi.h" : ELF_TILESIM_LIB, !inc ? "TILESIM_MPI_INCLUDE" : "TILESIM_MPI_LIB");
    status = 2;
    goto out;
  }
  char buf[PATH_MAX + 64];
  snprintf(buf, sizeof buf, "-I%s", inc);
  push(&cflags, buf);
  if (count_blocks) push(&cflags, "-fsanitize-coverage=trace-pc");
  push(&cflags, "-fPIC");
  push(&cflags, "-ffunction-sections");
  push(&cflags, "-fdata-sections");
  push(&ldflags, "-shared");
  push(&ldflags, "-Wl,-Bsymbolic");
  push(&ldflags, "-Wl,-z,defs");
  push(&ldflags, "-Wl,--exclude-libs,ALL");
  push(&ldflags, "-Wl,--gc-sections");
  push(&ldflags, "-Wl,-z,max-page-size=" GAP);
  push(&ldflags, "-Wl,-z,noseparate-code");
  push(&ldflags, "-Wl,-z,norelro");
  push(&ldflags, "-Wl,--push-state,--no-as-needed");   /* needed even by a program that calls no MPI */
  snprintf(buf, sizeof buf, "%s/%s", lib, ELF_TILESIM_LIB);
  push(&ldflags, buf);
  push(&ldflags, "-Wl,--pop-state");
  snprintf(buf, sizeof buf, "-Wl,-rpath,%s", lib);
  push(&ldflags, buf);
  int linking = !compile_only && !shared && any_input;
  vec cmd = {NULL, 0, 0};
  if (show == SHOW_CFLAGS || show == SHOW_LDFLAGS) {
    print(stdout, show == SHOW_CFLAGS ? &cflags : &ldflags);
    goto out;
  }
  push_all(&cmd, &cc);
  if (show == SHOW_CINFO || show == SHOW_LINFO) {
    push_all(&cmd, show == SHOW_CINFO ? &cflags : &ldflags);
    print(stdout, &cmd);
    drop(&cmd);
    goto out;
  }
  /* The include folder first (the program's own -I after it, as mpicc
   * does), then the program's arguments, then what tilesim needs. */
  push(&cmd, cflags.v[0]);
  push_all(&cmd, &user);
  if (any_input || show)
    for (int i = 1; i < cflags.n; i++) push(&cmd, cflags.v[i]);
  int interp = -1;
  if (linking && !show && (interp = interp_source()) >= 0) {
    snprintf(buf, sizeof buf, "/proc/self/fd/%d", interp);
    push(&cmd, "-x");
    push(&cmd, "assembler");
    push(&cmd, buf);
    push(&cmd, "-x");
    push(&cmd, "none");
    push(&cmd, "-Wl,-u,tilesim_interp");
  }
  if (linking || (show && !compile_only && !shared)) push_all(&cmd, &ldflags);
  if (show) print(stdout, &cmd);
  else status = run(&cmd, fl);
  if (interp >= 0) close(interp);
  drop(&cmd);
  if (status == 0 && linking && !show) status = check_linked(out, fl);
out:
  drop(&cc);
  drop(&cflags);
  drop(&ldflags);
  drop(&user);
  free(inc);
  free(lib);
  return status;
}
