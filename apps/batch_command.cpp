#include "apps/batch_command.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "batch/manifest.hpp"
#include "batch/merge.hpp"
#include "batch/shard_runner.hpp"
#include "batch/slurm.hpp"
#include "batch/stats_shards.hpp"
#include "rig/trials_shards.hpp"

namespace neopipe::apps {
namespace {

namespace fs = std::filesystem;
namespace bt = neopipe::batch;
using nlohmann::json;

bt::Manifest batch_manifest_of(const BatchArgs& a) {
  return bt::load_manifest(a.manifest);
}

int batch_plan(const BatchArgs& a) {
  bt::PlanRequest r;
  r.inputs = a.inputs;
  r.out = a.out;
  r.shards = a.shards;
  r.options.graph = a.graph;
  if (!a.graph.empty() && (!a.threshold.empty() || a.connectivity != 8)) {
    throw UsageError{"--threshold and --connectivity configure the built-in blob graph; with --graph, set them in " +
                     a.graph};
  }
  r.options.threshold = a.threshold == "otsu" ? "" : a.threshold;
  r.options.connectivity = a.connectivity;
  r.options.moments = a.moments;
  r.options.format = a.format;
  ProgressBar bar("neopipe batch plan", std::nullopt, !a.quiet);
  r.progress = [&](std::int64_t done, std::int64_t total) {
    bar.update(done, fmt::format("of {} checksummed", total));
  };
  const bt::Manifest m = bt::plan_manifest(r);
  bar.clear();
  const bool written = bt::write_manifest(m);
  std::int64_t bytes = 0;
  for (const auto& in : m.inputs) bytes += in.bytes;
  std::cout << fmt::format("{} {}: {} inputs ({:.1f} MB) in {} shards, id {}\n", written ? "planned" : "unchanged",
                           m.manifest_path().string(), m.inputs.size(), static_cast<double>(bytes) / 1e6, m.shards,
                           m.id);
  return kExitOk;
}

int batch_run(const BatchArgs& a) {
  const bt::Manifest m = batch_manifest_of(a);
  bt::check_shard_index(m, a.shard);
  const auto inputs = m.shard_inputs(a.shard);
  ProgressBar bar(fmt::format("neopipe batch run {}", a.shard), std::ssize(inputs), !a.quiet);
  std::int64_t seen = 0;
  bt::ShardRunOptions o;
  o.threads = a.threads;
  o.on_input = [&](const bt::ManifestInput& in, const bt::InputStatus& s, bool skipped) {
    bar.update(++seen);
    if (s.state == bt::InputState::failed) {
      bar.clear();
      std::cerr << fmt::format("neopipe batch run: {}: failed: {}\n", in.path, s.error);
    } else if (!a.quiet && !skipped) {
      bar.clear();
      std::cerr << fmt::format("neopipe batch run: {}: {} frames, {} blobs in {:.2f} s\n", in.path, s.frames, s.blobs,
                               s.seconds);
    }
  };
  const bt::ShardReport r = bt::run_shard(m, a.shard, o);
  bar.clear();
  std::cout << fmt::format("shard {}/{}: {} inputs: {} done now, {} done before, {} failed; {} frames in {:.2f} s\n",
                           a.shard, m.shards, r.inputs, r.done, r.skipped, r.failed, r.frames, r.seconds);
  return kExitOk;  // a failed input is recorded (batch status, merge), not the shard's failure
}

std::vector<std::int64_t> unfinished_shards(const bt::Manifest& m) {
  std::vector<std::int64_t> shards;
  for (std::int64_t s = 0; s < m.shards; ++s) {
    for (const bt::ManifestInput* in : m.shard_inputs(s)) {
      if (bt::input_status(m, *in).state != bt::InputState::done) {
        shards.push_back(s);
        break;
      }
    }
  }
  return shards;
}

int batch_submit(const BatchArgs& a) {
  const bt::Manifest m = batch_manifest_of(a);
  bt::check_output_folder(m);
  bt::SubmitOptions o;
  o.partition = a.partition;
  o.time = a.time;
  o.mem = a.mem;
  o.max_parallel = a.max_parallel;
  o.cpus_per_task = a.cpus_per_task;
  o.neopipe = fs::canonical("/proc/self/exe").string();
  if (!a.all_shards) {
    o.shards = unfinished_shards(m);
    if (o.shards.empty()) {
      std::cout << fmt::format("nothing to submit: all {} inputs are done (neopipe batch merge)\n", m.inputs.size());
      return kExitOk;
    }
  }
  const std::string script = bt::sbatch_script(m, o);
  if (a.dry_run) {
    std::cout << script;
    return kExitOk;
  }
  const std::string job = bt::submit(m, script);
  std::cout << job << '\n';
  return kExitOk;
}

int batch_status(const BatchArgs& a) {
  const bt::Manifest m = batch_manifest_of(a);
  const auto jobs = bt::submitted_jobs(m);
  const auto states = bt::shard_states(jobs);
  json shards = json::array();
  std::int64_t totals[3] = {0, 0, 0};
  if (!a.json) std::cout << fmt::format("{:>5} {:>6} {:>6} {:>7}  {}\n", "SHARD", "DONE", "FAILED", "PENDING", "SLURM");
  for (std::int64_t s = 0; s < m.shards; ++s) {
    std::int64_t n[3] = {0, 0, 0};
    for (const bt::ManifestInput* in : m.shard_inputs(s)) ++n[static_cast<int>(bt::input_status(m, *in).state)];
    const auto st = states.find(s);
    const std::string slurm = st == states.end() ? "-" : st->second;
    const std::int64_t done = n[static_cast<int>(bt::InputState::done)];
    const std::int64_t failed = n[static_cast<int>(bt::InputState::failed)];
    const std::int64_t pending = n[static_cast<int>(bt::InputState::pending)];
    totals[0] += done;
    totals[1] += failed;
    totals[2] += pending;
    shards.push_back({{"shard", s}, {"done", done}, {"failed", failed}, {"pending", pending}, {"slurm", slurm}});
    if (!a.json) std::cout << fmt::format("{:>5} {:>6} {:>6} {:>7}  {}\n", s, done, failed, pending, slurm);
  }
  if (a.json) {
    std::cout << json({{"manifest", m.id},
                       {"inputs", m.inputs.size()},
                       {"done", totals[0]},
                       {"failed", totals[1]},
                       {"pending", totals[2]},
                       {"jobs", jobs},
                       {"shards", shards}})
                     .dump()
              << '\n';
  } else {
    std::cout << fmt::format("{:>5} {:>6} {:>6} {:>7}  jobs: {}\n", "all", totals[0], totals[1], totals[2],
                             jobs.empty() ? "none submitted" : fmt::format("{}", fmt::join(jobs, ", ")));
  }
  return kExitOk;
}

int batch_merge(const BatchArgs& a) {
  const bt::Manifest m = batch_manifest_of(a);
  const bt::BatchSummary s = bt::merge_tables(m, a.out, a.partial);
  if (a.json) {
    json failures = json::array();
    for (const auto& [input, error] : s.failures) failures.push_back({{"input", input}, {"error", error}});
    std::cout << json({{"out", a.out},
                       {"inputs", s.inputs},
                       {"done", s.done},
                       {"failed", s.failed},
                       {"pending", s.pending},
                       {"frames", s.frames},
                       {"blobs", s.blobs},
                       {"seconds", s.seconds},
                       {"failures", failures}})
                     .dump()
              << '\n';
    return kExitOk;
  }
  std::cout << fmt::format("{}: {} of {} inputs ({} failed, {} pending): {} frames, {} blobs; {:.2f} s of processing\n",
                           a.out, s.done, s.inputs, s.failed, s.pending, s.frames, s.blobs, s.seconds);
  for (const auto& [input, error] : s.failures) std::cout << fmt::format("failed: {}: {}\n", input, error);
  return kExitOk;
}

std::string batch_read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read", path));
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int batch_merge_shards(const BatchArgs& a) {
  std::vector<std::string> texts;
  for (const std::string& f : a.shard_files) texts.push_back(batch_read_text(f));
  const bool nav = !texts.empty() && !texts.front().empty() && texts.front().front() == '{';
  std::string merged;
  if (nav) {
    std::vector<json> shards;
    for (std::size_t i = 0; i < texts.size(); ++i) {
      try {
        shards.push_back(json::parse(texts[i]));
      } catch (const std::exception& e) {
        throw std::runtime_error(fmt::format("{}: not JSON ({})", a.shard_files[i], e.what()));
      }
    }
    merged = rig::merge_trials_shards(shards, a.shard_files).dump() + "\n";
  } else {
    merged = bt::merge_shard_tables(texts, a.shard_files);
  }
  if (a.out.empty()) {
    std::cout << merged;
    return kExitOk;
  }
  std::ofstream out(a.out, std::ios::binary | std::ios::trunc);
  out << merged;
  out.flush();
  if (!out) throw std::runtime_error(fmt::format("--out {}: write failed", a.out));
  return kExitOk;
}

}  // namespace

CLI::App* add_batch_command(CLI::App& app, BatchArgs& a) {
  CLI::App* batch = app.add_subcommand(
      "batch",
      "Video archives on a Slurm cluster: plan a manifest, submit an array job, status, merge (docs/cluster.md)");
  batch->require_subcommand(1);
  batch->footer(
      "A typical run: neopipe batch plan videos/ --out /shared/run1 --shards 100\n"
      "               neopipe batch submit --manifest /shared/run1/manifest.json --max-parallel 50\n"
      "               neopipe batch status --manifest /shared/run1/manifest.json\n"
      "               neopipe batch merge --manifest /shared/run1/manifest.json --out all.csv");

  CLI::App* plan = batch->add_subcommand("plan", "Write the manifest: inputs sorted, checksummed, split into shards");
  plan->add_option("inputs", a.inputs, "Video files, folders of videos (searched recursively), list files (.txt)")
      ->required()
      ->type_name("INPUT...");
  plan->add_option("--out", a.out, "Output folder: the manifest, per-input tables, markers and logs")->required();
  plan->add_option("--shards", a.shards, "Number of shards (array tasks); input i goes to shard i mod N")
      ->capture_default_str()
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{1000000}));
  plan->add_option("--graph", a.graph, "Graph spec (YAML) instead of the built-in blob graph")
      ->check(CLI::ExistingFile)
      ->type_name("G.yaml");
  plan->add_option("--threshold", a.threshold, "Built-in graph: fixed threshold T, or otsu")
      ->check(CLI::Range(0, 255) | CLI::IsMember({"otsu"}))
      ->type_name("T");
  plan->add_option("--connectivity", a.connectivity, "Built-in graph: blob connectivity")
      ->check(CLI::IsMember({4, 8}))
      ->capture_default_str();
  plan->add_flag("--moments", a.moments, "Add mu20,mu11,mu02 to the tables");
  plan->add_option("--format", a.format, "Table format")->check(CLI::IsMember({"csv", "jsonl"}))->capture_default_str();
  plan->add_flag("-q,--quiet", a.quiet, "No progress bar");

  CLI::App* run =
      batch->add_subcommand("run", "Process one shard (what each array task runs); resumes past done inputs");
  run->add_option("--manifest", a.manifest, "The manifest (OUT/manifest.json)")->required();
  run->add_option("--shard", a.shard, "Shard index, 0 to N-1 (an array task: $SLURM_ARRAY_TASK_ID)")->required();
  run->add_option("--threads", a.threads, "Worker threads per input (0: all cores)")->capture_default_str();
  run->add_flag("-q,--quiet", a.quiet, "No progress bar and no per-input lines (failures are still printed)");

  CLI::App* submit = batch->add_subcommand("submit", "Write the sbatch array script and submit it with sbatch");
  submit->add_option("--manifest", a.manifest, "The manifest (OUT/manifest.json)")->required();
  submit->add_option("--partition", a.partition, "Slurm partition (default: the cluster's)");
  submit->add_option("--time", a.time, "Time limit per task (e.g. 1:00:00)");
  submit->add_option("--mem", a.mem, "Memory per task (e.g. 2G)");
  submit->add_option("--max-parallel", a.max_parallel, "Tasks running at once (--array=...%K; 0: no limit)")
      ->check(CLI::NonNegativeNumber);
  submit->add_option("--cpus-per-task", a.cpus_per_task, "CPUs (threads) per task")
      ->capture_default_str()
      ->check(CLI::Range(1, 1024));
  submit->add_flag("--all-shards", a.all_shards, "Submit every shard, not only those with inputs still to do");
  submit->add_flag("--dry-run", a.dry_run, "Print the script; submit nothing");

  CLI::App* status = batch->add_subcommand("status", "Done / failed / pending inputs per shard, with Slurm's states");
  status->add_option("--manifest", a.manifest, "The manifest (OUT/manifest.json)")->required();
  status->add_flag("--json", a.json, "One JSON object instead of the table");

  CLI::App* merge = batch->add_subcommand("merge", "One table of every done input, with an input column; a summary");
  merge->add_option("--manifest", a.manifest, "The manifest (OUT/manifest.json)")->required();
  merge->add_option("--out", a.out, "Merged table (.csv or .jsonl, as the batch's tables)")->required();
  merge->add_flag("--partial", a.partial, "Merge what is done even while inputs are pending");
  merge->add_flag("--json", a.json, "The summary as one JSON object");

  CLI::App* merge_shards = batch->add_subcommand(
      "merge-shards", "Merge the shards of `nav --trials N --shard I/K --json` or `map stats --shard I/K`");
  merge_shards->add_option("files", a.shard_files, "Every shard's output, in any order")->required();
  merge_shards->add_option("--out", a.out, "Write the merge here instead of stdout");
  return batch;
}

int batch_command(const CLI::App& batch, const BatchArgs& a) {
  const CLI::App* sub = batch.get_subcommands().front();
  const std::string name = sub->get_name();
  try {
    if (name == "plan") return batch_plan(a);
    if (name == "run") return batch_run(a);
    if (name == "submit") return batch_submit(a);
    if (name == "status") return batch_status(a);
    if (name == "merge") return batch_merge(a);
    return batch_merge_shards(a);
  } catch (const bt::BatchError& e) {
    print_error("batch " + name, e.what());
    return kExitFailure;
  }
}

}  // namespace neopipe::apps
