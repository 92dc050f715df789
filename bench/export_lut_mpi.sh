#!/usr/bin/env bash
# Side by side in one run (docs/PERFORMANCE.md "Renderer exports"): the default 64 x 64 look-up texture at
# Delta E 0.5 as one process on 1 thread, one process on all cores, and mpirun -n 2 (one thread per rank), and
# that the 2-rank texture and spectra equal the 1-process ones byte for byte.
# Usage: bench/export_lut_mpi.sh [PROGRAM] (default build/skinspec; needs a build with MPI and mpirun)
set -euo pipefail
# Two EXR files hold the same pixels (bit for bit: idiff's thresholds 0) and the same metadata but the time of writing.
same_exr() {
  idiff -fail 0 -failpercent 0 -warn 0 "$1" "$2" > /dev/null &&
    diff <(oiiotool --info -v "$1" | grep -v -e DateTime -e "$1") <(oiiotool --info -v "$2" | grep -v -e DateTime -e "$2") > /dev/null
}
program=$(realpath "${1:-build/skinspec}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
seconds() { local s e; s=$(date +%s.%N); "$@" > /dev/null 2>&1; e=$(date +%s.%N); echo "$e - $s" | bc; }
lut=(export lut --delta-e 0.5 --overwrite)
one_thread=$(seconds "$program" "${lut[@]}" --threads 1 -o one.exr --spectra one.csv)
all_cores=$(seconds "$program" "${lut[@]}" -o all.exr)
two_ranks=$(seconds mpirun -n 2 "$program" "${lut[@]}" --threads 1 -o two.exr --spectra two.csv)
cmp one.csv two.csv && same_exr one.exr two.exr && same_exr one.exr all.exr && identical=yes || identical=NO
printf "64 x 64 LUT, Delta E 0.5: 1 process 1 thread %.2f s; 1 process %s threads %.2f s; mpirun -n 2 (1 thread each) %.2f s\n" \
  "$one_thread" "$(nproc)" "$all_cores" "$two_ranks"
printf "speed-up of 2 ranks over 1 process on 1 thread: %.2fx; outputs identical: %s\n" "$(echo "$one_thread / $two_ranks" | bc -l)" "$identical"
