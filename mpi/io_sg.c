/* io_sg.c -- SimGrid's file-system calls on the machine's file systems (io_sg.h). */
#include "mpi/io_sg.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "mpi/io.h"
#include "mp/mp.h"

struct io_sg_file {
  char path[IO_PATH_MAX];   /* as the program named it */
  char host[IO_PATH_MAX];
  io_fs *fs;
};

io_sg_file *sg_file_open(const char *fullpath, void *data) {
  char why[160];
  (void)data;
  io_sg_file *f = calloc(1, sizeof *f);
  if (!f || !fullpath || !(f->fs = io_fs_of(fullpath, f->host, why, sizeof why))) {
    fprintf(stderr, "tilesim: sg_file_open(%.200s): %s\n", fullpath ? fullpath : "NULL",
            !f ? "out of memory" : !fullpath ? "no path" : why);
    free(f);
    return NULL;
  }
  snprintf(f->path, sizeof f->path, "%s", fullpath);
  return f;
}

void sg_file_close(io_sg_file *fd) { free(fd); }

void sg_file_unlink(io_sg_file *fd) {
  if (!fd) return;
  unlink(fd->host);
  mp *self = mp_self();
  if (self) io_until(io_fs_request(fd->fs, mp_time(self), 0));
  free(fd);
}

const char *sg_file_get_name(const io_sg_file *fd) { return fd ? fd->path : NULL; }

unsigned long long sg_file_get_size(const io_sg_file *fd) {
  struct stat st;
  return fd && stat(fd->host, &st) == 0 ? (unsigned long long)st.st_size : 0;
}
