#include "distributed/session.h"

#include <cstdio>
#include <cstdlib>

#ifdef TORTE_HAVE_MPI
#include <mpi.h>
#endif

namespace torte::dist {

namespace {
int g_rank = 0, g_ranks = 1;
bool g_mpi = false;
}  // namespace

void init(int* argc, char*** argv) {
#ifdef TORTE_HAVE_MPI
  // Open MPI's mpirun sets OMPI_COMM_WORLD_SIZE; srun and other PMIx launchers PMIX_RANK; MPICH-style PMI_RANK.
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMIX_RANK") && !std::getenv("PMI_RANK")) return;
  int provided = 0;
  // Rank 0 serves work requests on a thread of its own while the main thread renders and may fail (MPI_Abort).
  MPI_Init_thread(argc, argv, MPI_THREAD_MULTIPLE, &provided);
  if (provided < MPI_THREAD_MULTIPLE) {
    std::fprintf(stderr, "torte: error: the MPI library does not support MPI_THREAD_MULTIPLE\n");
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  g_mpi = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_ranks);
#else
  (void)argc, (void)argv;
#endif
}

int rank() { return g_rank; }
int ranks() { return g_ranks; }

int finish(int code) {
#ifdef TORTE_HAVE_MPI
  if (g_mpi) {
    if (code != 0 && code != 130 && g_ranks > 1) {
      std::fflush(stderr);
      MPI_Abort(MPI_COMM_WORLD, code);
    }
    if (code == 130) {
      // Interrupted: mpirun is killing the job and does not serve MPI_Finalize's fence until its SIGKILL
      // timeout ends. The images are written; leave without it.
      std::fflush(nullptr);
      std::_Exit(code);
    }
    MPI_Finalize();
  }
#endif
  return code;
}

void abort_all(const std::string& message) {
  std::fprintf(stderr, "torte: error: rank %d: %s\n", g_rank, message.c_str());
  std::fflush(stderr);
#ifdef TORTE_HAVE_MPI
  if (g_mpi) MPI_Abort(MPI_COMM_WORLD, 1);
#endif
  std::exit(1);
}

}  // namespace torte::dist
