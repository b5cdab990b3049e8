#!/bin/bash
# A gonio sweep as a Slurm job array: each task traces its shard of the work units (gonio reads
# SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT), then one dependent job merges the parts.
#   sbatch --array=0-15 scripts/slurm_array.sh configs/table_beckmann_0.5_gold.toml table
#   sbatch --dependency=afterok:<array job id> --wrap \
#       "build/gonio merge table.part-*.h5 -o table.h5"
# The surfaces are shared through the cache: put it on a filesystem every node sees, and let each
# surface be made once before the array runs (`gonio surface CONFIG`), or accept that the first
# tasks make it concurrently (entries are written whole under a temporary name and renamed).
#SBATCH --job-name=gonio
#SBATCH --cpus-per-task=8
#SBATCH --time=04:00:00
set -euo pipefail
config=$1
stem=$2
export GONIO_CACHE_DIR=${GONIO_CACHE_DIR:-$PWD/gonio-cache}
# HDF5's file locks fail on some network filesystems (NFS without lockd, Lustre without flock):
export HDF5_USE_FILE_LOCKING=${HDF5_USE_FILE_LOCKING:-FALSE}
build/gonio run "$config" -q --shard slurm --threads "${SLURM_CPUS_PER_TASK:-0}" \
    -o "$stem.part-${SLURM_ARRAY_TASK_ID}.h5"
