#!/usr/bin/env bash
# Submits a rocking study as a Slurm job array of N shards and a merge that runs when all of
# them have succeeded. Prints the two job ids (array, merge).
#   examples/slurm/submit.sh N STUDY_DIR spectrum SCENE [--axis ...] [--set ...]
#   examples/slurm/submit.sh N STUDY_DIR batch SCENE --records DIR --scales 0.5,1,2
# Run it from the directory the scene path is relative to: the merge runs there too.
set -euo pipefail
if [ $# -lt 4 ]; then
    sed -n '2,6p' "$0" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
n=$1
study=$2
shift 2
array=$(sbatch --parsable --array="0-$((n - 1))" "$here/shard.sbatch" "$study" "$@")
array=${array%%;*}
merge=$(sbatch --parsable --dependency="afterok:$array" "$here/merge.sbatch" "$study" "$n")
echo "$array ${merge%%;*}"
