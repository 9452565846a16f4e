#!/bin/sh
# loopsurf-mpi on NP ranks in 4 parts of fandisk, its pieces merged on
# their global node ids and compared with `loopsurf mesh --parts 4`'s
# mesh (reference.vtu, made by the mpi_remesh_reference test).
# Usage: mpi_remesh.sh MPIEXEC NP LOOPSURF_MPI MESH MERGE_PIECES_PY
set -e
mpiexec=$1 np=$2 program=$3 mesh=$4 merge=$5
rm -f "pieces_$np.pvtu" pieces_"$np"_*.vtu
"$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$program" "$mesh" --hard-angle 30 --parts 4 -o "pieces_$np.pvtu"
python3 "$merge" reference.vtu "pieces_$np.pvtu"
