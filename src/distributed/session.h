// The process's place in a distributed render (docs/distributed.md): rank and rank count under mpirun or srun,
// rank 0 of 1 otherwise. Built without MPI (TORTE_HAVE_MPI undefined) every process is rank 0 of 1.
#pragma once
#include <string>

namespace torte::dist {

/// Initialises MPI when the process was started by an MPI launcher (Open MPI's or PMIx's environment
/// variables); a plain start stays out of MPI and pays nothing. Call once, first thing in main.
void init(int* argc, char*** argv);
/// This process's rank and the number of ranks (0 and 1 without a launcher).
int rank();
int ranks();
/// True when more than one process renders the images (ranks() > 1).
inline bool distributed() { return ranks() > 1; }
/// Ends MPI: a clean finalize for exit code 0 or 130, MPI_Abort for any other (the error line was printed, the
/// other ranks are stopped instead of waiting forever for this one). Returns `code` when it returns.
int finish(int code);  // (an interrupted rank, code 130, exits without MPI_Finalize)
/// Prints "torte: error: rank R: <message>" and stops every rank (MPI_Abort); for failures outside the script.
[[noreturn]] void abort_all(const std::string& message);

}  // namespace torte::dist
