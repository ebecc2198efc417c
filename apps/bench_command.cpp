#include "apps/bench_command.hpp"

#include <fmt/format.h>
#include <oneapi/tbb/info.h>

#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <regex>

#include "apps/cli_support.hpp"
#include "apps/progress.hpp"
#include "bench/blob_bench.hpp"

namespace neopipe::apps {
namespace {

cv::Size parse_size(const std::string& s) {
  static const std::regex kSize(R"((\d{1,5})x(\d{1,5}))");
  std::smatch m;
  if (!std::regex_match(s, m, kSize)) throw UsageError{"--size " + s + ": expected WxH, e.g. 640x480"};
  const cv::Size size(std::stoi(m[1]), std::stoi(m[2]));
  if (size.width < 16 || size.height < 16) throw UsageError{"--size " + s + ": at least 16x16"};
  return size;
}

}  // namespace

CLI::App* add_bench_command(CLI::App& parent, BenchArgs& a) {
  CLI::App* cmd = parent.add_subcommand(
      "bench", "Measure the built-in blob graph against OpenCV and a memory-read floor on generated frames");
  cmd->footer(
      "Cases: dots (about 100 small bright disks on a dark noisy background) and dense (smoothed noise\n"
      "thresholded at its mean: many large irregular components). neopipe runs its built-in blob graph\n"
      "with a fixed threshold; opencv is cv::threshold + cv::connectedComponentsWithStats; floor is one\n"
      "pass summing every pixel. All three run in the same process, interleaved, on the same frames.");
  cmd->add_option("--size", a.sizes, "Frame size(s) (default: 256x256 640x480 1920x1080)")->type_name("WxH");
  cmd->add_option("--threads", a.threads, "Thread count (default: 1 and all hardware threads)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--case", a.cases, "Case(s) to run (default: dots dense)")->check(CLI::IsMember({"dots", "dense"}));
  cmd->add_flag("--json", a.json, "Print a JSON array of records instead of the table");
  cmd->add_option("--min-time", a.min_seconds, "Seconds each timed run lasts at least")->check(CLI::Range(0.01, 60.0));
  cmd->add_option("--repeats", a.repeats, "Timed runs per measurement; the median is reported")
      ->check(CLI::Range(1, 100));
  return cmd;
}

int bench_command(const BenchArgs& a) {
  std::vector<cv::Size> sizes;
  for (const auto& s : a.sizes) sizes.push_back(parse_size(s));
  if (sizes.empty()) sizes = {{256, 256}, {640, 480}, {1920, 1080}};
  const int all = tbb::info::default_concurrency();
  std::vector<int> threads = a.threads > 0 ? std::vector<int>{a.threads} : std::vector<int>{1, all};
  if (threads.size() == 2 && threads[0] == threads[1]) threads.pop_back();
  const std::vector<std::string> cases = a.cases.empty() ? std::vector<std::string>{"dots", "dense"} : a.cases;

  std::vector<bench::BenchCase> plan;
  for (const auto& c : cases) {
    for (const auto& s : sizes) {
      for (const int t : threads) plan.push_back({c, s, t});
    }
  }
  for (const auto& c : cases) {
    const std::string mismatch = bench::cross_check({c, sizes.front(), 1});
    if (!mismatch.empty()) {
      print_error("bench", "results disagree, so timing them means nothing: " + mismatch);
      return kExitFailure;
    }
  }

  bench::BenchOptions o;
  o.min_seconds = a.min_seconds;
  o.repeats = a.repeats;
  nlohmann::json records = nlohmann::json::array();
  if (!a.json) {
    fmt::print("neopipe bench: median of {} run(s) of >= {:.2f} s each; {} hardware threads; OpenCV {}\n", o.repeats,
               o.min_seconds, all, CV_VERSION);
    fmt::print("{:<6} {:>10} {:>7} {:>13} {:>13} {:>13} {:>10} {:>10}\n", "case", "size", "threads", "neopipe f/s",
               "opencv f/s", "floor f/s", "vs opencv", "floor/np");
    std::fflush(stdout);
  }
  ProgressBar bar("neopipe bench", static_cast<std::int64_t>(plan.size()), a.json);
  for (size_t i = 0; i < plan.size(); ++i) {
    bar.update(static_cast<std::int64_t>(i), plan[i].name);
    const auto recs = bench::run_blob_bench(plan[i], o);
    std::map<std::string, double> fps;
    for (const auto& r : recs) {
      fps[r.impl] = r.fps;
      records.push_back({{"case", r.case_name},
                         {"impl", r.impl},
                         {"width", r.width},
                         {"height", r.height},
                         {"threads", r.threads},
                         {"fps", r.fps},
                         {"mpix_s", r.mpix_s}});
    }
    if (!a.json) {
      bar.clear();
      fmt::print("{:<6} {:>10} {:>7} {:>13.1f} {:>13.1f} {:>13.1f} {:>9.2f}x {:>9.2f}x\n", plan[i].name,
                 fmt::format("{}x{}", plan[i].size.width, plan[i].size.height), plan[i].threads, fps["neopipe"],
                 fps["opencv"], fps["floor"], fps["neopipe"] / fps["opencv"], fps["floor"] / fps["neopipe"]);
      std::fflush(stdout);
    }
  }
  bar.clear();
  if (a.json) std::cout << records.dump(2) << '\n';
  return kExitOk;
}

}  // namespace neopipe::apps
