#!/usr/bin/env bash
# tumble-sweep under mpirun writes the table `tumble sweep` writes: the same bytes but for the
# wall_s column (a measurement), with 2 and with 3 ranks (oversubscribed on a small machine).
# Usage: sweep_mpi_test.sh TUMBLE TUMBLE_SWEEP MPIEXEC STUDY SCRATCH
set -euo pipefail
tumble=$1 sweep=$2 mpiexec=$3 study=$4 scratch=$5
rm -rf "$scratch" && mkdir -p "$scratch"
# CI runs as root; Open MPI refuses root unless told twice.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
"$tumble" sweep "$study" --out "$scratch/local" --jobs 2 2>/dev/null
"$mpiexec" -np 2 --oversubscribe "$sweep" "$study" --out "$scratch/np2" 2>/dev/null
"$mpiexec" -np 3 --oversubscribe "$sweep" "$study" --out "$scratch/np3" 2>/dev/null
strip() { sed 's/,[^,]*$//' "$1/results.csv"; }
rows=$(strip "$scratch/local" | wc -l)
[ "$rows" -gt 1 ] || { echo "no rows in the local table"; exit 1; }
for n in np2 np3; do
  if ! cmp <(strip "$scratch/local") <(strip "$scratch/$n"); then
    echo "tumble-sweep ($n) differs from tumble sweep:"
    diff <(strip "$scratch/local") <(strip "$scratch/$n") | head -20
    exit 1
  fi
done
echo "tumble-sweep with 2 and 3 ranks: the same $((rows - 1)) rows as tumble sweep"
