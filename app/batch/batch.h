// app/batch/batch.h: what `frontier batch` (app/batch_command.cpp) uses of app/batch/, the folder of
// the batch's parts:
//   plan.h        the plan: scenes times variations, expanded into jobs with stable ids
//   scene.h       a job's scene: the plan's scene paths set, the seeded perturbation, the inputs digest
//   jobs.h        a job's folder and files, whether its results stand, shards
//   merge.cpp     --merge: DIR/batch.csv, DIR/summary.md, DIR/chart.png
//   slurm.cpp     --slurm: DIR/slurm/batch.sbatch and merge.sbatch (words quoted by shell_quote.h)
#pragma once

#include "app/batch/jobs.h"
#include "app/batch/plan.h"
#include "app/batch/scene.h"
#include "app/commands.h"

namespace frontier::app
{

// --merge: DIR/batch.csv, DIR/summary.md, with --chart DIR/chart.png. Returns the exit code.
int mergeBatch(const BatchPlan& plan, const BatchOptions& options);
// --slurm: DIR/slurm/batch.sbatch and merge.sbatch; with --submit, sbatch both. Returns the exit code.
int slurmBatch(const BatchPlan& plan, const BatchOptions& options);

} // namespace frontier::app
