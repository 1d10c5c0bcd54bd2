/* Ranks: pdk under MPI (docs/scaling.md).
 *
 * A build with MPI (CMake option PDK_MPI; PDK_HAVE_MPI in pdk/version.h) runs a scene on P ranks
 * under `mpiexec -n P pdk run SCENE`; the results are bitwise those of one rank. A program that
 * calls pdk_comm_init before it creates its context and pdk_comm_finalize at its end runs on the
 * ranks mpiexec gave it; without pdk_comm_init (or in a build without MPI) the library runs on one
 * rank, as before.
 */
#ifndef PDK_COMM_H
#define PDK_COMM_H

#include "pdk/export.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Starts MPI (threads funneled: only the main thread calls MPI) when a launcher (mpiexec) started
 * the process, unless MPI runs already or the build has no MPI; a process started otherwise stays
 * on one rank. Returns PDK_SUCCESS, or PDK_ERR_EXTERNAL when MPI could not start. */
PDK_EXPORT int pdk_comm_init(int *argc, char ***argv);
/* Ends MPI when pdk_comm_init started it. */
PDK_EXPORT void pdk_comm_finalize(void);
/* Stops every rank with exit code `code` (a failure on one rank that the others cannot see);
 * exit(code) on one rank. */
PDK_EXPORT void pdk_comm_abort(int code);
/* This process's rank (0 without MPI) and the number of ranks (1 without MPI). */
PDK_EXPORT int pdk_comm_rank(void);
PDK_EXPORT int pdk_comm_size(void);
/* 1 when the library was built with MPI. */
PDK_EXPORT int pdk_comm_built_with_mpi(void);

#ifdef __cplusplus
}
#endif

#endif
