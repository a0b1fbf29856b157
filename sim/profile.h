/* profile.h -- the simulator's configurations: the machine profiles and
 * the network models' names (sim.h declares them: sim_config_init,
 * sim_profile, sim_net_name, sim_net_parse; this is the one place for the
 * machine's default costs), and the check of a configuration that
 * sim_new makes. */
#ifndef PROFILE_H
#define PROFILE_H

#include <stddef.h>

#include "sim/sim.h"

/* cfg for nranks ranks (checked for nranks >= 1 already): 0, its topology
 * made (*tp, NULL without one) and the machine's processors (*procs: cfg's,
 * or the topology's); or -1 and why in err (a cost negative or not finite,
 * a processor model refused, an unknown network, a topology that cannot be
 * made, a place outside the processors). */
int sim_config_check(const sim_config *cfg, int nranks, topo **tp, int *procs, char *err, size_t errlen);

#endif
