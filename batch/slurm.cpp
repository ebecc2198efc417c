#include "batch/slurm.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "batch/atomic_file.hpp"
#include "batch/process.hpp"

namespace neopipe::batch {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A word for the shell: single-quoted, inner quotes as '\''.
std::string shell_word(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string first_line(const std::string& text) {
  const auto start = text.find_first_not_of(" \n\r\t");
  if (start == std::string::npos) return "";
  const auto end = text.find_first_of("\n\r", start);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// Reads "123_4 STATE" (squeue -o "%i %T") or "123_4|STATE" (sacct -P) into `states` for tasks of
// `job`; an unexpanded "123_[5-7%2]" (pending) is expanded.
void read_states(const std::string& text, const std::string& job, char sep, std::map<std::int64_t, std::string>& states,
                 bool overwrite) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto at = line.find(sep);
    if (at == std::string::npos) continue;
    const std::string id = line.substr(0, at);
    std::string state = first_line(line.substr(at + 1));
    if (const auto space = state.find(' '); space != std::string::npos) state = state.substr(0, space);
    if (id.rfind(job + "_", 0) != 0) continue;
    std::string task = id.substr(job.size() + 1);
    std::vector<std::int64_t> tasks;
    if (!task.empty() && task.front() == '[') {
      task = task.substr(1, task.find_first_of("%]") - 1);
      std::istringstream parts(task);
      std::string part;
      while (std::getline(parts, part, ',')) {
        const auto dash = part.find('-');
        try {
          const std::int64_t a = std::stoll(part.substr(0, dash));
          const std::int64_t b = dash == std::string::npos ? a : std::stoll(part.substr(dash + 1));
          for (std::int64_t t = a; t <= b; ++t) tasks.push_back(t);
        } catch (const std::exception&) {
        }
      }
    } else {
      try {
        tasks.push_back(std::stoll(task));
      } catch (const std::exception&) {
      }
    }
    for (const std::int64_t t : tasks)
      if (overwrite || !states.count(t)) states[t] = state;
  }
}

}  // namespace

std::string array_spec(const std::vector<std::int64_t>& shards, std::int64_t max_parallel) {
  std::vector<std::int64_t> s = shards;
  std::sort(s.begin(), s.end());
  s.erase(std::unique(s.begin(), s.end()), s.end());
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    std::size_t j = i;
    while (j + 1 < s.size() && s[j + 1] == s[j] + 1) ++j;
    if (!out.empty()) out += ',';
    out += j == i ? fmt::format("{}", s[i]) : fmt::format("{}-{}", s[i], s[j]);
    i = j + 1;
  }
  if (max_parallel > 0) out += fmt::format("%{}", max_parallel);
  return out;
}

std::string sbatch_script(const Manifest& m, const SubmitOptions& o) {
  std::vector<std::int64_t> shards = o.shards;
  if (shards.empty()) {
    for (std::int64_t i = 0; i < m.shards; ++i) shards.push_back(i);
  }
  std::string s = "#!/bin/bash\n";
  s += fmt::format("# neopipe batch: manifest {} ({} inputs in {} shards), written by `neopipe batch submit`.\n", m.id,
                   m.inputs.size(), m.shards);
  s += "# One array task per shard; a task skips the inputs already done, so resubmitting resumes.\n";
  s += fmt::format("#SBATCH --job-name=neopipe-{}\n", m.id.substr(0, 8));
  s += fmt::format("#SBATCH --array={}\n", array_spec(shards, o.max_parallel));
  s += fmt::format("#SBATCH --output={}/logs/%A_%a.out\n", m.out);
  s += fmt::format("#SBATCH --cpus-per-task={}\n", o.cpus_per_task);
  s += "#SBATCH --ntasks=1\n";
  if (!o.partition.empty()) s += fmt::format("#SBATCH --partition={}\n", o.partition);
  if (!o.time.empty()) s += fmt::format("#SBATCH --time={}\n", o.time);
  if (!o.mem.empty()) s += fmt::format("#SBATCH --mem={}\n", o.mem);
  s += "set -eu\n";
  s += fmt::format("exec {} batch run --manifest {} --shard \"$SLURM_ARRAY_TASK_ID\" --threads {} --quiet\n",
                   shell_word(o.neopipe), shell_word(m.manifest_path().string()), o.cpus_per_task);
  return s;
}

std::vector<std::string> submitted_jobs(const Manifest& m) {
  std::ifstream in(fs::path(m.out) / "jobs.json");
  if (!in) return {};
  try {
    std::vector<std::string> jobs;
    for (const json& j : json::parse(in)) jobs.push_back(j.at("job").get<std::string>());
    return jobs;
  } catch (const std::exception&) {
    return {};
  }
}

std::string submit(const Manifest& m, const std::string& script) {
  if (!on_path("sbatch")) {
    throw BatchError(
        "sbatch: not found on PATH (submit from a Slurm login node, or use --dry-run and submit the script)");
  }
  const std::vector<std::string> jobs_before = submitted_jobs(m);
  const fs::path script_path = fs::path(m.out) / "logs" / fmt::format("submit-{}.sbatch", jobs_before.size() + 1);
  write_file_atomically(script_path, script);
  const ProcessResult r = run_process({"sbatch", "--parsable", script_path.string()}, 60);
  if (r.timed_out) throw BatchError("sbatch: no answer within 60 s (is slurmctld running?); nothing submitted");
  if (r.exit_code != 0) {
    throw BatchError(fmt::format("sbatch refused the job: {}", first_line(r.err.empty() ? r.out : r.err)));
  }
  std::string job = first_line(r.out);
  job = job.substr(0, job.find(';'));  // "123;cluster" on a federation
  if (job.empty() || job.find_first_not_of("0123456789") != std::string::npos) {
    throw BatchError(fmt::format("sbatch answered '{}', not a job id", first_line(r.out)));
  }
  json jobs = json::array();
  for (const std::string& j : jobs_before) jobs.push_back({{"job", j}});
  jobs.push_back({{"job", job}, {"script", script_path.string()}});
  write_file_atomically(fs::path(m.out) / "jobs.json", jobs.dump(2) + "\n");
  return job;
}

std::map<std::int64_t, std::string> shard_states(const std::vector<std::string>& jobs) {
  std::map<std::int64_t, std::string> states;
  // Later jobs (resubmissions) override earlier ones; squeue (live) overrides sacct (history).
  const bool have_sacct = on_path("sacct");
  const bool have_squeue = on_path("squeue");
  for (const std::string& job : jobs) {
    if (have_sacct) {
      const ProcessResult r = run_process({"sacct", "-n", "-X", "-P", "-j", job, "-o", "JobID,State"}, 20);
      if (r.exit_code == 0) read_states(r.out, job, '|', states, true);
    }
    if (have_squeue) {
      const ProcessResult r = run_process({"squeue", "-h", "-r", "-j", job, "-o", "%i %T"}, 20);
      if (r.exit_code == 0) read_states(r.out, job, ' ', states, true);
    }
  }
  return states;
}

}  // namespace neopipe::batch
