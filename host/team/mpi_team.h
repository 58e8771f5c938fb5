// mpi_team.h — the ranks of an MPI job as a team (team/team.h); built when CMake finds MPI
// (FEN_HAVE_MPI), absent otherwise.
//
// main() joins MPI only when the process was started by an MPI launcher (mpirun sets its rank in
// the environment), so a plain `fenestra render` never initialises MPI. A failure on any rank
// ends the whole job (MPI_Abort) once its one-line message is printed: no rank waits forever in a
// collective for one that is gone. The 128-bit sum is a user-defined MPI operation on pairs of
// 64-bit words, commutative, carrying from the low word into the high.
#pragma once

#include <memory>

#include "team/team.h"

namespace fen {

// True when an MPI launcher started this process (Open MPI, MPICH, PMIx, Slurm's PMI).
bool launchedByMpi();

// Joins MPI (MPI_Init) and returns the job's team; MPI_Finalize when it is destroyed.
std::unique_ptr<Team> joinMpi(int* argc, char*** argv);

// Ends every rank of the job with `code` (after this rank's message is out).
[[noreturn]] void abortMpi(int code);

}  // namespace fen
