/* ss_cli_sweep.c — `subspectra sweep` (analyse many cases into a results
 * store, resumably, in threads or as one MPI job): the command's entry,
 * which runs the threaded sweep or hands over to the MPI driver.
 *
 * The sweep's files, each above the ones after it:
 *  - ss_cli_sweep.c (this file): the choice between the two drivers;
 *  - ss_cli_sweep_mpi.c: the MPI driver (built only with MPI);
 *  - ss_cli_sweep_run.c: the sweep's life and the steps of a case, and the
 *    threaded flush;
 *  - ss_cli_sweep_opts.c: the usage text and the options, parsed once.
 * ss_cli_sweep.h is their interface.  `subspectra merge`, which joins the
 * stores of a sweep's parts, is ss_cli_merge.c. */
#include <stdlib.h>
#include <string.h>

#include "ss_cli.h"
#include "ss_cli_sweep.h"

int ss_cli_sweep(int argc, char **argv) {
#if SS_HAVE_MPI
  /* under mpirun or srun: MPI (ss_cli_sweep_mpi.c); otherwise MPI is never
   * initialised, so a plain run is the threaded sweep, unchanged */
  if (ss_sweep_mpi_launched()) return ss_sweep_mpi(argc, argv);
#else
  /* mpirun of a build without MPI would run R copies of the same sweep */
  const char *ranks = getenv("OMPI_COMM_WORLD_SIZE");
  if (ranks && strcmp(ranks, "1"))
    return ss_cli_usage_error("sweep",
                              "started by mpirun with %s ranks, but this build has no "
                              "MPI (meson option mpi): run one process, or use --part "
                              "and merge",
                              ranks);
#endif
  ss_sweep *w = NULL;
  int rc = ss_sweep_open(argc, argv, SS_SWEEP_WHOLE, &w);
  if (rc < 0) {
    ss_sweep_run(w);
    rc = ss_sweep_close(w);
  }
  ss_sweep_raise();
  return rc;
}
