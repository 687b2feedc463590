#!/bin/bash
# tumble sweep end to end through the real command line and GNU parallel:
# bad specs are refused before anything runs, a 16-run sweep runs with every
# outcome (passed, expectation failed, script error), a second run resumes
# (finished runs are skipped, removed ones run again with the same state
# hashes), and collect writes the CSV, the summary and its plots.
#   check_sweep_local.sh BIN_DIR SOURCE_DIR OUT_DIR
set -u
bin=$1 src=$2 out=$3
rm -rf "$out" && mkdir -p "$out" && cd "$out" || exit 1
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
expect_in() {  # expect_in TEXT FILE WHAT
  grep -qF -- "$1" "$2" || { fail "$3: '$1' not in $2:"; cat "$2"; }
}
spec() {  # spec NAME GRID [EXTRA]
  cat >"$1.json" <<JSON
{"name": "$1", "scenarios": ["sweeptest:drop"], "mods": ["$src/mods"], "grid": $2,
 "seeds": [1, 2], "integrators": ["symplectic_euler", "rk4"]${3:-}}
JSON
}

# ---- bad input: a clear message, exit 1, no folder written
spec unknown '{"heigth": [1, 2]}'
"$bin/tumble" sweep unknown.json >unknown.txt 2>&1 && fail "an unknown parameter was accepted"
expect_in "sweeptest:drop has no parameter 'heigth' (its parameters: explode, height;" unknown.txt "unknown parameter"
[ -e sweep-unknown ] && fail "a folder was written for a refused spec"
spec empty '{"height": []}'
"$bin/tumble" sweep empty.json >empty.txt 2>&1 && fail "an empty grid was accepted"
expect_in "field 'grid.height' is an empty list" empty.txt "empty grid"
spec large '{"height": [1, 2, 3, 4, 5, 6]}' ', "dt": [0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1], "substeps": [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42]'
"$bin/tumble" sweep large.json >large.txt 2>&1 && fail "a sweep over the limit ran without --force"
expect_in "the sweep has 10080 jobs, more than 10000; check the grid, or pass --force" large.txt "too large"
[ -e sweep-large ] && fail "a folder was written for a too large sweep"

# ---- a sweep with every outcome, run through GNU parallel
spec drops '{"height": [1, 6], "explode": [false, true]}'
"$bin/tumble" sweep drops.json --run -j 2 >run1.txt 2>&1
status=$?
[ $status = 2 ] || fail "a sweep with failed expectations exits 2, got $status"
expect_in "16 jobs: 4 passed, 4 failed an expectation, 8 had a script error, 0 failed to run, 0 not run" run1.txt "first run"
[ "$(wc -l <sweep-drops/jobs.txt)" = 16 ] || fail "jobs.txt has one line per job"
expect_in "tumble run sweeptest:drop --seed 1 --integrator symplectic_euler --set explode=false --set height=1 --mods $src/mods --report runs/0000" sweep-drops/jobs.txt "job line"
expect_in "#SBATCH --array=0-" sweep-drops/slurm.sh "slurm script"
expect_in "completionMode: Indexed" sweep-drops/k8s-job.yaml "kubernetes manifest"
runs() { cat sweep-drops/runs/*/log.txt | grep -c "^== .*tumble run sweeptest"; }
[ "$(runs)" = 16 ] || fail "the runs' logs record the 16 runs"
[ -s sweep-drops/joblog.txt ] || fail "GNU parallel's joblog was written"
[ "$(ls sweep-drops/runs/*/time | wc -l)" = 16 ] || fail "each run's start and end times are kept"
grep -q "asked to fail with explode = true" sweep-drops/runs/000008/log.txt || fail "a script error's log is kept"

# ---- resume: nothing to do; then two removed reports run again, same hashes
"$bin/tumble" sweep run sweep-drops >run2.txt 2>&1
expect_in "all 16 jobs finished already (nothing to run)" run2.txt "resume"
[ "$(runs)" = 16 ] || fail "a resumed sweep with nothing to do runs nothing"
h0=$(grep -o '"state_hash": "[0-9a-f]*"' sweep-drops/runs/000000/report.json)
h9=$(grep -o '"state_hash": "[0-9a-f]*"' sweep-drops/runs/000009/report.json)
rm sweep-drops/runs/000000/report.json sweep-drops/runs/000009/report.json
"$bin/tumble" sweep drops.json --run >run3.txt 2>&1   # the same spec again: the same folder, resumed
expect_in "2 of 16 jobs to run (14 finished before are skipped)" run3.txt "partial resume"
[ "$(runs)" = 18 ] || fail "the logs gain the two runs"
[ "$h0" = "$(grep -o '"state_hash": "[0-9a-f]*"' sweep-drops/runs/000000/report.json)" ] || fail "job 0's state differs on a rerun"
[ "$h9" = "$(grep -o '"state_hash": "[0-9a-f]*"' sweep-drops/runs/000009/report.json)" ] || fail "job 9's state differs on a rerun"

# ---- --timeout stops a run that takes longer; its reason says so, and a
# later run without it finishes the job (resume)
spec slow '{"height": [1]}'
"$bin/tumble" sweep slow.json --out sweep-slow >/dev/null 2>&1
"$bin/tumble" sweep run sweep-slow --timeout nan >nan.txt 2>&1 && fail "--timeout nan was accepted"
expect_in "expected a finite number, got nan" nan.txt "--timeout nan"
"$bin/tumble" sweep run sweep-slow --timeout 0.001 >slow1.txt 2>&1
[ $? = 1 ] || fail "a sweep whose runs timed out exits 1"
expect_in "0 passed, 0 failed an expectation, 0 had a script error, 4 failed to run" slow1.txt "timed-out runs"
expect_in "stopped by the sweep: ran longer than --timeout 0.001 s" sweep-slow/runs/000000/log.txt "timeout in the log"
"$bin/tumble" sweep collect sweep-slow --no-plots >/dev/null 2>&1
expect_in "exit 124 without a report: stopped by the sweep: ran longer than --timeout 0.001 s" sweep-slow/results.csv "timeout reason"
"$bin/tumble" sweep run sweep-slow >slow2.txt 2>&1 || fail "the timed-out runs did not finish on a second run"
expect_in "4 of 4 jobs to run" slow2.txt "timed-out runs run again"

# ---- collect
"$bin/tumble" sweep collect sweep-drops >collect.txt 2>&1 || fail "collect failed: $(cat collect.txt)"
csv=sweep-drops/results.csv
[ "$(wc -l <$csv)" = 17 ] || fail "results.csv has a header and 16 rows"
expect_in "id,scenario,explode,height,seed,integrator,status,exit,reason,state_hash,wall_seconds.total" $csv "csv header"
[ "$(grep -c ',passed,0,,' $csv)" = 4 ] || fail "4 passed rows"
[ "$(grep -c 'expectation failed: lands within 1 s' $csv)" = 4 ] || fail "4 rows with the failed expectation named"
[ "$(grep -c 'script error: scenarios/drop.lua:13: ' $csv)" = 8 ] || fail "8 rows with the script error's file and line"
md=sweep-drops/summary.md
for text in "## Pass rate per scenario" "| sweeptest:drop | 4 | 16 | 25.0% |" "plots/error_energy_rel_drift_max__height.png" \
            "plots/wall_seconds_total__integrator.png" "Pareto front" "## Runs that did not pass" "asked to fail with explode = true"; do
  expect_in "$text" $md "summary"
done
for png in pass_rate error_vs_time error_energy_rel_drift_max__height wall_seconds_total__seed; do
  [ -s sweep-drops/plots/$png.png ] || fail "plot $png.png was not drawn"
done
[ $fails = 0 ] && echo "sweep.local: all checks passed"
exit $((fails > 0))
