#!/usr/bin/env bash
# Scale-out benchmark (issue 15): frames per second of `holoray animate` as
# one process (all cores), as one MPI rank, and as one rank per core, on the
# bench shots (120 frames, 512x512, reverse reprojection, K = 8), 3 rounds
# alternated, medians of the whole command's wall time. The do-nothing
# baselines (`holoray --help`, plain and under mpirun) are timed in the same
# rounds. Then bench/mpi_cost_model.py fits the cost model to the logs and
# writes bench/mpi_results.md. Needs ../shared beside the checkout and a
# build with MPI (scripts/setup.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=$PWD/build/holoray
logs=bench/mpi_logs
rm -rf "$logs"
mkdir -p "$logs"
# Containers run as root, which mpirun refuses unless told.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cores=$(nproc)
mpirun=(mpirun --oversubscribe --bind-to none)
rounds=${ROUNDS:-3}
shots=${SHOTS:-"bench/shots/teapot.toml bench/shots/tree.toml bench/keyframe_shots/tree_hold_cut.toml"}

# time_cmd LOG CMD...: runs CMD with its output in LOG, appends the wall time.
time_cmd() {
  local log=$1; shift
  local t0 t1
  t0=$(date +%s%N)
  "$@" > "$log" 2>&1
  t1=$(date +%s%N)
  echo "wall_ms $(( (t1 - t0) / 1000000 ))" >> "$log"
}

for round in $(seq 1 "$rounds"); do
  time_cmd "$logs/nothing_plain_$round.log" "$bin" --help
  time_cmd "$logs/nothing_mpi_${cores}_$round.log" "${mpirun[@]}" -np "$cores" "$bin" --help
  for shot in $shots; do
    name=$(basename "$shot" .toml)
    out=/tmp/holoray_mpi_bench
    args=(animate "$shot" --method reverse --keyframe-interval 8)
    rm -rf "$out"; time_cmd "$logs/${name}_process_$round.log" "$bin" "${args[@]}" -o "$out"
    rm -rf "$out"; time_cmd "$logs/${name}_ranks1_$round.log" "${mpirun[@]}" -np 1 "$bin" "${args[@]}" -o "$out"
    rm -rf "$out"; time_cmd "$logs/${name}_ranks${cores}_$round.log" "${mpirun[@]}" -np "$cores" "$bin" "${args[@]}" -o "$out" --threads 1
    echo "round $round $name done"
  done
done
# Sending a keyframe instead of tracing it twice: the receiver's wait while
# the sender renders 0.3 s (a group) without calling MPI, over shared memory
# (one node) and over TCP (between nodes), best of 3.
mpicc -O2 bench/mpi_keyframe_transfer.c -o /tmp/holoray_mpi_keyframe_transfer
"${mpirun[@]}" -np 2 /tmp/holoray_mpi_keyframe_transfer 0.3 3 > "$logs/transfer_shm_ms.txt"
"${mpirun[@]}" --mca btl self,tcp -np 2 /tmp/holoray_mpi_keyframe_transfer 0.3 3 > "$logs/transfer_tcp_ms.txt"
du -sb /tmp/holoray_mpi_bench | cut -f1 > "$logs/frame_bytes_last_shot.txt"
python3 bench/mpi_cost_model.py "$logs" "$cores" > bench/mpi_results.md
cat bench/mpi_results.md
