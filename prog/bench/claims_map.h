/* bench_map.h -- ./bench --claims-map: the paper's seven claims judged on
 * many machines and pairs at once, one CSV row per configuration. */
#ifndef BENCH_MAP_H
#define BENCH_MAP_H

/* The whole command line (argv[1] is --claims-map); the exit status. */
int bench_map(int argc, char **argv);

#endif
