#!/usr/bin/env bash
# A stand-in for `sbatch`: run the Snakemake job script (the last argument) in the background,
# log the submission, print a job id. Used by workflow/profiles/cluster-local.
set -euo pipefail
jobscript="${!#}"
dir=".snakemake/cluster-local"
mkdir -p "$dir"
id="local-$(date +%s%N)-$$"
printf '%s %s\n' "$id" "$jobscript" >> "$dir/submissions.txt"
nohup bash "$jobscript" > "$dir/$id.out" 2> "$dir/$id.err" < /dev/null &
echo "$id"
