#pragma once
// Slurm, through its own commands: an sbatch array script with one task per shard, submitted with
// `sbatch`, and the tasks' states from `squeue` (and `sacct` where accounting is on). neopipe keeps
// no scheduler of its own: the cluster's limits, fair share and retries stay Slurm's.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "batch/manifest.hpp"

namespace neopipe::batch {

struct SubmitOptions {
  std::string partition;             ///< empty: the cluster's default
  std::string time;                  ///< per task, Slurm's format (e.g. 2:00:00); empty: the partition's default
  std::string mem;                   ///< per task (e.g. 4G); empty: the partition's default
  std::int64_t max_parallel = 0;     ///< %K: tasks running at once; 0: no limit
  int cpus_per_task = 1;             ///< the threads of each task
  std::vector<std::int64_t> shards;  ///< the array's indices; empty: every shard
  std::string neopipe;               ///< the neopipe binary the tasks run (absolute)
};

/// Slurm's --array value: "0-3%2", or "1,3,5%2" for some shards. Ranges of consecutive shards
/// are written as A-B.
std::string array_spec(const std::vector<std::int64_t>& shards, std::int64_t max_parallel);

/// The sbatch script: one task per shard, its log in OUT/logs/, running
/// `neopipe batch run --manifest OUT/manifest.json --shard $SLURM_ARRAY_TASK_ID`.
std::string sbatch_script(const Manifest& manifest, const SubmitOptions& options);

/// Submits `script` (written to OUT/logs/ first) with `sbatch --parsable`; returns the job id and
/// records it in OUT/jobs.json. Throws BatchError when sbatch is missing, refuses the job, or does
/// not answer within a minute.
std::string submit(const Manifest& manifest, const std::string& script);

/// The job ids submitted for this output folder, oldest first.
std::vector<std::string> submitted_jobs(const Manifest& manifest);

/// The scheduler's state of each shard's latest task ("PENDING", "RUNNING", "COMPLETED", ...), from
/// squeue, then sacct for tasks no longer queued. Empty when neither answers (no Slurm here).
std::map<std::int64_t, std::string> shard_states(const std::vector<std::string>& jobs);

}  // namespace neopipe::batch
