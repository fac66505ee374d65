/* ss_testlink.h — links for the tests. */
#ifndef SS_TESTLINK_H
#define SS_TESTLINK_H

#include "ss_link.h"

/* A relabelled copy of l: vertices permuted by a shuffle seeded with seed,
 * each neighbour list turned by a random offset, and (if mirror) every list
 * reversed.  NULL (with a message on stderr) if the copy is invalid. */
ss_link *ss_testlink_scrambled(const ss_link *l, unsigned seed, int mirror);

#endif
