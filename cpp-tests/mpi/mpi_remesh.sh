#!/bin/sh
# loopsurf-mpi on NP ranks in 4 parts of fandisk, its pieces merged on
# their global node ids and compared with `loopsurf mesh --parts 4`'s
# mesh (reference.vtu, made by the mpi_remesh_reference test). FORMAT is
# vtu or msh (.vtu pieces merged by merge_pieces.py, .msh pieces merged
# in gmsh by merge_msh_pieces.py); any further arguments go to
# loopsurf-mpi (e.g. --binary). With --verbose, the output must also
# give every rank's peak memory after every stage and after writing.
# Usage: mpi_remesh.sh MPIEXEC NP LOOPSURF_MPI MESH SCRIPTS_DIR FORMAT [ARGS...]
set -e
mpiexec=$1 np=$2 program=$3 mesh=$4 scripts=$5 format=$6
shift 6
name="pieces_${np}_$format$(echo "$@" | tr -d ' -')"
rm -f "$name".pvtu "$name"_*.vtu "$name"_*.msh
if [ "$format" = msh ]; then
    "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$program" "$mesh" --hard-angle 30 --parts 4 "$@" -o "$name.msh"
    q=0 pieces=""
    while [ "$q" -lt "$np" ]; do pieces="$pieces ${name}_$q.msh"; q=$((q + 1)); done
    # shellcheck disable=SC2086
    python3 "$scripts/merge_msh_pieces.py" reference.vtu $pieces
else
    # Its output kept for the --verbose check below (a pipe would hide
    # loopsurf-mpi's exit status from set -e).
    "$mpiexec" --allow-run-as-root --oversubscribe -np "$np" "$program" "$mesh" --hard-angle 30 --parts 4 "$@" -o "$name.pvtu" > "$name.log" || {
        cat "$name.log"
        exit 1
    }
    cat "$name.log"
    python3 "$scripts/merge_pieces.py" reference.vtu "$name.pvtu"
fi
case " $* " in
*" --verbose "*)
    # One figure per rank after each of the five stages and after writing.
    for when in sizes "first pass" "interface band" "interface crossings" touch-up writing; do
        line=$(grep "peak RSS after $when:" "$name.log") || {
            echo "no peak RSS after $when in the --verbose output" >&2
            exit 1
        }
        figures=$(echo "${line#*:}" | tr ',' '\n' | grep -c '^ *[0-9][0-9]* *M*B*$')
        if [ "$figures" -ne "$np" ]; then
            echo "peak RSS after $when: $figures figures for $np ranks: $line" >&2
            exit 1
        fi
    done
    ;;
esac
