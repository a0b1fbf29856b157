/* meshio.c -- OBJ, PLY and STL writers; temporary file, then rename(). */
#include "surface/meshio.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/atomicfile.h"

meshio_format meshio_format_of(const char *file) {
  const char *dot = strrchr(file, '.');
  static const char *ext[] = {"obj", "ply", "stl"};
  if (!dot || strchr(dot, '/')) return MESHIO_NONE;
  for (int f = 0; f < 3; f++) {
    int k = 0;
    while (k < 3 && dot[1 + k] && tolower((unsigned char)dot[1 + k]) == ext[f][k]) k++;
    if (k == 3 && dot[4] == 0) return (meshio_format)f;
  }
  return MESHIO_NONE;
}

static void obj(FILE *f, const mesh *me) {
  fprintf(f, "# tilesim: %d vertices, %d triangles\n", me->nv, me->nt);
  for (int i = 0; i < me->nv; i++)
    fprintf(f, "v %.17g %.17g %.17g\n", me->v[i].x, me->v[i].y, me->v[i].z);
  for (int i = 0; i < me->nt; i++)
    fprintf(f, "f %d %d %d\n", me->t[i][0] + 1, me->t[i][1] + 1, me->t[i][2] + 1);
}

static void ply(FILE *f, const mesh *me) {
  fprintf(f,
          "ply\nformat ascii 1.0\ncomment tilesim\nelement vertex %d\n"
          "property double x\nproperty double y\nproperty double z\n"
          "element face %d\nproperty list uchar int vertex_indices\nend_header\n",
          me->nv, me->nt);
  for (int i = 0; i < me->nv; i++)
    fprintf(f, "%.17g %.17g %.17g\n", me->v[i].x, me->v[i].y, me->v[i].z);
  for (int i = 0; i < me->nt; i++) fprintf(f, "3 %d %d %d\n", me->t[i][0], me->t[i][1], me->t[i][2]);
}

/* Little-endian, whatever the host. */
static void put32(FILE *f, uint32_t x) {
  unsigned char b[4] = {(unsigned char)x, (unsigned char)(x >> 8), (unsigned char)(x >> 16),
                        (unsigned char)(x >> 24)};
  fwrite(b, 1, 4, f);
}

static void putf(FILE *f, double v) {
  float x = (float)v;
  uint32_t u;
  memcpy(&u, &x, 4);
  put32(f, u);
}

static void stl(FILE *f, const mesh *me) {
  char head[80];
  memset(head, ' ', sizeof head);
  memcpy(head, "tilesim binary STL", 18);   /* must not begin with "solid" */
  fwrite(head, 1, sizeof head, f);
  put32(f, (uint32_t)me->nt);
  for (int i = 0; i < me->nt; i++) {
    vec3 a = me->v[me->t[i][0]], b = me->v[me->t[i][1]], c = me->v[me->t[i][2]];
    double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
    double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
    double len = sqrt(nx * nx + ny * ny + nz * nz);
    if (len > 0) nx /= len, ny /= len, nz /= len;
    putf(f, nx), putf(f, ny), putf(f, nz);
    for (int k = 0; k < 3; k++) {
      vec3 p = me->v[me->t[i][k]];
      putf(f, p.x), putf(f, p.y), putf(f, p.z);
    }
    fputc(0, f);
    fputc(0, f);
  }
}

int meshio_write(const mesh *me, const char *file, char *err, size_t errlen) {
  meshio_format fmt = meshio_format_of(file);
  if (fmt == MESHIO_NONE) {
    snprintf(err, errlen, "%s: unknown mesh format (use .obj, .ply or .stl)", file);
    return -1;
  }
  atomicfile a;
  if (atomicfile_open(&a, file, "wb", err, errlen) != 0) return -1;
  if (fmt == MESHIO_OBJ) obj(a.f, me);
  else if (fmt == MESHIO_PLY) ply(a.f, me);
  else stl(a.f, me);
  return atomicfile_close(&a, 1, err, errlen);
}
