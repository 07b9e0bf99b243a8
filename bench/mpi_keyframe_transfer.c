/* What sending a keyframe's point image between two ranks would cost, for
 * bench/run_mpi_bench.sh (issue 15: "traced once and sent, or traced twice
 * where that measures cheaper"). Rank 0 posts a non-blocking send of a
 * 512x512 point image (36 bytes per pixel) and goes on rendering (a busy
 * loop of `busy` seconds, no MPI calls, as a rank does between two group
 * requests); rank 1 arrives a little later and receives. Prints the
 * receiver's wait in ms, the best of `rounds`. Without an asynchronous
 * progress engine, a large message over TCP moves only when the sender
 * next enters MPI; over shared memory the receiver copies it alone.
 * Usage: mpirun -np 2 mpi_keyframe_transfer [busy_s] [rounds] */
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static void busy(double s) {
  const double t0 = MPI_Wtime();
  volatile double x = 0;
  while (MPI_Wtime() - t0 < s) x += 1;
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const double busy_s = argc > 1 ? atof(argv[1]) : 0.3;
  const int rounds = argc > 2 ? atoi(argv[2]) : 3;
  const size_t n = (size_t)36 * 512 * 512;
  char* buf = malloc(n);
  for (size_t i = 0; i < n; ++i) buf[i] = (char)i;
  double best = 1e9;
  for (int r = 0; r < rounds; ++r) {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank == 0) {
      MPI_Request q;
      MPI_Isend(buf, (int)n, MPI_CHAR, 1, 0, MPI_COMM_WORLD, &q);
      busy(busy_s);
      MPI_Wait(&q, MPI_STATUS_IGNORE);
    } else {
      busy(0.05);
      const double t0 = MPI_Wtime();
      MPI_Recv(buf, (int)n, MPI_CHAR, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      const double t = MPI_Wtime() - t0;
      if (t < best) best = t;
    }
  }
  if (rank == 1) printf("%.1f\n", best * 1e3);
  free(buf);
  MPI_Finalize();
  return 0;
}
