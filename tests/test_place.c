/* test_place.c -- placements of ranks on the topologies' processors:
 * every named placement (linear, snake, gray, random:SEED) a one-to-one map
 * onto the machine's processors, the same each time; the dilations of
 * linear and snake on meshes and tori and of linear and gray on hypercubes
 * counted by the distance formulas (topomachine.h), and the simulator's
 * hop-bytes agreeing; gray a ring of cube neighbours; a placement read from
 * a file, and its refusals (file and line, the value). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/link.h"
#include "sim/place.h"
#include "tests/check.h"
#include "tests/topomachine.h"

static void test_place_maps(void) {
  char err[256];
  static const char *const names[] = {"linear", "snake", "gray", "random:1", "random:2"};
  int bad = 0;
  for (int i = 0; i < NMACHINES; i++) {
    const machine *mc = &machines[i];
    dims x = tm_dims(mc);
    topo *t = tm_topo(mc, err, sizeof err);
    for (size_t j = 0; j < sizeof names / sizeof *names; j++) {
      place_spec ps;
      place_parse(names[j], &ps, err, sizeof err);
      int map[64], again[64];
      for (int n = 1; n <= x.N; n++) {
        if (place_map(&ps, t, n, map, err, sizeof err) != 0) {
          bad++;
          continue;
        }
        char used[64] = {0};
        for (int v = 0; v < n; v++) {
          bad += map[v] < 0 || map[v] >= x.N || used[map[v]];
          if (map[v] >= 0 && map[v] < x.N) used[map[v]] = 1;
        }
        place_map(&ps, t, n, again, err, sizeof err);
        bad += memcmp(map, again, (size_t)n * sizeof *map) != 0;
      }
      CHECK(place_map(&ps, t, x.N + 1, map, err, sizeof err) != 0, "%s on machine %d: N+1 placed",
            names[j], i);
    }
    topo_free(t);
  }
  CHECK(bad == 0, "%d placements not a deterministic injection into the machine", bad);

  /* Dilation: the algorithm's line of processors, v -> v+1 (the design
   * note's sums of links over the P-1 pairs). */
  static const struct {
    machine mc;
    const char *place;
    int sum;
  } dil[] = {
      {{TOPO_LINE, 0, 0, 9}, "linear", 8},
      {{TOPO_MESH, 5, 3, 15}, "linear", 3 * 4 + 2 * 5},   /* H(W-1) + (H-1)W */
      {{TOPO_MESH, 5, 3, 15}, "snake", 14},
      {{TOPO_TORUS, 4, 4, 16}, "snake", 15},
      {{TOPO_HYPERCUBE, 3, 0, 8}, "linear", 16 - 3 - 2},  /* 2^(d+1) - d - 2 */
      {{TOPO_HYPERCUBE, 5, 0, 32}, "linear", 64 - 5 - 2},
      {{TOPO_HYPERCUBE, 5, 0, 32}, "gray", 31},
      {{TOPO_HYPERCUBE, 4, 0, 11}, "gray", 10},
  };
  for (size_t i = 0; i < sizeof dil / sizeof *dil; i++) {
    const machine *mc = &dil[i].mc;
    dims x = tm_dims(mc);
    int P = mc->procs, map[64], sum = 0;
    place_spec ps;
    place_parse(dil[i].place, &ps, err, sizeof err);
    topo *t = tm_topo(mc, err, sizeof err);
    place_map(&ps, t, P, map, err, sizeof err);
    topo_free(t);
    for (int v = 0; v + 1 < P; v++) sum += tm_hops(mc, &x, map[v], map[v + 1]);
    CHECK(sum == dil[i].sum, "dilation case %zu (%s): %d links, expected %d", i, dil[i].place, sum,
          dil[i].sum);
    /* The simulator agrees: L-byte messages v -> v+1 make L times that in hop-bytes. */
    perm p;
    p.len = 40;
    for (int v = 0; v < P; v++) p.dst[v] = v + 1 < P ? v + 1 : -1;
    sim_config cfg = tm_netcfg(mc, 0);
    cfg.place = map;
    memset(p.expect, 0, sizeof p.expect);
    for (int v = 1; v < P; v++) p.expect[v] = 1;
    p.bad = 0;
    int rc;
    sim *s = simrun(&cfg, P, tm_perm_main, &p, &rc, err, sizeof err);
    net_stats ns;
    links_total(sim_links(s), &ns);
    CHECK(rc == 0 && ns.hop_bytes == 40LL * dil[i].sum, "dilation case %zu: hop-bytes %lld, expected %d",
          i, ns.hop_bytes, 40 * dil[i].sum);
    sim_free(s);
  }
  /* Gray on a hypercube: consecutive processors are neighbours, ring closed. */
  place_spec gray;
  place_parse("gray", &gray, err, sizeof err);
  topo_spec cube = {TOPO_HYPERCUBE, 6, 0};
  topo *t = topo_new(&cube, 64, err, sizeof err);
  int map[64];
  place_map(&gray, t, 64, map, err, sizeof err);
  int off = 0;
  for (int v = 0; v < 64; v++) off += tm_popcount((unsigned)(map[v] ^ map[(v + 1) % 64])) != 1;
  CHECK(off == 0, "gray on hypercube:6: %d of 64 ring neighbours are not cube neighbours", off);
  /* Two seeds, two permutations. */
  place_spec r1, r2;
  place_parse("random:1", &r1, err, sizeof err);
  place_parse("random:2", &r2, err, sizeof err);
  int m1[64], m2[64];
  place_map(&r1, t, 64, m1, err, sizeof err);
  place_map(&r2, t, 64, m2, err, sizeof err);
  CHECK(memcmp(m1, m2, sizeof m1) != 0, "random:1 and random:2 give the same placement");
  topo_free(t);
}

static const char *write_tmp(const char *name, const char *text) {
  static char path[4][256];
  static int k;
  char *p = path[k++ % 4];
  snprintf(p, 256, "%s/test_topo_%d_%s", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid(),
           name);
  FILE *f = fopen(p, "w");
  fputs(text, f);
  fclose(f);
  return p;
}

static void test_place_file(void) {
  char err[512], arg[400];
  topo_spec sp = {TOPO_MESH, 3, 3};
  topo *t = topo_new(&sp, 9, err, sizeof err);
  const char *good = write_tmp("good", "# rank 0 in the middle\n4\n\n0\r\n8\n2\n");
  snprintf(arg, sizeof arg, "file:%s", good);
  place_spec ps;
  CHECK(place_parse(arg, &ps, err, sizeof err) == 0, "good file: %s", err);
  int map[9];
  CHECK(place_map(&ps, t, 4, map, err, sizeof err) == 0 && map[0] == 4 && map[1] == 0 &&
            map[2] == 8 && map[3] == 2,
        "file placement: %s", err);
  CHECK(place_map(&ps, t, 5, map, err, sizeof err) != 0 && strstr(err, "4 processors listed"),
        "a file too short: %s", err);
  remove(good);
  static const struct {
    const char *text, *want;
  } bad[] = {{"0\n1\nx2\n", ":3: 'x2' is not a processor number"},
             {"0\n1\n0\n", ":3: processor 0 is placed twice (line 1 too)"},
             {"0\n-1\n", ":2: '-1' is not"},
             {"0 \n", ":1: '0 ' is not"},
             {"# nothing\n\n", "no processors listed"}};
  for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
    const char *path = write_tmp("bad", bad[i].text);
    snprintf(arg, sizeof arg, "file:%s", path);
    err[0] = 0;
    CHECK(place_parse(arg, &ps, err, sizeof err) != 0 && strstr(err, path) && strstr(err, bad[i].want),
          "bad file %zu: '%s'", i, err);
    remove(path);
  }
  const char *far = write_tmp("far", "0\n1\n9\n");
  snprintf(arg, sizeof arg, "file:%s", far);
  CHECK(place_parse(arg, &ps, err, sizeof err) == 0, "%s", err);
  CHECK(place_map(&ps, t, 3, map, err, sizeof err) != 0 && strstr(err, ":3: processor 9: the machine has 9"),
        "a processor outside the machine: %s", err);
  remove(far);
  CHECK(place_parse("file:/nonexistent/place.txt", &ps, err, sizeof err) != 0 &&
            strstr(err, "/nonexistent/place.txt"),
        "a missing file: %s", err);
  topo_free(t);
}

int main(void) {
  test_place_maps();
  test_place_file();
  return check_done("test_place");
}
