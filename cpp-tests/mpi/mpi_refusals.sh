#!/bin/sh
# loopsurf-mpi refuses bad arguments and input on 2 ranks with exit status
# 2 and one line naming the problem (mpirun adds its own banner); --help
# prints the usage once, on stdout, and exits 0.
# Usage: mpi_refusals.sh MPIEXEC LOOPSURF_MPI MESH
mpiexec=$1 program=$2 mesh=$3
status=0
refused() {
    expect=$1
    shift
    "$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$program" "$@" >out.txt 2>err.txt
    code=$?
    lines=$(grep -c "loopsurf-mpi:" err.txt)
    if [ "$code" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -q "loopsurf-mpi: error: .*$expect" err.txt; then
        echo "FAILED: $* (exit $code, $lines lines, expected one line with '$expect'):"
        cat err.txt
        status=1
    else
        echo "refused: $* -> $(grep "loopsurf-mpi:" err.txt)"
    fi
}
refused "unknown option --bogus" "$mesh" --bogus -o x.pvtu
refused "no such file\|No such file\|missing.off" missing.off -o x.pvtu
refused "the output is a .pvtu .* or a .msh" "$mesh" -o x.vtu
refused "--parts 0: must be at least 1" "$mesh" --parts 0 -o x.pvtu
refused "size" "$mesh" --size -1 -o x.pvtu
refused "not a number" "$mesh" --size abc -o x.pvtu
refused "no output given" "$mesh"
"$mpiexec" --allow-run-as-root --oversubscribe -np 2 "$program" --help >out.txt 2>err.txt
code=$?
if [ "$code" -ne 0 ] || [ "$(grep -c "^usage: mpirun -np N loopsurf-mpi MESH" out.txt)" -ne 1 ] ||
    ! grep -q -- "--parts K" out.txt || grep -q "loopsurf-mpi: error" err.txt; then
    echo "FAILED: --help (exit $code):"
    cat out.txt err.txt
    status=1
else
    echo "help: $(head -1 out.txt)"
fi
exit $status
