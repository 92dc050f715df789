#!/usr/bin/env bash
# mpirun -n 2 gives the one-process results bit for bit (cli/process_group.hpp): a look-up texture with its
# spectra (EXR: the same pixels and metadata; only the time of writing differs), and `spectrum --vary` sweeps
# of the BioSpec walk and of the volumetric walk (several replay groups); a bad request under mpirun fails
# once, cleanly. Usage: mpi_equal.sh PROGRAM MPIEXEC FOLDER
set -euo pipefail
# Two EXR files hold the same pixels (bit for bit: idiff's thresholds 0) and the same metadata but the time of writing.
same_exr() {
  idiff -fail 0 -failpercent 0 -warn 0 "$1" "$2" > /dev/null &&
    diff <(oiiotool --info -v "$1" | grep -v -e DateTime -e "$1") <(oiiotool --info -v "$2" | grep -v -e DateTime -e "$2") > /dev/null
}
program=$1 mpiexec=$2 folder=$3
mkdir -p "$folder"
cd "$folder"
# CI runs as root; OpenMPI refuses root without these. Containers often forbid the cross-memory attach OpenMPI's
# shared-memory transport uses for large messages; plain copies work everywhere.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
run2() { "$mpiexec" -n 2 --oversubscribe "$program" "$@"; }

lut=(export lut --melanin 0.01:0.42:12:log --blood 0.002:0.05:8:log --delta-e 1 --overwrite)
run2 "${lut[@]}" -o two.exr --spectra two.csv > two.txt
"$program" "${lut[@]}" -o one.exr --spectra one.csv > one.txt
grep -q "on 2 process(es)" two.txt
cmp two.csv one.csv
same_exr two.exr one.exr

sweep=(spectrum --vary epidermis.melanosome_fraction=0.01:0.4:6:log --vary dermis.blood_fraction=0.002:0.05:3 --wavelengths 400:700:50 --rays 500 --json)
run2 "${sweep[@]}" | grep -v '"seconds"' > two.json
"$program" "${sweep[@]}" | grep -v '"seconds"' > one.json
cmp two.json one.json
rte=(spectrum --mode rte --vary epidermis.thickness_cm=0.008:0.012:3 --vary epidermis.melanosome_fraction=0.02:0.1:2 --wavelengths 550 --rays 500 --json)
run2 "${rte[@]}" | grep -v '"seconds"' > two_rte.json
"$program" "${rte[@]}" | grep -v '"seconds"' > one_rte.json
cmp two_rte.json one_rte.json

status=0
run2 export lut --melanin 0.1:1.5:4 -o bad.exr > bad.txt 2>&1 || status=$?
[ "$status" -ne 0 ]
[ "$(grep -c "is outside \[0, 1\]" bad.txt)" -eq 1 ]
[ ! -e bad.exr ]
echo "mpirun -n 2: texture, spectra and sweeps equal to one process; bad input refused (exit $status)"
