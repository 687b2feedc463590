#!/bin/bash
# A 20-run sweep through a real single-node Slurm (munge, slurmctld and
# slurmd started here by local_slurm.sh, stopped on exit) and through GNU
# parallel: the collected results are equal, hash for hash.
#   check_sweep_slurm.sh BIN_DIR SOURCE_DIR OUT_DIR
# Exit 77 (ctest: skipped) with the reason when Slurm cannot run here.
set -u
bin=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
state="$out/slurm-state"
trap 'bash "$src/local_slurm.sh" stop "$state"' EXIT
conf=$(bash "$src/local_slurm.sh" start "$state")
rc=$?
[ $rc = 0 ] || exit $rc
export SLURM_CONF=$conf
cat >drops.json <<JSON
{"name": "drops20", "scenarios": ["sweeptest:drop"], "mods": ["$src/mods"],
 "grid": {"height": [1, 2, 4, 6, 8]}, "seeds": [1, 2], "integrators": ["symplectic_euler", "rk4"]}
JSON
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

"$bin/tumble" sweep drops.json --out by-parallel --run -j 2 >parallel.txt 2>&1
"$bin/tumble" sweep collect by-parallel >/dev/null 2>&1 || fail "collect of the parallel run"

"$bin/tumble" sweep drops.json --out by-slurm --chunk-size 4 >write.txt 2>&1 || fail "writing the Slurm sweep: $(cat write.txt)"
grep -q -- "--array=0-4" by-slurm/slurm.sh || fail "20 jobs in chunks of 4 are array tasks 0-4"
start=$(date +%s)
timeout 150 sbatch --wait "$out/by-slurm/slurm.sh" >sbatch.txt 2>&1 || { fail "sbatch --wait: $(cat sbatch.txt)"; tail -20 "$state/slurmctld.log"; }
echo "Slurm ran the array in $(( $(date +%s) - start )) s: $(cat sbatch.txt)"
[ "$(ls by-slurm/slurm/task-*.out 2>/dev/null | wc -l)" = 5 ] || fail "five array tasks left their output"
"$bin/tumble" sweep collect by-slurm >collect.txt 2>&1 || fail "collect of the Slurm run: $(cat collect.txt)"

# The same jobs, outcomes and state hashes (the timing columns differ).
key() { cut -d, -f1-9 "$1/results.csv"; }
[ "$(key by-parallel | tail -n +2 | cut -d, -f9 | grep -c '^[0-9a-f]\{16\}$')" = 20 ] || fail "20 state hashes from parallel"
if [ "$(key by-parallel)" != "$(key by-slurm)" ]; then
  fail "Slurm's results differ from GNU parallel's"
  diff <(key by-parallel) <(key by-slurm)
fi
[ $fails = 0 ] && echo "sweep.slurm: 20 runs through sbatch equal GNU parallel's, hash for hash"
exit $((fails > 0))
