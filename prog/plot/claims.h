/* claims.h -- build/plot claims: a claims map (bench --claims-map) as an
 * SVG grid of held, failed and n/a cells. */
#ifndef PLOT_CLAIMS_H
#define PLOT_CLAIMS_H

/* The whole command line (argv[1] is "claims"); the exit status. */
int plot_claims(int argc, char **argv);

#endif
